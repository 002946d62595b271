// Loops closed the Gazebo way in a URDF: a <joint> inside a <gazebo> element
// (URDF's trees cannot close a loop; Gazebo copies such a joint into the
// SDFormat it makes, as Gazebo's own four-bar URDF does):
//   <gazebo>
//     <joint name="coupler_rocker" type="revolute">
//       <parent>coupler</parent> <child>rocker</child>
//       <pose>2 0 0 0 0 0</pose>      optional: the joint frame in the child link's frame
//       <axis><xyz>0 0 1</xyz></axis>  revolute, prismatic: in the joint frame
//     </joint>
//   </gazebo>
// Each becomes an ordinary joint of the description (as an SDFormat file's
// loop-closing joints are) at the links' zero-configuration poses.
#ifndef CCMA_FORMATS_INTERNAL_GAZEBO_LOOP_JOINTS_H_
#define CCMA_FORMATS_INTERNAL_GAZEBO_LOOP_JOINTS_H_

#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <tinyxml.h>

#include "formats/robot_description.h"

namespace ccma::internal {

struct GazeboJoint {
  std::string name, parent, child;
  RobotJointType type = RobotJointType::kFixed;  // revolute/continuous, prismatic, fixed, ball
  Eigen::Isometry3d X_CJ = Eigen::Isometry3d::Identity();  // joint frame in the child link's frame
  Eigen::Vector3d axis_J = Eigen::Vector3d::UnitZ();       // in the joint frame, unit
  int line = 0;
};

// The joints of every <gazebo> child of `robot` (a URDF's root element), in
// file order. Throws ModelError "source:line: gazebo joint 'name': what" for
// a missing name, parent or child, an unsupported type, a malformed pose or
// axis (six or three finite numbers within 1e4; a non-zero axis).
std::vector<GazeboJoint> ReadGazeboJoints(const TiXmlElement& robot, const std::string& source);

// Adds `joints` to `robot`, whose links are posed: X_WJ = X_WC X_CJ, the
// axis in W. Throws ModelError naming the joint for an unknown link or a
// name another joint has.
void AddGazeboJoints(const std::vector<GazeboJoint>& joints, const std::string& source, RobotDescription* robot);

}  // namespace ccma::internal

#endif  // CCMA_FORMATS_INTERNAL_GAZEBO_LOOP_JOINTS_H_
