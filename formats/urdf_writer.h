// A model written as URDF plus a closure file (`ccma export --format=urdf`,
// docs/cli.md; the closure file follows the example-parallel-robots
// convention of docs/model_format.md, "Robots described elsewhere").
//
// URDF holds a tree, rooted at a link `world`: the writer keeps a spanning
// tree of the joint graph (bases' joints from world, then revolute, prismatic and
// universal joints, then fixed, then spherical ones) and writes every other
// joint as a loop closure:
//  * every body is a link of the same name, with the body's frame. A wheeled
//    mobile base hangs from world by a `planar` joint (normal z), a legged
//    one by a `floating` joint holding ccma's <ccma_legged> extension
//    (formats/internal/legged_extension.h: its body height, limits and
//    footprint), its origin the body frame at home. The joint that
//    joins any other body to its parent moves a frame at the joint point,
//    with the body's home orientation (universal joints: x = the parent's
//    axis, y = the child's axis): the body's own link when that is its body
//    frame, else a link `<body>_joint_frame` welded to the body's link by a
//    fixed joint `<body>_weld`. A joint whose `between` runs against the
//    tree gets its axis negated, so its coordinate keeps its sign;
//  * URDF's zero configuration is q = 0 for every joint: a joint with q_home
//    != 0 has its origin moved back by q_home, so the model's home is where
//    every joint reads q_home. The closure file's `q_home` (ccma's extension)
//    lists those positions: `ccma import` reads the links there, where the
//    loops are closed, and every joint keeps its coordinate;
//  * revolute: `revolute` with its limits, or `continuous`; prismatic:
//    `prismatic` (a <limit> without lower/upper when unlimited); fixed:
//    `fixed`; spherical and universal: a `continuous` joint replaced in the
//    closure file (joint_name/joint_type: SPHERICAL, UJOINT_XY);
//  * a cut fixed or spherical joint J becomes two frame links J_A, J_B (fixed
//    to its two bodies at the joint point, world orientation at home) closed
//    by a '6d' or '3d' closure; a cut revolute, prismatic or universal joint
//    becomes a link J_A hanging from the first body through J itself, closed
//    '6d' to a frame link J_B of the second body;
//  * name_mot: the bases' planar and floating joints in base order, then the actuated
//    joints in file order (the model's control order). The end-effector goes
//    to ccma's `end_effector` extension (link, point in the link frame).
//  * the links that are frames, not bodies (`<body>_joint_frame`, J_A, J_B)
//    are listed in the closure file's `frames` (ccma's extension): `ccma
//    import` fuses each into the body it is welded to, so the import has the
//    model's bodies, no more (formats/internal/frame_links.h).
// Added names get a suffix "_2", ... when the model already uses them.
// Numbers are written in the fewest digits (15 to 17) that read back to the same doubles.
#ifndef CCMA_FORMATS_URDF_WRITER_H_
#define CCMA_FORMATS_URDF_WRITER_H_

#include <string>

#include "ccma/model.h"

namespace ccma {

struct UrdfExport {
  std::string urdf;      // the URDF document
  std::string closures;  // the closure file (YAML)
  int links = 0;         // URDF links, world included
  int joints = 0;        // URDF joints
  int loops = 0;         // closures
};

// The model (any valid one, as LoadModel returns it) as URDF and closure
// file. Throws std::invalid_argument for a body not connected to world.
UrdfExport WriteUrdf(const Model& model);

// Where the closure file of `urdf_path` goes: the path with its extension
// replaced by `.closures.yaml` (robot.urdf -> robot.closures.yaml; a path
// without an extension gets `.closures.yaml` appended).
std::string ClosureFilePath(const std::string& urdf_path);

}  // namespace ccma

#endif  // CCMA_FORMATS_URDF_WRITER_H_
