#include "viewer/mesh_files.h"

#include <filesystem>
#include <map>

#include "formats/model_loader.h"
#include "viewer/stl.h"
#include "viewer/view_frames.h"

namespace ccma::viewer {
namespace {

std::string MiB(std::size_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

// "MODEL:LINE: body 'NAME': mesh 'FILE': " for messages.
std::string Where(const Model& model, const Body& body, const BodyMesh& mesh) {
  const std::string source = model.source.empty() ? "model" : model.source;
  return source + ":" + std::to_string(mesh.line) + ": body '" + body.name + "': mesh '" + mesh.file + "': ";
}

}  // namespace

std::string ResolveMeshPath(const std::string& model_source, const std::string& file) {
  const std::filesystem::path path(file);
  if (path.is_absolute()) return file;
  return (std::filesystem::path(model_source).parent_path() / path).string();
}

MeshFiles ReadMeshFiles(const Model& model) {
  MeshFiles out;
  std::map<std::string, int> index;  // resolved path -> files[]
  for (const Body& body : model.bodies) {
    out.file_of.emplace_back();
    for (const BodyMesh& mesh : body.meshes) {
      const std::string path = ResolveMeshPath(model.source, mesh.file);
      const auto known = index.find(path);
      if (known != index.end()) {
        out.file_of.back().push_back(known->second);
        continue;
      }
      std::string bytes, error;
      if (!internal::ReadRegularFile(path, kMaxMeshFileBytes, "mesh file", &bytes, &error)) {
        throw ViewInputError(Where(model, body, mesh) + error);
      }
      out.bytes_read += bytes.size();
      if (out.bytes_read > kMaxMeshTotalBytes) {
        throw ViewInputError(Where(model, body, mesh) + "the mesh files add up to more than " +
                             MiB(kMaxMeshTotalBytes) + " (the limit for one page)");
      }
      MeshFiles::File file;
      file.path = path;
      try {
        const std::vector<StlTriangle> triangles = ReadStl(bytes);
        file.triangles = triangles.size();
        file.stl = WriteBinaryStl(triangles);
      } catch (const StlError& e) {
        throw ViewInputError(Where(model, body, mesh) + path + ": not a valid STL: " + e.what());
      }
      index.emplace(path, static_cast<int>(out.files.size()));
      out.file_of.back().push_back(static_cast<int>(out.files.size()));
      out.files.push_back(std::move(file));
    }
  }
  return out;
}

}  // namespace ccma::viewer
