#include "analyses/internal/robot_model_builder.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <string>

#include "analyses/internal/import_model_name.h"
#include "ccma/base_kind.h"
#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/joint_geometry.h"
#include "formats/model_loader.h"

namespace ccma {
namespace internal {
namespace {

[[noreturn]] void Fail(const RobotDescription& robot, int line, const std::string& what) {
  throw ModelError(robot.source + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what);
}

// Index of the body for source link `link` (kWorld for the ground).
int BodyOf(const std::map<std::string, int>& bodies, const std::string& link) {
  if (link == kRobotWorld) return kWorld;
  const auto it = bodies.find(link);
  return it == bodies.end() ? -2 : it->second;
}

// A planar joint's child as a mobile base: the link itself when its frame is
// on the ground and upright; otherwise (not supported) an error.
MobileBase Base(const RobotDescription& robot, const RobotJoint& joint, const RobotLink& link) {
  const Eigen::Isometry3d& X = link.X_WL;
  if ((joint.axis_W - Eigen::Vector3d::UnitZ()).norm() > 1e-9 && (joint.axis_W + Eigen::Vector3d::UnitZ()).norm() > 1e-9) {
    Fail(robot, joint.line, "joint " + Quote(joint.name) + ": a planar joint's normal must be the world z axis");
  }
  if (std::abs(X.translation().z()) > 1e-9 || X.linear().col(2).z() < 1 - 1e-12) {
    Fail(robot, joint.line, "joint " + Quote(joint.name) + ": the mobile base link " + Quote(link.name) +
                                " must have its frame on the ground (z = 0) and upright at home");
  }
  MobileBase base;
  base.name = CcmaName(link.name);
  base.home_pose = Eigen::Vector3d(X.translation().x(), X.translation().y(),
                                   std::atan2(X.linear()(1, 0), X.linear()(0, 0)));
  return base;
}

// A floating joint's child as a legged base: the link itself when its frame
// is upright at the body height its extension gives (the body frame at home).
MobileBase LeggedBaseOf(const RobotDescription& robot, const RobotJoint& joint, const RobotLink& link) {
  const Eigen::Isometry3d& X = link.X_WL;
  if (std::abs(X.translation().z() - joint.legged.height) > 1e-9 || X.linear().col(2).z() < 1 - 1e-12) {
    Fail(robot, joint.line, "joint " + Quote(joint.name) + ": the legged base link " + Quote(link.name) +
                                " must be upright at home with its frame at body_height " +
                                FormatG(joint.legged.height) + " m above the ground (it is at " +
                                FormatG(X.translation().z()) + " m)");
  }
  MobileBase base;
  base.name = CcmaName(link.name);
  base.type = BaseType::kLegged;
  base.legged = joint.legged;
  base.home_pose = Eigen::Vector3d(X.translation().x(), X.translation().y(),
                                   std::atan2(X.linear()(1, 0), X.linear()(0, 0)));
  return base;
}

bool IsBaseJoint(RobotJointType type) { return type == RobotJointType::kPlanar || type == RobotJointType::kFloating; }

// Bodies: links first (source order), then the bases in control order.
void AddBodies(const RobotDescription& robot, const std::vector<int>& base_joints, Model* model,
               std::map<std::string, int>* bodies) {
  std::set<std::string> base_links;
  for (const int j : base_joints) base_links.insert(robot.joints[j].child);
  std::set<std::string> names;
  const auto add = [&](const RobotLink& link) {
    Body body;
    body.name = CcmaName(link.name);
    if (!names.insert(body.name).second) {
      Fail(robot, link.line, "link " + Quote(link.name) + ": its ccma name " + Quote(body.name) + " is taken by another link");
    }
    body.R_WB_home = link.X_WL.linear();
    body.p_WB_home = link.X_WL.translation();
    // The source's inertial, in the body frame (ccma/mass_properties.h).
    body.inertia.mass = link.mass;
    body.inertia.com_B = body.R_WB_home.transpose() * (link.com_W - body.p_WB_home);
    body.inertia.inertia_B = body.R_WB_home.transpose() * link.inertia_W * body.R_WB_home;
    for (const RobotMesh& mesh : link.meshes) {
      BodyMesh m;
      m.file = mesh.file;
      m.R_BM = body.R_WB_home.transpose() * mesh.X_WM.linear();
      m.p_BM = body.R_WB_home.transpose() * (mesh.X_WM.translation() - body.p_WB_home);
      m.scale = mesh.scale;
      body.meshes.push_back(m);
    }
    (*bodies)[link.name] = model->num_bodies();
    model->bodies.push_back(body);
  };
  for (const RobotLink& link : robot.links) {
    if (link.name == kRobotWorld) Fail(robot, link.line, "link 'world' must be the root of the tree");
    if (base_links.count(link.name) == 0) add(link);
  }
  for (const int j : base_joints) {
    const RobotJoint& joint = robot.joints[j];
    const RobotLink& link = robot.links[robot.FindLink(joint.child)];
    MobileBase base = joint.type == RobotJointType::kFloating ? LeggedBaseOf(robot, joint, link) : Base(robot, joint, link);
    base.body = model->num_bodies();
    add(link);
    Body& body = model->bodies.back();
    body.base_index = model->num_bases();
    KindOf(base).HomeFrame(base, &body.R_WB_home, &body.p_WB_home);
    model->mobile_bases.push_back(base);
  }
}

JointType TypeOf(RobotJointType type) {
  switch (type) {
    case RobotJointType::kRevolute: return JointType::kRevolute;
    case RobotJointType::kPrismatic: return JointType::kPrismatic;
    case RobotJointType::kSpherical: return JointType::kSpherical;
    case RobotJointType::kUniversal: return JointType::kUniversal;
    default: return JointType::kFixed;
  }
}

Joint TreeJoint(const RobotDescription& robot, const RobotJoint& source, const Model& model,
                const std::map<std::string, int>& bodies) {
  Joint joint;
  joint.name = CcmaName(source.name);
  joint.type = TypeOf(source.type);
  joint.body_a = BodyOf(bodies, source.parent);
  joint.body_b = BodyOf(bodies, source.child);
  if (joint.body_a == -2 || joint.body_b == -2 || joint.body_b == kWorld) {
    Fail(robot, source.line, "joint " + Quote(source.name) + " connects an unknown link or has the ground as its child");
  }
  Eigen::Vector3d b_W = source.axis2_W;
  if (joint.type == JointType::kUniversal) {
    const double cosine = source.axis_W.dot(b_W);
    if (std::abs(cosine) > 1e-6) Fail(robot, source.line, "joint " + Quote(source.name) + ": universal axes not perpendicular");
    b_W = (b_W - cosine * source.axis_W).normalized();
  }
  SetJointGeometry(model, source.X_WJ.translation(), source.axis_W, b_W, &joint);
  joint.q_home = source.position;
  joint.limited = source.limited;
  joint.lower = source.lower;
  joint.upper = source.upper;
  joint.line = source.line;
  return joint;
}

// A closure: a fixed (6d) or spherical (3d) joint whose two frames keep
// their own points (and orientations) in their bodies until assembled.
Joint ClosureJoint(const RobotDescription& robot, const RobotClosure& c, const Model& model,
                   const std::map<std::string, int>& bodies) {
  Joint joint;
  joint.name = CcmaName(ClosureJointName(c));
  joint.type = c.six_d ? JointType::kFixed : JointType::kSpherical;
  joint.body_a = BodyOf(bodies, c.link_a);
  joint.body_b = BodyOf(bodies, c.link_b);
  if (joint.body_a == -2 || joint.body_b == -2) Fail(robot, c.line, "closure " + Quote(joint.name) + ": unknown link");
  static const Body kGround;
  const Body& A = joint.body_a == kWorld ? kGround : model.bodies[joint.body_a];
  const Body& B = joint.body_b == kWorld ? kGround : model.bodies[joint.body_b];
  joint.p_A = A.R_WB_home.transpose() * (c.X_WA.translation() - A.p_WB_home);
  joint.p_B = B.R_WB_home.transpose() * (c.X_WB.translation() - B.p_WB_home);
  joint.d1_A = A.R_WB_home.transpose() * c.X_WA.linear().col(0);
  joint.d2_A = A.R_WB_home.transpose() * c.X_WA.linear().col(1);
  joint.d1_B = B.R_WB_home.transpose() * c.X_WB.linear().col(0);
  joint.d2_B = B.R_WB_home.transpose() * c.X_WB.linear().col(1);
  joint.line = c.line;
  return joint;
}

// The actuated list split into planar joints (bases) and motors, checked.
void SplitActuated(const RobotDescription& robot, const std::vector<std::string>& actuated, std::vector<int>* bases,
                   std::vector<int>* motors) {
  std::set<std::string> seen;
  for (const std::string& name : actuated) {
    const int j = robot.FindJoint(name);
    if (j < 0) Fail(robot, 0, "actuated joint " + Quote(name) + ": no joint of " + robot.source + " has that name");
    if (!seen.insert(name).second) Fail(robot, robot.joints[j].line, "joint " + Quote(name) + " is actuated twice");
    const RobotJointType type = robot.joints[j].type;
    if (IsBaseJoint(type)) {
      bases->push_back(j);
    } else if (type == RobotJointType::kRevolute || type == RobotJointType::kPrismatic) {
      motors->push_back(j);
    } else {
      Fail(robot, robot.joints[j].line, "joint " + Quote(name) +
                                            " cannot be actuated (only revolute, prismatic, planar and floating "
                                            "joints can)");
    }
  }
  for (int j = 0; j < static_cast<int>(robot.joints.size()); ++j) {
    if (IsBaseJoint(robot.joints[j].type) && std::count(bases->begin(), bases->end(), j) == 0) {
      bases->push_back(j);
    }
  }
}

// The tree joints in source order, the motors' slots holding the motors in
// control order (the loader numbers actuated joints in file order).
std::vector<int> TreeOrder(const RobotDescription& robot, const std::vector<int>& motors) {
  std::vector<int> order, slots;
  for (int j = 0; j < static_cast<int>(robot.joints.size()); ++j) {
    if (IsBaseJoint(robot.joints[j].type)) continue;
    if (std::count(motors.begin(), motors.end(), j) > 0) slots.push_back(static_cast<int>(order.size()));
    order.push_back(j);
  }
  for (std::size_t k = 0; k < slots.size(); ++k) order[slots[k]] = motors[k];
  return order;
}

// The end-effector; returns where its controlled components come from
// (RobotModel::controlled).
RobotModel::Controlled SetEndEffector(const RobotDescription& robot, const ImportOptions& options,
                                      const std::map<std::string, int>& bodies, Model* model) {
  const bool given = !options.end_effector_link.empty();
  if (!given && !robot.has_end_effector) {
    Fail(robot, 0, "no end-effector link: name one with --end_effector=LINK[:px,py,pz]");
  }
  std::string link = given ? options.end_effector_link : robot.end_effector.link;
  const Eigen::Vector3d p_L = given ? options.end_effector_point_L : robot.end_effector.point_L;
  if (robot.FindLink(link) < 0 && robot.FindJoint(link) >= 0) link = robot.joints[robot.FindJoint(link)].child;
  const int body = BodyOf(bodies, link);
  if (body < 0) Fail(robot, 0, "end-effector link " + Quote(link) + ": no link of " + robot.source + " has that name");
  EndEffector& ee = model->end_effector;
  ee.body = body;
  ee.p_B = p_L;
  const Body& B = model->bodies[body];
  ee.p_W_home = B.R_WB_home * p_L + B.p_WB_home;
  const bool stored = !given && !robot.end_effector.controlled.empty();
  const std::vector<std::string> all_six(kEndEffectorComponentNames.begin(), kEndEffectorComponentNames.end());
  const std::vector<std::string>& controlled = !options.controlled.empty() ? options.controlled
                                               : stored                    ? robot.end_effector.controlled
                                                                           : all_six;
  for (const std::string& name : controlled) {
    const auto it = std::find(kEndEffectorComponentNames.begin(), kEndEffectorComponentNames.end(), name);
    if (it == kEndEffectorComponentNames.end()) {
      Fail(robot, 0, "unknown controlled component " + Quote(name) + " (x, y, z, roll, pitch, yaw)");
    }
    bool& component = ee.controlled[it - kEndEffectorComponentNames.begin()];
    // As an actuated joint named twice: a repeated component is a typo, not a request.
    if (component) Fail(robot, 0, "controlled component " + Quote(name) + " given twice");
    component = true;
  }
  return !options.controlled.empty() ? RobotModel::Controlled::kGiven
         : stored                    ? RobotModel::Controlled::kStored
                                     : RobotModel::Controlled::kToChoose;
}

// Every body must reach the ground or a mobile base through joints.
void CheckConnected(const RobotDescription& robot, const Model& model) {
  const int n = model.num_bodies();
  std::vector<int> parent(n + 1);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  const auto node = [&](int body) { return body == kWorld ? n : body; };
  for (const Joint& joint : model.joints) parent[find(node(joint.body_a))] = find(node(joint.body_b));
  for (const MobileBase& base : model.mobile_bases) parent[find(base.body)] = find(n);
  for (int i = 0; i < n; ++i) {
    if (find(i) != find(n)) {
      const int link = robot.FindLink(model.bodies[i].name);
      Fail(robot, link >= 0 ? robot.links[link].line : 0,
           "link " + Quote(model.bodies[i].name) + " is connected to neither the ground nor a mobile base");
    }
  }
}

void AddJoints(const RobotDescription& robot, const std::vector<int>& motors, const std::map<std::string, int>& bodies,
               RobotModel* out) {
  Model& model = out->model;
  std::set<std::string> names;
  const auto add = [&](Joint joint, bool closure) {
    if (!names.insert(joint.name).second) {
      Fail(robot, joint.line, "joint " + Quote(joint.name) + ": its ccma name is taken by another joint");
    }
    model.joints.push_back(joint);
    out->closure.push_back(closure);
  };
  for (const int j : TreeOrder(robot, motors)) {
    Joint joint = TreeJoint(robot, robot.joints[j], model, bodies);
    const auto motor = std::find(motors.begin(), motors.end(), j);
    if (motor != motors.end()) {
      joint.actuated = true;
      joint.control = model.num_base_controls() + static_cast<int>(motor - motors.begin());
    }
    add(joint, false);
  }
  for (const RobotClosure& c : robot.closures) add(ClosureJoint(robot, c, model, bodies), true);
}

// Links, joints, closures and meshes within the bounds of
// formats/robot_description.h and ccma/limits.h, so that the model written
// fits the loader's size (refused here, naming the robot's file, rather than
// after assembling it).
void CheckSize(const RobotDescription& robot) {
  std::size_t meshes = 0;
  for (const RobotLink& link : robot.links) {
    meshes += link.meshes.size();
    if (link.meshes.size() > static_cast<std::size_t>(kMaxMeshesPerBody)) {
      Fail(robot, link.line, "link " + Quote(link.name) + ": more than " + std::to_string(kMaxMeshesPerBody) +
                                 " meshes");
    }
  }
  if (robot.links.size() > static_cast<std::size_t>(kMaxRobotLinks) ||
      robot.joints.size() > static_cast<std::size_t>(kMaxRobotJoints) ||
      robot.closures.size() > static_cast<std::size_t>(kMaxRobotClosures) ||
      meshes > static_cast<std::size_t>(kMaxMeshes)) {
    Fail(robot, 0, std::to_string(robot.links.size()) + " links, " + std::to_string(robot.joints.size()) +
                       " joints, " + std::to_string(robot.closures.size()) + " closures and " +
                       std::to_string(meshes) + " meshes: ccma imports at most " + std::to_string(kMaxRobotLinks) +
                       ", " + std::to_string(kMaxRobotJoints) + ", " + std::to_string(kMaxRobotClosures) + " and " +
                       std::to_string(kMaxMeshes));
  }
}

}  // namespace

std::string CcmaName(const std::string& name) {
  std::string out;
  for (const char c : name.substr(0, kMaxNameLength)) {
    out += std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ? c : '_';
  }
  return out.empty() ? "_" : out;
}

}  // namespace internal
}  // namespace ccma

