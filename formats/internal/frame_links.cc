#include "formats/internal/frame_links.h"

#include <algorithm>
#include <set>
#include <utility>

#include "ccma/internal/format.h"
#include "formats/model_loader.h"

namespace ccma::internal {
namespace {

// A link `frame` is welded to that is not itself waiting to be fused: the
// other end of a fixed joint or of a 6d closure ("" when none). Sets *joint
// or *closure to that weld (the other -1).
std::string WeldedTo(const RobotDescription& robot, const std::string& frame, const std::vector<std::string>& pending,
                     int* joint, int* closure) {
  *joint = *closure = -1;
  const auto body = [&](const std::string& name) {
    return std::find(pending.begin(), pending.end(), name) == pending.end();
  };
  for (int j = 0; j < static_cast<int>(robot.joints.size()); ++j) {
    const RobotJoint& weld = robot.joints[j];
    if (weld.type != RobotJointType::kFixed || (weld.parent != frame) == (weld.child != frame)) continue;
    const std::string& other = weld.parent == frame ? weld.child : weld.parent;
    if (!body(other)) continue;
    *joint = j;
    return other;
  }
  for (int c = 0; c < static_cast<int>(robot.closures.size()); ++c) {
    const RobotClosure& weld = robot.closures[c];
    if (!weld.six_d || (weld.link_a != frame) == (weld.link_b != frame)) continue;
    const std::string& other = weld.link_a == frame ? weld.link_b : weld.link_a;
    if (!body(other)) continue;
    *closure = c;
    return other;
  }
  return "";
}

// A joint whose child became the ground (a cut joint of the world, whose
// frame link hung from its other body) is read the other way round: parent
// and child swapped, the axis negated so that the coordinate keeps its value
// (the child turned by q about -a relative to the parent is the parent turned
// by q about a relative to the child); a universal joint's two axes swap,
// each staying fixed in its link.
void TurnAround(RobotJoint* joint) {
  std::swap(joint->parent, joint->child);
  if (joint->type == RobotJointType::kUniversal) {
    std::swap(joint->axis_W, joint->axis2_W);
  } else {
    joint->axis_W = -joint->axis_W;
  }
}

// Every reference to link `from` becomes `to`; the weld (joint or closure
// index) and the link itself go.
void Fuse(const std::string& from, const std::string& to, int joint, int closure, RobotDescription* robot) {
  if (joint >= 0) robot->joints.erase(robot->joints.begin() + joint);
  if (closure >= 0) robot->closures.erase(robot->closures.begin() + closure);
  for (RobotJoint& j : robot->joints) {
    if (j.parent == from) j.parent = to;
    if (j.child == from) j.child = to;
    if (j.child == kRobotWorld) TurnAround(&j);
  }
  for (RobotClosure& c : robot->closures) {
    if (c.link_a == from) c.link_a = to;
    if (c.link_b == from) c.link_b = to;
  }
  // A 6d closure between two frames of one body now joins the body to itself.
  robot->closures.erase(std::remove_if(robot->closures.begin(), robot->closures.end(),
                                       [](const RobotClosure& c) { return c.link_a == c.link_b; }),
                        robot->closures.end());
  robot->links.erase(robot->links.begin() + robot->FindLink(from));
}

}  // namespace

void FuseFrameLinks(const std::vector<std::string>& frames, const std::string& where, RobotDescription* robot) {
  const std::set<std::string> pending_set(frames.begin(), frames.end());
  std::vector<std::string> pending(pending_set.begin(), pending_set.end());
  for (const std::string& name : pending) {
    const int link = robot->FindLink(name);
    if (name == kRobotWorld || link < 0) throw ModelError(where + ": " + Quote(name) + " is not a link of " + robot->source);
    const RobotLink& l = robot->links[static_cast<std::size_t>(link)];
    if (l.mass > 0 || !l.meshes.empty() || (robot->has_end_effector && robot->end_effector.link == name)) {
      throw ModelError(where + ": link " + Quote(name) + " is a body (it has a mass, meshes or the end-effector), not a frame");
    }
  }
  // A frame may be welded only to another frame (a cut joint's two sides):
  // fuse those whose weld leads to a body first, until none is left.
  while (!pending.empty()) {
    bool fused = false;
    for (std::size_t i = 0; i < pending.size(); ++i) {
      int joint = -1, closure = -1;
      const std::string to = WeldedTo(*robot, pending[i], pending, &joint, &closure);
      if (to.empty()) continue;
      Fuse(pending[i], to, joint, closure, robot);
      pending.erase(pending.begin() + static_cast<std::ptrdiff_t>(i));
      fused = true;
      break;
    }
    if (!fused) {
      throw ModelError(where + ": link " + Quote(pending.front()) +
                       " is welded (by a fixed joint or a 6d closure) to no body, so it cannot be fused into one");
    }
  }
}

}  // namespace ccma::internal
