#include "formats/internal/gazebo_loop_joints.h"

#include <cmath>
#include <sstream>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "ccma/rotation.h"
#include "formats/model_loader.h"

namespace ccma::internal {
namespace {

[[noreturn]] void Fail(const std::string& source, int line, const std::string& name, const std::string& what) {
  throw ModelError(source + ":" + std::to_string(line) + ": gazebo joint " + Quote(name) + ": " + what);
}

std::string ChildText(const TiXmlElement& e, const char* child) {
  const TiXmlElement* c = e.FirstChildElement(child);
  return c != nullptr && c->GetText() != nullptr ? c->GetText() : "";
}

// `count` finite numbers within kMaxMagnitude from `text`; false otherwise.
bool Numbers(const std::string& text, int count, Eigen::VectorXd* out) {
  std::istringstream in(text);
  out->resize(count);
  for (int i = 0; i < count; ++i) {
    if (!(in >> (*out)[i]) || !std::isfinite((*out)[i]) || std::abs((*out)[i]) > kMaxMagnitude) return false;
  }
  std::string rest;
  return !(in >> rest);
}

RobotJointType TypeOf(const std::string& type, const std::string& source, int line, const std::string& name) {
  if (type == "revolute" || type == "continuous") return RobotJointType::kRevolute;
  if (type == "prismatic") return RobotJointType::kPrismatic;
  if (type == "fixed") return RobotJointType::kFixed;
  if (type == "ball") return RobotJointType::kSpherical;
  Fail(source, line, name, "type " + Quote(type) + " is not supported (revolute, continuous, prismatic, fixed, ball)");
}

GazeboJoint ReadOne(const TiXmlElement& e, const std::string& source) {
  GazeboJoint j;
  j.line = e.Row();
  const char* name = e.Attribute("name");
  const char* type = e.Attribute("type");
  j.name = name != nullptr ? name : "";
  if (j.name.empty() || j.name.size() > 4 * kMaxNameLength) {
    Fail(source, j.line, j.name, "needs a name of at most " + std::to_string(4 * kMaxNameLength) + " bytes");
  }
  j.type = TypeOf(type != nullptr ? type : "", source, j.line, j.name);
  j.parent = ChildText(e, "parent");
  j.child = ChildText(e, "child");
  if (j.parent.empty() || j.child.empty()) Fail(source, j.line, j.name, "needs <parent> and <child> links");
  Eigen::VectorXd v;
  if (e.FirstChildElement("pose") != nullptr) {
    if (!Numbers(ChildText(e, "pose"), 6, &v)) Fail(source, j.line, j.name, "<pose> must be six numbers x y z roll pitch yaw");
    j.X_CJ.linear() = RotationFromRpy(v.tail<3>());
    j.X_CJ.translation() = v.head<3>();
  }
  const TiXmlElement* axis = e.FirstChildElement("axis");
  if (axis != nullptr) {
    if (!Numbers(ChildText(*axis, "xyz"), 3, &v) || v.norm() < 1e-9) {
      Fail(source, j.line, j.name, "<axis><xyz> must be three numbers, not all zero");
    }
    j.axis_J = v.normalized();
  } else if (j.type == RobotJointType::kRevolute || j.type == RobotJointType::kPrismatic) {
    Fail(source, j.line, j.name, "needs <axis><xyz>");
  }
  return j;
}

}  // namespace

std::vector<GazeboJoint> ReadGazeboJoints(const TiXmlElement& robot, const std::string& source) {
  std::vector<GazeboJoint> joints;
  for (const TiXmlElement* g = robot.FirstChildElement("gazebo"); g != nullptr; g = g->NextSiblingElement("gazebo")) {
    for (const TiXmlElement* e = g->FirstChildElement("joint"); e != nullptr; e = e->NextSiblingElement("joint")) {
      if (joints.size() >= static_cast<std::size_t>(kMaxRobotJoints)) {
        Fail(source, e->Row(), "", "more than " + std::to_string(kMaxRobotJoints) + " joints");
      }
      joints.push_back(ReadOne(*e, source));
    }
  }
  return joints;
}

void AddGazeboJoints(const std::vector<GazeboJoint>& joints, const std::string& source, RobotDescription* robot) {
  for (const GazeboJoint& g : joints) {
    if (robot->FindJoint(g.name) >= 0) Fail(source, g.line, g.name, "another joint has that name");
    const int child = robot->FindLink(g.child);
    const bool world_parent = g.parent == kRobotWorld;
    if (child < 0 || (!world_parent && robot->FindLink(g.parent) < 0)) {
      Fail(source, g.line, g.name, "unknown link " + Quote(child < 0 ? g.child : g.parent));
    }
    RobotJoint joint;
    joint.name = g.name;
    joint.type = g.type;
    joint.parent = g.parent;
    joint.child = g.child;
    joint.X_WJ = robot->links[static_cast<std::size_t>(child)].X_WL * g.X_CJ;
    joint.axis_W = joint.X_WJ.linear() * g.axis_J;
    joint.line = g.line;
    robot->joints.push_back(joint);
  }
}

}  // namespace ccma::internal
