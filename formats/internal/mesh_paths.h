// Where a robot file's mesh reference points on this machine. Robot files
// name meshes as `package://PKG/rest` (ROS), `model://MODEL/rest` (Gazebo),
// `file:///abs/path` or a path relative to the robot file.
#ifndef CCMA_FORMATS_INTERNAL_MESH_PATHS_H_
#define CCMA_FORMATS_INTERNAL_MESH_PATHS_H_

#include <string>

namespace ccma {
namespace internal {

// The absolute path of mesh reference `uri` in a robot file in folder
// `robot_folder` (absolute). package://PKG/rest and model://PKG/rest: the
// first existing of FOLDER/rest and ANCESTOR/PKG/rest for the robot folder
// and each ancestor (an empty PKG, as in `package:///m.stl`, means the robot
// folder); when none exists, robot_folder/rest (the viewer reports it
// missing). Nothing is opened or read here.
std::string ResolveMeshPath(const std::string& uri, const std::string& robot_folder);

// The absolute folder of `file` (the current directory joined when relative).
std::string AbsoluteFolderOf(const std::string& file);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_MESH_PATHS_H_
