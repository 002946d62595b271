// The folders `ccma view --meshes` may read mesh files from. A model file
// comes from someone else as often as not: the meshes it names are confined
// to its own folder, so that a page (which people pass on) never embeds a
// file of the viewing user's from elsewhere (`/home/me/...`, `../..`, or a
// symlink shipped beside the model). The user adds trusted folders with
// `--mesh_root` (Python: mesh_root=); the model file itself cannot.
#ifndef CCMA_VIEWER_MESH_FOLDERS_H_
#define CCMA_VIEWER_MESH_FOLDERS_H_

#include <optional>
#include <string>
#include <vector>

namespace ccma::viewer {

class MeshFolders {
 public:
  // The folder of `model_source` (Model::source; the working directory when
  // it has none) and each of `roots`, all canonical (symlinks resolved).
  // Throws ViewInputError (viewer/view_frames.h) for a root that is not an
  // existing folder.
  MeshFolders(const std::string& model_source, const std::vector<std::string>& roots);

  // The canonical form of `path` (symlinks resolved; a missing tail kept as
  // written, lexically normalised) when it lies inside one of the folders,
  // else nothing.
  std::optional<std::string> Confine(const std::string& path) const;

  // The model file's folder, canonical (for messages); empty when it does not exist.
  const std::string& model_folder() const { return model_folder_; }
  // Whether folders beyond the model's were given.
  bool has_roots() const { return has_roots_; }

 private:
  std::string model_folder_;
  std::vector<std::string> folders_;  // model_folder_ (when it exists), then the roots
  bool has_roots_ = false;
};

// What the page records for a mesh `file` as the model writes it: the path
// relative to the model's folder when it is relative and stays inside it
// lexically, else the file name alone. Never an absolute path.
std::string PageMeshPath(const std::string& file);

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_MESH_FOLDERS_H_
