#include "formats/internal/joint_positions.h"

#include <map>
#include <set>
#include <string>

#include <Eigen/Geometry>

namespace ccma::internal {
namespace {

// The world-frame motion of a joint's child relative to its parent at
// position q, from the zero configuration: a turn about the axis through the
// joint point, or a shift along the axis.
Eigen::Isometry3d JointMotion(const RobotJoint& joint, double q) {
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  if (joint.type == RobotJointType::kRevolute) {
    const Eigen::Vector3d p = joint.X_WJ.translation();
    M.linear() = Eigen::AngleAxisd(q, joint.axis_W.normalized()).toRotationMatrix();
    M.translation() = p - M.linear() * p;
  } else if (joint.type == RobotJointType::kPrismatic) {
    M.translation() = q * joint.axis_W.normalized();
  }
  return M;
}

}  // namespace

void MoveToJointPositions(const std::vector<std::pair<int, double>>& positions, RobotDescription* robot) {
  std::vector<double> q(robot->joints.size(), 0.0);
  for (const auto& [j, value] : positions) q[j] = value;
  // Each link's motion D (new pose = D * zero pose), from the roots down.
  std::map<std::string, std::vector<int>> children;  // link -> joints it is the parent of
  std::set<std::string> child_links;
  for (int j = 0; j < static_cast<int>(robot->joints.size()); ++j) {
    children[robot->joints[j].parent].push_back(j);
    child_links.insert(robot->joints[j].child);
  }
  std::map<std::string, Eigen::Isometry3d> motion;
  std::vector<std::string> pending;
  const auto root = [&](const std::string& name) {
    if (child_links.count(name) == 0 && motion.emplace(name, Eigen::Isometry3d::Identity()).second) {
      pending.push_back(name);
    }
  };
  root(kRobotWorld);
  for (const RobotLink& link : robot->links) root(link.name);
  while (!pending.empty()) {
    const std::string parent = pending.back();
    pending.pop_back();
    const Eigen::Isometry3d D_P = motion.at(parent);
    for (const int j : children[parent]) {
      RobotJoint& joint = robot->joints[j];
      const Eigen::Isometry3d D_C = D_P * JointMotion(joint, q[j]);
      if (!motion.emplace(joint.child, D_C).second) continue;  // not a tree: keep the first path
      pending.push_back(joint.child);
      joint.axis_W = D_P.linear() * joint.axis_W;    // fixed in the parent
      joint.axis2_W = D_C.linear() * joint.axis2_W;  // universal: fixed in the child
      joint.X_WJ = D_C * joint.X_WJ;                 // the child's frame (URDF)
      joint.position = q[j];
    }
  }
  for (RobotLink& link : robot->links) {
    const auto it = motion.find(link.name);
    if (it == motion.end()) continue;
    link.X_WL = it->second * link.X_WL;
    for (RobotMesh& mesh : link.meshes) mesh.X_WM = it->second * mesh.X_WM;
  }
}

}  // namespace ccma::internal
