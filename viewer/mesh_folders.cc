#include "viewer/mesh_folders.h"

#include <filesystem>
#include <system_error>

#include "viewer/view_frames.h"

namespace ccma::viewer {
namespace {

namespace fs = std::filesystem;

// Whether canonical `path` is `folder` or lies below it, compared by whole
// components ("/a/bc" is not inside "/a/b").
bool Inside(const fs::path& path, const fs::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
    if (f->empty()) continue;  // a trailing separator
    if (p == path.end() || *p != *f) return false;
  }
  return true;
}

// The canonical existing folder `dir`, or empty.
std::string CanonicalFolder(const fs::path& dir) {
  std::error_code error;
  const fs::path canonical = fs::canonical(dir, error);
  if (error || !fs::is_directory(canonical, error) || error) return "";
  return canonical.string();
}

}  // namespace

MeshFolders::MeshFolders(const std::string& model_source, const std::vector<std::string>& roots) {
  const fs::path parent = fs::path(model_source).parent_path();
  model_folder_ = CanonicalFolder(parent.empty() ? fs::path(".") : parent);
  if (!model_folder_.empty()) folders_.push_back(model_folder_);
  for (const std::string& root : roots) {
    const std::string folder = CanonicalFolder(root);
    if (root.empty() || folder.empty()) throw ViewInputError("mesh root '" + root + "': not an existing folder");
    folders_.push_back(folder);
    has_roots_ = true;
  }
}

std::optional<std::string> MeshFolders::Confine(const std::string& path) const {
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(fs::absolute(path, error), error);
  if (error) return std::nullopt;
  for (const std::string& folder : folders_) {
    if (Inside(canonical, folder)) return canonical.string();
  }
  return std::nullopt;
}

std::string PageMeshPath(const std::string& file) {
  const fs::path path = fs::path(file).lexically_normal();
  const bool escapes = !path.empty() && *path.begin() == "..";
  if (path.is_relative() && !escapes && !path.empty()) return path.generic_string();
  return fs::path(file).filename().generic_string();
}

}  // namespace ccma::viewer
