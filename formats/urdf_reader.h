// URDF (a tree of links and joints) plus an optional closure file
// (formats/closure_file.h) -> RobotDescription (formats/robot_description.h).
// Parsed with urdfdom, the ROS community's parser; TinyXML (urdfdom's own
// XML parser) supplies line numbers and what urdfdom does not keep (whether
// a <limit> gives lower and upper, the order of elements).
#ifndef CCMA_FORMATS_URDF_READER_H_
#define CCMA_FORMATS_URDF_READER_H_

#include <string>

#include "formats/robot_description.h"

namespace ccma {

// A URDF file is a few hundred kilobytes; this bounds hostile ones.
constexpr std::size_t kMaxRobotFileBytes = std::size_t{16} << 20;

// Before any XML parser sees it, the file must be plain XML with one <robot>
// element, at most 100 deep and 100,000 elements (formats/internal/robot_xml.h);
// at most kMaxRobotLinks links and kMaxRobotJoints joints.
// Reads `urdf_path` and, unless `closures_path` is empty, its closure file.
// Link poses are those of the URDF's zero configuration (every joint at 0),
// or, when the closure file gives ccma's `q_home`, of those joint positions.
// The root link is the ground when it is called `world`; otherwise it is
// welded to the ground by a fixed joint `world__ROOT`. Mesh references are
// resolved against the URDF's folder. Throws ModelError naming the file,
// the line and the element on a malformed file, an unsupported joint type
// (planar or floating other than from the ground) or an unknown name. A
// floating joint from the ground is a legged base: it must hold ccma's
// <ccma_legged .../> (formats/internal/legged_extension.h), read into
// RobotJoint::legged.
RobotDescription ReadUrdf(const std::string& urdf_path, const std::string& closures_path);

// The URDF part of ReadUrdf for text in memory; `urdf_path` names it in
// messages and its folder resolves mesh paths (the file is not read). A
// closure file's text goes through ParseClosureFile and ApplyClosureFile
// (formats/closure_file.h).
RobotDescription ReadUrdfFromString(const std::string& text, const std::string& urdf_path);

}  // namespace ccma

#endif  // CCMA_FORMATS_URDF_READER_H_