namespace ccma {
namespace internal {

RobotModel BuildRobotModel(const RobotDescription& robot, const ImportOptions& options) {
  if (robot.links.empty()) Fail(robot, 0, "the robot has no links");
  CheckSize(robot);
  std::vector<int> bases, motors;
  SplitActuated(robot, options.actuated.empty() ? robot.actuated : options.actuated, &bases, &motors);
  if (bases.empty() && motors.empty()) {
    Fail(robot, 0, "no actuated joint: name the motors with --actuated=J1,J2,... (or name_mot in the closure file)");
  }
  RobotModel out;
  Model& model = out.model;
  model.name = options.model_name.empty() ? ImportedModelName(robot) : CcmaName(options.model_name);
  model.description = "Imported by ccma import from " + robot.source.substr(robot.source.find_last_of('/') + 1);
  if (robot.has_gravity) model.gravity = robot.gravity;
  std::map<std::string, int> bodies;
  AddBodies(robot, bases, &model, &bodies);
  AddJoints(robot, motors, bodies, &out);
  for (const int j : bases) out.actuated.push_back(CcmaName(robot.joints[j].name));
  for (const int j : motors) out.actuated.push_back(CcmaName(robot.joints[j].name));
  out.controlled = SetEndEffector(robot, options, bodies, &model);
  CheckConnected(robot, model);
  return out;
}

}  // namespace internal
}  // namespace ccma
