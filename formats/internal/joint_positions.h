// A robot read at its zero configuration (formats/robot_description.h) moved
// to given joint positions: the closure file's `q_home` (formats/closure_file.h),
// which `ccma export` writes so that the URDF's links are read where the
// model's loops are closed. Every link, its meshes and the frames of the
// joints it carries move by the link's rigid motion, found by walking the
// tree from the ground: a child link moves as its parent, then by its joint
// (a turn by q about the joint's axis through the joint point, or a shift by
// q along it).
#ifndef CCMA_FORMATS_INTERNAL_JOINT_POSITIONS_H_
#define CCMA_FORMATS_INTERNAL_JOINT_POSITIONS_H_

#include <utility>
#include <vector>

#include "formats/robot_description.h"

namespace ccma::internal {

// `positions`: (index into robot->joints, q in rad or m), each a revolute or
// prismatic joint of the tree (the caller checks); the other joints keep
// their zero position. Sets each listed joint's RobotJoint::position.
void MoveToJointPositions(const std::vector<std::pair<int, double>>& positions, RobotDescription* robot);

}  // namespace ccma::internal

#endif  // CCMA_FORMATS_INTERNAL_JOINT_POSITIONS_H_
