#include "viewer/mesh_files.h"

#include <filesystem>
#include <map>

#include "ccma/internal/format.h"
#include "formats/model_loader.h"
#include "viewer/mesh_folders.h"
#include "viewer/stl.h"
#include "viewer/view_frames.h"

namespace ccma::viewer {
namespace {

std::string MiB(std::size_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

// "MODEL:LINE: body 'NAME': mesh 'FILE': " for messages.
std::string Where(const Model& model, const Body& body, const BodyMesh& mesh) {
  const std::string source = model.source.empty() ? "model" : model.source;
  return source + ":" + std::to_string(mesh.line) + ": body " + Quote(body.name) + ": mesh " + Quote(mesh.file) + ": ";
}

// Why a mesh outside the allowed folders is not read, and how to allow it.
std::string Outside(const MeshFolders& folders) {
  const std::string folder = folders.model_folder().empty() ? "" : " '" + folders.model_folder() + "'";
  return "outside the model file's folder" + folder + (folders.has_roots() ? " and the mesh roots" : "") +
         " (symlinks resolved): not read; to allow it, give its folder with --mesh_root=DIR (Python: mesh_root=)";
}

// ReadRegularFile's message without the path it starts with: Where() names
// the mesh as the model writes it, quoted.
std::string WithoutPath(const std::string& error, const std::string& path) {
  if (error.compare(0, path.size(), path) == 0 && error.compare(path.size(), 2, ": ") == 0) {
    return error.substr(path.size() + 2);
  }
  if (error.compare(0, path.size(), path) == 0) return error.substr(path.size());
  return error;
}

// One mesh file: confined, read within the bounds, checked as STL.
MeshFiles::File ReadOne(const Model& model, const Body& body, const BodyMesh& mesh, const std::string& path,
                        const MeshFolders& folders, std::size_t* bytes_read) {
  const std::optional<std::string> confined = folders.Confine(path);
  if (!confined) throw ViewInputError(Where(model, body, mesh) + Outside(folders));
  std::string bytes, error;
  // The canonical path, checked above: a symlink in `path` is not followed again.
  if (!internal::ReadRegularFile(*confined, kMaxMeshFileBytes, "mesh file", &bytes, &error)) {
    throw ViewInputError(Where(model, body, mesh) + WithoutPath(error, *confined));
  }
  *bytes_read += bytes.size();
  if (*bytes_read > kMaxMeshTotalBytes) {
    throw ViewInputError(Where(model, body, mesh) + "the mesh files add up to more than " +
                         MiB(kMaxMeshTotalBytes) + " (the limit for one page)");
  }
  MeshFiles::File file;
  file.path = path;
  file.page_path = PageMeshPath(mesh.file);
  try {
    const std::vector<StlTriangle> triangles = ReadStl(bytes);
    file.triangles = triangles.size();
    file.stl = WriteBinaryStl(triangles);
  } catch (const StlError& e) {
    throw ViewInputError(Where(model, body, mesh) + "not a valid STL: " + e.what());
  }
  return file;
}

}  // namespace

std::string ResolveMeshPath(const std::string& model_source, const std::string& file) {
  const std::filesystem::path path(file);
  if (path.is_absolute()) return file;
  return (std::filesystem::path(model_source).parent_path() / path).string();
}

MeshFiles ReadMeshFiles(const Model& model, const std::vector<std::string>& mesh_roots) {
  const MeshFolders folders(model.source, mesh_roots);
  MeshFiles out;
  std::map<std::string, int> index;  // resolved path -> files[]
  for (const Body& body : model.bodies) {
    out.file_of.emplace_back();
    for (const BodyMesh& mesh : body.meshes) {
      const std::string path = ResolveMeshPath(model.source, mesh.file);
      auto known = index.find(path);
      if (known == index.end()) {
        out.files.push_back(ReadOne(model, body, mesh, path, folders, &out.bytes_read));
        known = index.emplace(path, static_cast<int>(out.files.size()) - 1).first;
      }
      out.file_of.back().push_back(known->second);
    }
  }
  return out;
}

}  // namespace ccma::viewer
