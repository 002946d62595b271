#include "analyses/internal/import_mesh_paths.h"

#include <cctype>
#include <filesystem>
#include <system_error>

#include "ccma/internal/format.h"

namespace ccma {
namespace internal {
namespace {

namespace fs = std::filesystem;

// `path` absolute, its existing part with symlinks resolved.
fs::path Canonical(const fs::path& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  if (error) absolute = path;
  const fs::path canonical = fs::weakly_canonical(absolute, error);
  return error ? absolute.lexically_normal() : canonical;
}

}  // namespace

std::string MeshPathRelativeTo(const std::string& mesh, const std::string& folder) {
  const fs::path file(mesh);
  // The mesh's folder resolved, its file name kept: a mesh that is itself a
  // symlink stays one (the viewer decides where it may point).
  const fs::path resolved = Canonical(file.parent_path()) / file.filename();
  const fs::path base = Canonical(folder.empty() ? fs::path(".") : fs::path(folder));
  const fs::path relative = resolved.lexically_relative(base);
  return relative.empty() ? resolved.generic_string() : relative.generic_string();
}

std::vector<std::string> UndrawableMeshes(const std::string& source, const Model& model) {
  int missing = 0, other = 0;
  std::string first_missing, first_other;
  for (const Body& body : model.bodies) {
    for (const BodyMesh& mesh : body.meshes) {
      std::error_code error;
      if (!fs::is_regular_file(fs::path(mesh.file), error) && missing++ == 0) first_missing = mesh.file;
      std::string extension = fs::path(mesh.file).extension().string();
      for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (extension != ".stl" && other++ == 0) first_other = mesh.file;
    }
  }
  std::vector<std::string> out;
  if (missing > 0) {
    out.push_back(source + ": " + std::to_string(missing) + " mesh file(s) are not there (the first: " +
                  Quote(first_missing) + "): written into the model, but `ccma view --meshes` cannot draw them");
  }
  if (other > 0) {
    out.push_back(source + ": " + std::to_string(other) + " mesh file(s) are not STL (the first: " + Quote(first_other) +
                  "): written into the model, but `ccma view --meshes` draws STL only (convert them, e.g. with "
                  "meshlab or assimp, and change the model's mesh paths)");
  }
  return out;
}

std::string RelateMeshPaths(const std::string& folder, const std::string& source, Model* model) {
  int outside = 0;
  std::string first;
  for (Body& body : model->bodies) {
    for (BodyMesh& mesh : body.meshes) {
      mesh.file = MeshPathRelativeTo(mesh.file, folder);
      if (mesh.file.compare(0, 3, "../") == 0 && outside++ == 0) first = mesh.file;
    }
  }
  if (outside == 0) return "";
  return source + ": " + std::to_string(outside) + " mesh file(s) lie outside the model file's folder (the first: " +
         Quote(first) + "): `ccma view --meshes` reads them only with --mesh_root=DIR naming their folder";
}

}  // namespace internal
}  // namespace ccma
