// Reading an SDFormat (1.4 or later: older versions through libsdformat's own
// conversion, with their meaning) robot into a RobotDescription, with
// libsdformat 12. SDFormat joints may form loops: libsdformat loads such a
// model when its links are posed assembled, and so does this reader (the
// closures of the description stay empty; the loop-closing joints are
// ordinary joints).
//
// What is read (docs/import.md has the user's view):
//  - the file's one <model> (or the one model of its one <world>); nested
//    models are rejected;
//  - every <link>, in file order, with its pose in W (the model's own pose
//    applied) and the <mesh> of each <visual> (uri resolved to a path, see
//    below; the mesh frame and <scale>);
//  - every <joint>, in file order: revolute and continuous -> kRevolute,
//    prismatic, fixed, ball -> kSpherical, universal -> kUniversal (axis fixed
//    in the parent, axis2 fixed in the child), `planar` from `world` ->
//    kPlanar (normal: the joint frame's z) and `floating` from `world` with
//    ccma's <ccma:legged .../> (formats/internal/legged_extension.h) ->
//    kFloating, a legged base. SDFormat has neither type: libsdformat reports
//    "Joint type of planar is invalid" (or floating) and loads the rest;
//    only those reports are forgiven. Other types (screw, gearbox, revolute2) are
//    rejected naming the joint. A parent or child that is a <frame> stands for
//    the link it is attached to; `world` is kRobotWorld.
//    The joint frame (X_WJ) is the joint's pose; the axis is <xyz> resolved
//    in W. <initial_position> (1.7/1.8) is the joint's position in the posed
//    configuration. A <limit> counts only when both <lower> and <upper> are
//    written, finite and not the +-1e16 that SDFormat uses for "no limit";
//    continuous joints have none.
//  - ccma's own optional element, inside <model>:
//      <ccma:end_effector link="L" point="x y z" controlled="x y z yaw"/>
//    (point in the link frame, m; controlled from x y z roll pitch yaw).
//  - a model with no joint to `world`: its root link (the first that is no
//    joint's child) is welded to `world` by a fixed joint `world__ROOT`, as a
//    URDF's root is, with a warning in RobotDescription::warnings.
// Mesh uris are resolved against the file's folder as URDF ones are
// (formats/internal/mesh_paths.h: file://, relative, model://NAME/rest and
// package://NAME/rest searched from the file's folder upwards; not found ->
// the file's folder/rest, which the viewer reports missing).
//
// Refused before libsdformat sees the file (it would otherwise read another
// file or run out of memory): anything but the plain XML of
// formats/internal/robot_xml.h with one <sdf> root (at most 100 deep, 100,000
// elements), any <include> (the only element that makes libsdformat open a
// file), and a file whose elements would take libsdformat more than
// kMaxSdformatMegabytes (formats/internal/sdformat_cost.h: about 700 links).
//
// Errors: ModelError. libsdformat's rejections are quoted (its first three),
//   FILE: libsdformat: <message> [line N]; ...
// the reader's own findings name file, line and element:
//   FILE:LINE: joint 'j': type 'screw' is not supported (...)
// Nothing is printed (libsdformat's console is silenced).
#ifndef CCMA_FORMATS_SDFORMAT_READER_H_
#define CCMA_FORMATS_SDFORMAT_READER_H_

#include <cstddef>
#include <string>
#include <vector>

#include "formats/robot_description.h"

namespace ccma {

// SDFormat files are read up to this many bytes and must be regular files.
constexpr std::size_t kMaxSdformatFileBytes = std::size_t{16} << 20;

// Reads the SDFormat file at `path`. `actuated` (joint names, in control
// order) is copied to RobotDescription::actuated, or when empty the list a
// `<ccma:actuated joints="..."/>` element stores (`ccma export` writes one);
// ImportRobot checks the names.
// Throws ModelError.
RobotDescription ReadSdformat(const std::string& path, const std::vector<std::string>& actuated);

// The same for SDFormat text held in memory; `path` names it in messages and
// its folder resolves relative mesh uris (the file itself is not read).
RobotDescription ReadSdformatFromString(const std::string& text, const std::string& path,
                                        const std::vector<std::string>& actuated);

}  // namespace ccma

#endif  // CCMA_FORMATS_SDFORMAT_READER_H_
