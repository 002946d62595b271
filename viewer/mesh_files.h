// The mesh files of a model's bodies (Body::meshes), read for
// `ccma view --meshes`: each distinct file once, bounded in size, checked as
// STL and kept as canonical binary STL (viewer/stl.h) for the page.
#ifndef CCMA_VIEWER_MESH_FILES_H_
#define CCMA_VIEWER_MESH_FILES_H_

#include <cstddef>
#include <string>
#include <vector>

#include "ccma/model.h"

namespace ccma::viewer {

// At most 16 MiB per mesh file and 64 MiB for all the distinct files of a
// page (the page carries them base64-encoded, 4/3 of their binary size).
constexpr std::size_t kMaxMeshFileBytes = std::size_t{16} << 20;
constexpr std::size_t kMaxMeshTotalBytes = std::size_t{64} << 20;

struct MeshFiles {
  struct File {
    std::string path;       // as resolved: absolute, or relative to the working directory
    std::string page_path;  // what the page records (PageMeshPath, viewer/mesh_folders.h): never absolute
    std::string stl;   // canonical binary STL (WriteBinaryStl)
    std::size_t triangles = 0;
  };
  std::vector<File> files;  // distinct resolved paths, in order of first use
  // Per body, per entry of Body::meshes: the index into `files`.
  std::vector<std::vector<int>> file_of;
  std::size_t bytes_read = 0;  // the files' sizes on disk, summed
};

// The path a mesh's `file` names: itself when absolute, else relative to the
// folder of `model_source` (Model::source; the working directory when empty).
std::string ResolveMeshPath(const std::string& model_source, const std::string& file);

// Reads every body's meshes, each only from inside the model file's folder
// or one of `mesh_roots` (symlinks resolved; viewer/mesh_folders.h). Throws
// ViewInputError (viewer/view_frames.h) "MODEL:LINE: body 'NAME': mesh
// 'FILE': what" (names quoted) for a file outside those folders, missing,
// unreadable, not a regular file, over kMaxMeshFileBytes, not a valid STL
// (viewer/stl.h), or past kMaxMeshTotalBytes in all; "mesh root 'DIR': ..."
// for a root that is not an existing folder.
MeshFiles ReadMeshFiles(const Model& model, const std::vector<std::string>& mesh_roots = {});

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_MESH_FILES_H_
