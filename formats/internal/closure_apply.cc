// ApplyClosureFile (formats/closure_file.h): closures, overrides, motors.
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "ccma/internal/format.h"
#include "formats/closure_file.h"
#include "formats/internal/frame_links.h"
#include "formats/internal/joint_positions.h"
#include "formats/model_loader.h"

namespace ccma {
namespace {

[[noreturn]] void Fail(const ClosureFile& file, int line, const std::string& key, const std::string& what) {
  throw ModelError(file.source + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + key + ": " + what);
}

// The link carrying frame `name` (a link, or a joint's child link).
int FrameLink(const RobotDescription& robot, const std::string& name) {
  const int link = robot.FindLink(name);
  if (link >= 0) return link;
  const int joint = robot.FindJoint(name);
  return joint >= 0 ? robot.FindLink(robot.joints[joint].child) : -1;
}

RobotClosure Closure(const ClosureFile& file, std::size_t i, const RobotDescription& robot) {
  const ClosureFile::Loop& loop = file.loops[i];
  RobotClosure closure;
  closure.frame_a = loop.frame_a;
  closure.frame_b = loop.frame_b;
  closure.six_d = loop.six_d;
  closure.line = loop.line;
  const std::string key = "closed_loop[" + std::to_string(i) + "]";
  const int a = FrameLink(robot, loop.frame_a), b = FrameLink(robot, loop.frame_b);
  const std::initializer_list<std::pair<int, std::string>> ends = {{a, loop.frame_a}, {b, loop.frame_b}};
  for (const auto& [link, name] : ends) {
    if (link < 0) {
      Fail(file, loop.line, key, "unknown frame " + Quote(name) + " (no link or joint of " + robot.source +
                                     " has that name)");
    }
  }
  if (a == b) Fail(file, loop.line, key, "both frames are on link " + Quote(robot.links[a].name));
  closure.link_a = robot.links[a].name;
  closure.link_b = robot.links[b].name;
  closure.X_WA = robot.links[a].X_WL * loop.X_A_offset;
  closure.X_WB = robot.links[b].X_WL;
  return closure;
}

// UJOINT_XY: a universal joint whose axis fixed in the parent is the joint
// frame's x axis and whose axis fixed in the child is its y axis.
void MakeUniversal(const std::string& type, RobotJoint* joint) {
  const auto axis = [&](char c) -> Eigen::Vector3d {
    return joint->X_WJ.linear().col(c == 'X' ? 0 : c == 'Y' ? 1 : 2);
  };
  joint->type = RobotJointType::kUniversal;
  joint->axis_W = axis(type[7]);
  joint->axis2_W = axis(type[8]);
  joint->limited = false;
}

void ApplyOverride(const ClosureFile& file, const ClosureFile::Override& o, RobotDescription* robot) {
  const int j = robot->FindJoint(o.joint);
  if (j < 0) {  // the collection's own loader skips these too; say so
    robot->warnings.push_back(file.source + ":" + std::to_string(o.line) + ": joint_name: no joint " + Quote(o.joint) +
                              " in " + robot->source + ", ignored");
    return;
  }
  RobotJoint& joint = robot->joints[j];
  if (joint.type == RobotJointType::kPlanar) Fail(file, o.line, "joint_type", "joint " + Quote(o.joint) + " is planar");
  if (o.type == "SPHERICAL") {
    joint.type = RobotJointType::kSpherical;
    joint.limited = false;
  } else if (o.type == "FIXED") {
    joint.type = RobotJointType::kFixed;
    joint.limited = false;
  } else {
    MakeUniversal(o.type, &joint);
  }
}

// q_home: the links moved to these joint positions (before the closures'
// frames are taken from them).
void ApplyPositions(const ClosureFile& file, RobotDescription* robot) {
  std::vector<std::pair<int, double>> positions;
  for (const ClosureFile::Position& p : file.positions) {
    const int j = robot->FindJoint(p.joint);
    if (j < 0) {
      Fail(file, p.line, "q_home", "unknown joint " + Quote(p.joint) + " (not a joint of " + robot->source + ")");
    }
    const RobotJointType type = robot->joints[j].type;
    if (type != RobotJointType::kRevolute && type != RobotJointType::kPrismatic) {
      Fail(file, p.line, "q_home", "joint " + Quote(p.joint) + " is not revolute or prismatic: it has no position");
    }
    positions.emplace_back(j, p.q);
  }
  if (!positions.empty()) internal::MoveToJointPositions(positions, robot);
}

}  // namespace

void ApplyClosureFile(const ClosureFile& file, RobotDescription* robot) {
  for (const ClosureFile::Override& o : file.overrides) ApplyOverride(file, o, robot);
  ApplyPositions(file, robot);
  for (std::size_t i = 0; i < file.loops.size(); ++i) robot->closures.push_back(Closure(file, i, *robot));
  for (const std::string& name : file.actuated) {
    if (robot->FindJoint(name) < 0) {
      Fail(file, file.actuated_line, "name_mot", "unknown joint " + Quote(name) + " (not a joint of " + robot->source + ")");
    }
  }
  robot->actuated = file.actuated;
  if (file.has_end_effector) {
    robot->has_end_effector = true;
    robot->end_effector = file.end_effector;
  }
  if (!file.frames.empty()) {
    internal::FuseFrameLinks(file.frames, file.source + ":" + std::to_string(file.frames_line) + ": frames", robot);
  }
}

}  // namespace ccma
