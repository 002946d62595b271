// A robot file of any format ccma imports, read by its format's reader: the
// one entry `ccma import` and Python's import_robot() use, so that a new
// format (a reader of its own, formats/<format>_reader.h) arrives here once.
#ifndef CCMA_FORMATS_ROBOT_FILE_H_
#define CCMA_FORMATS_ROBOT_FILE_H_

#include <string>
#include <vector>

#include "formats/robot_description.h"

namespace ccma {

enum class RobotFileFormat { kUnknown, kUrdf, kSdformat };

// The format a file's name says: .urdf or .xml URDF (an .xml whose root is
// <mujoco> is read as MuJoCo MJCF by ReadRobotFile), .sdf or .world
// SDFormat, anything else kUnknown.
RobotFileFormat RobotFileFormatOf(const std::string& path);

// Reads the robot at `path` in `format` (not kUnknown): a URDF with its
// closure file `closures_path` ("" for none; urdf_reader.h), an SDFormat
// file with the actuated joints `actuated` (sdformat_reader.h), an MJCF
// (.xml with a <mujoco> root; mjcf_reader.h) with `actuated` and the
// configuration of its keyframe `keyframe` ("" for qpos0). Throws
// ModelError, and std::invalid_argument for a closure file given with an
// SDFormat or MJCF file ("closures is for URDF (SDFormat holds its loops)"),
// a keyframe with another format, or kUnknown.
RobotDescription ReadRobotFile(const std::string& path, RobotFileFormat format, const std::string& closures_path,
                               const std::vector<std::string>& actuated, const std::string& keyframe = "");

}  // namespace ccma

#endif  // CCMA_FORMATS_ROBOT_FILE_H_
