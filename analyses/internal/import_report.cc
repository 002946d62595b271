#include "analyses/internal/import_report.h"

#include <cmath>
#include <functional>
#include <map>
#include <string>

#include <Eigen/Geometry>

#include "analyses/internal/robot_model_builder.h"
#include "ccma/internal/format.h"

namespace ccma::internal {

namespace {

// The joints that close loops in the source itself (SDFormat's, a Gazebo
// <joint> in a URDF): those a spanning tree grown from the ground over the
// joints in file order leaves out. Each is posed once, in W, with both
// links at their source poses: gap 0 by construction.
std::vector<std::string> LoopJoints(const RobotDescription& robot) {
  std::map<std::string, std::string> root;  // union-find over link names
  const std::function<std::string(const std::string&)> find = [&](const std::string& link) {
    auto it = root.find(link);
    if (it == root.end() || it->second == link) return link;
    return it->second = find(it->second);
  };
  std::vector<std::string> loops;
  for (const RobotJoint& joint : robot.joints) {
    const std::string a = find(joint.parent), b = find(joint.child);
    if (a == b) {
      loops.push_back(joint.name);
    } else {
      root[a] = b;
    }
  }
  return loops;
}

}  // namespace

std::vector<ClosureGap> ClosureGaps(const RobotDescription& robot) {
  std::vector<ClosureGap> gaps;
  for (const std::string& name : LoopJoints(robot)) gaps.push_back({CcmaName(name), 0.0, 0.0});
  for (const RobotClosure& c : robot.closures) {
    ClosureGap gap;
    gap.name = CcmaName(ClosureJointName(c));
    gap.gap_m = (c.X_WA.translation() - c.X_WB.translation()).norm();
    if (c.six_d) gap.gap_rad = Eigen::AngleAxisd(c.X_WA.linear().transpose() * c.X_WB.linear()).angle();
    gaps.push_back(gap);
  }
  return gaps;
}

std::vector<MotorMove> MotorMoves(const Model& source, const Model& home) {
  std::vector<MotorMove> moves;
  for (std::size_t j = 0; j < home.joints.size(); ++j) {
    const Joint& joint = home.joints[j];
    if (!joint.actuated || !joint.has_coordinate()) continue;
    double move = joint.q_home - source.joints[j].q_home;
    if (joint.type == JointType::kRevolute) move = std::remainder(move, 2 * M_PI);
    moves.push_back({joint.name, move});
  }
  return moves;
}

std::vector<std::string> ImportChanges(const std::vector<ClosureGap>& gaps, const std::vector<MotorMove>& moves) {
  std::vector<std::string> lines;
  for (const ClosureGap& g : gaps) {
    if (g.gap_m > kImportTolerance || g.gap_rad > kImportTolerance) {
      lines.push_back("closure " + Quote(g.name) + ": its frames are " + FormatG(g.gap_m) + " m and " +
                      FormatG(g.gap_rad) + " rad apart in the source (joined where the assembly puts them)");
    }
  }
  for (const MotorMove& m : moves) {
    if (std::abs(m.move) > kImportTolerance) {
      lines.push_back("motor " + Quote(m.name) + " moved " + FormatG(m.move) +
                      " (rad or m) from its source position to close the loops");
    }
  }
  return lines;
}

}  // namespace ccma::internal
