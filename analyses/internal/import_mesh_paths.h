// Mesh paths in the model file `ccma import` writes: relative to the folder
// the model file goes to, so that the model and its meshes can be moved
// together and no absolute path of the importing machine is written (the
// robot readers resolve package://, model://, file:// and relative uris to
// absolute paths, formats/internal/mesh_paths.h).
#ifndef CCMA_ANALYSES_INTERNAL_IMPORT_MESH_PATHS_H_
#define CCMA_ANALYSES_INTERNAL_IMPORT_MESH_PATHS_H_

#include <string>
#include <vector>

#include "ccma/model.h"

namespace ccma {
namespace internal {

// `mesh` (absolute) relative to `folder` (absolute or relative to the
// working directory), both with the symlinks of their folders resolved:
// "meshes/a.stl", or "../robot/a.stl" when it lies outside `folder`.
std::string MeshPathRelativeTo(const std::string& mesh, const std::string& folder);

// Rewrites every body's mesh `file` with MeshPathRelativeTo(file, folder).
// Returns a warning naming `source` (the robot file) and the first such
// mesh when some lie outside `folder` (`ccma view --meshes` reads those only
// with --mesh_root), else "".
std::string RelateMeshPaths(const std::string& folder, const std::string& source, Model* model);

// What `ccma view --meshes` will not draw of the model's meshes (absolute
// paths, before RelateMeshPaths): files that are not there, and files that
// are not STL (.dae, .obj: the viewer reads STL only). One warning each
// kind, naming `source`, how many and the first; none when all are drawable.
std::vector<std::string> UndrawableMeshes(const std::string& source, const Model& model);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_ANALYSES_INTERNAL_IMPORT_MESH_PATHS_H_
