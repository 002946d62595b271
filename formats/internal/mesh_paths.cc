#include "formats/internal/mesh_paths.h"

#include <filesystem>
#include <string>
#include <system_error>

namespace ccma {
namespace internal {
namespace {

namespace fs = std::filesystem;

bool Exists(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error);
}

// For package://PKG/rest: rest relative to the robot folder, or PKG found
// in the robot folder or one of its ancestors.
std::string ResolvePackage(const std::string& reference, const fs::path& folder) {
  const std::size_t slash = reference.find('/');
  const std::string package = slash == std::string::npos ? reference : reference.substr(0, slash);
  const std::string rest = slash == std::string::npos ? "" : reference.substr(slash + 1);
  if (package.empty() || Exists(folder / rest)) return (folder / rest).lexically_normal().string();
  for (fs::path dir = folder; !dir.empty(); dir = dir.parent_path()) {
    if (Exists(dir / package / rest)) return (dir / package / rest).lexically_normal().string();
    if (dir.filename() == package && Exists(dir / rest)) return (dir / rest).lexically_normal().string();
    if (dir == dir.root_path()) break;
  }
  return (folder / rest).lexically_normal().string();
}

}  // namespace

std::string AbsoluteFolderOf(const std::string& file) {
  std::error_code error;
  fs::path path = fs::absolute(fs::path(file), error);
  if (error) path = fs::path(file);
  return path.parent_path().lexically_normal().string();
}

std::string ResolveMeshPath(const std::string& uri, const std::string& robot_folder) {
  const fs::path folder(robot_folder);
  for (const char* scheme : {"package://", "model://"}) {
    const std::string prefix(scheme);
    if (uri.compare(0, prefix.size(), prefix) == 0) return ResolvePackage(uri.substr(prefix.size()), folder);
  }
  const std::string file_scheme = "file://";
  if (uri.compare(0, file_scheme.size(), file_scheme) == 0) return uri.substr(file_scheme.size());
  const fs::path path(uri);
  return path.is_absolute() ? path.lexically_normal().string() : (folder / path).lexically_normal().string();
}

}  // namespace internal
}  // namespace ccma
