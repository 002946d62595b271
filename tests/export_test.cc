// `ccma export` (formats/urdf_writer.h, formats/sdformat_writer.h): every
// bundled model, a model with q_home, limits and reversed joints, and a model
// with rotated body frames, written as URDF + closure file and as SDFormat.
// The outputs are read with the field's own parsers (urdfdom, libsdformat
// 12), and the URDF's geometry is checked with a forward kinematics written
// here, independent of ccma's code: the closures hold at home to 1e-9, the
// body frames and joint axes are the model's, limits round-trip exactly.
// Imported again (`ccma import`), both give back the same mechanism.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <regex>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sdf/sdf.hh>
#include <urdf_parser/urdf_parser.h>
#include <yaml-cpp/yaml.h>

#include "analyses/robot_import.h"
#include "formats/model_loader.h"
#include "formats/sdformat_reader.h"
#include "formats/urdf_reader.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "formats/sdformat_writer.h"
#include "formats/urdf_writer.h"
#include "tests/bundled_models.h"
#include "tests/model_text.h"
#include "tests/tool_run.h"

namespace ccma {
namespace export_test {

constexpr double kTolerance = 1e-9;

// A four-bar on the ground driven at its crank, a U-P-S leg from the ground to
// its coupler and an actuated piston on the crank: q_home on revolute and
// prismatic joints (in the tree and cut), limits, joints whose `between` runs
// against the tree (coupler_crank, ground_leg: a universal, piston), a cut
// revolute (rocker_ground) and a cut spherical joint (leg_coupler).
const char* kLoopModel = R"(name: qhome_loop
bodies:
  - {name: crank, position: [0, 0, 0]}
  - {name: coupler, position: [0, 1, 0], rpy: [0.1, 0.2, 0.3]}
  - {name: rocker, position: [4, 2, 0]}
  - {name: leg_lower, position: [1, 1, 2]}
  - {name: leg_upper, position: [2, 1.5, 0], rpy: [0, 0.4, 0]}
  - {name: piston, position: [0, 0.5, 0.5]}
joints:
  - {name: crank_joint, type: revolute, actuated: true, q_home: 0.3, limits: [-1, 1], between: [world, crank],
     point: [0, 0, 0], axis: [0, 0, 1]}
  - {name: coupler_crank, type: revolute, q_home: -0.2, between: [coupler, crank], point: [0, 1, 0], axis: [0, 0, 1]}
  - {name: coupler_rocker, type: revolute, limits: [-0.5, 0.7], between: [coupler, rocker], point: [4, 2, 0],
     axis: [0, 0, 1]}
  - {name: rocker_ground, type: revolute, q_home: 0.1, between: [rocker, world], point: [4, 0, 0], axis: [0, 0, 1]}
  - {name: ground_leg, type: universal, between: [leg_lower, world], point: [1, 1, 2], axes: [[1, 0, 0], [0, 1, 0]]}
  - {name: slide, type: prismatic, q_home: 0.05, limits: [-0.1, 0.2], between: [leg_lower, leg_upper],
     point: [1.5, 1.25, 1], axis: [1, 0.5, -2]}
  - {name: leg_coupler, type: spherical, between: [leg_upper, coupler], point: [2, 1.5, 0]}
  - {name: piston, type: prismatic, actuated: true, q_home: -0.02, between: [piston, crank], point: [0, 0.5, 0.5],
     axis: [0, 0, 1]}
end_effector:
  body: coupler
  point: [2, 1.5, 0]
  controlled: [x, y, yaw]
)";

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  X.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z).toRotationMatrix();
  return X;
}

Eigen::Vector3d ToVector(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

// The forward kinematics of a URDF tree: every link's frame in the root's,
// each joint at q (0 when not given). Written from the URDF specification:
// child = parent * origin * motion(q about / along the axis in the child frame).
std::map<std::string, Eigen::Isometry3d> UrdfPoses(const urdf::ModelInterface& urdf,
                                                   const std::map<std::string, double>& q) {
  std::map<std::string, Eigen::Isometry3d> poses;
  std::vector<urdf::LinkConstSharedPtr> todo = {urdf.getRoot()};
  poses[urdf.getRoot()->name] = Eigen::Isometry3d::Identity();
  while (!todo.empty()) {
    const urdf::LinkConstSharedPtr link = todo.back();
    todo.pop_back();
    for (const urdf::JointSharedPtr& joint : link->child_joints) {
      const double value = q.count(joint->name) > 0 ? q.at(joint->name) : 0.0;
      const Eigen::Vector3d axis = ToVector(joint->axis);
      Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
      if (joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::CONTINUOUS) {
        motion.linear() = Eigen::AngleAxisd(value, axis).toRotationMatrix();
      } else if (joint->type == urdf::Joint::PRISMATIC) {
        motion.translation() = value * axis;
      }
      poses[joint->child_link_name] = poses[link->name] * ToIsometry(joint->parent_to_joint_origin_transform) * motion;
      todo.push_back(urdf.getLink(joint->child_link_name));
    }
  }
  return poses;
}

std::string Name(const Model& model, int body) { return body == kWorld ? "world" : model.bodies[body].name; }

Eigen::Isometry3d HomeFrame(const Model& model, int body) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (body == kWorld) return X;
  X.linear() = model.bodies[body].R_WB_home;
  X.translation() = model.bodies[body].p_WB_home;
  return X;
}

Eigen::Vector3d PointW(const Model& model, const Joint& joint) { return HomeFrame(model, joint.body_a) * joint.p_A; }
Eigen::Vector3d AxisW(const Model& model, const Joint& joint) {
  return HomeFrame(model, joint.body_a).linear() * joint.a_A;
}

// The link a closure frame names (a link, or a joint's child link).
std::string FrameLink(const urdf::ModelInterface& urdf, const std::string& frame) {
  if (urdf.getLink(frame)) return frame;
  const urdf::JointConstSharedPtr joint = urdf.getJoint(frame);
  return joint ? joint->child_link_name : "";
}

// The joint positions at home: q_home for every revolute and prismatic joint.
std::map<std::string, double> HomeCoordinates(const Model& model) {
  std::map<std::string, double> q;
  for (const Joint& joint : model.joints) {
    if (joint.has_coordinate()) q[joint.name] = joint.q_home;
  }
  return q;
}

struct ParsedUrdf {
  UrdfExport text;
  urdf::ModelInterfaceSharedPtr urdf;
  YAML::Node closures;
  std::map<std::string, Eigen::Isometry3d> home;  // link frames at home
};

ParsedUrdf ParseExport(const Model& model) {
  ParsedUrdf p;
  p.text = WriteUrdf(model);
  p.urdf = urdf::parseURDF(p.text.urdf);
  if (!p.urdf) return p;
  p.closures = YAML::Load(p.text.closures);
  // Home: the joint positions the closure file's q_home gives (0 where it
  // gives none), as another URDF reader would take them.
  std::map<std::string, double> q;
  for (const auto& entry : p.closures["q_home"]) q[entry.first.as<std::string>()] = entry.second.as<double>();
  p.home = UrdfPoses(*p.urdf, q);
  return p;
}

// The closure file's q_home lists exactly the joints whose q_home is not 0,
// with that value (17 digits: exactly).
void ExpectHomePositions(const ParsedUrdf& p, const Model& model) {
  std::map<std::string, double> written, expected;
  for (const auto& entry : p.closures["q_home"]) written[entry.first.as<std::string>()] = entry.second.as<double>();
  for (const auto& [name, q] : HomeCoordinates(model)) {
    if (q != 0) expected[name] = q;
  }
  EXPECT_EQ(written, expected);
}

// Every closure's two frames coincide at home (6d: whole frames; 3d: origins).
void ExpectClosuresHold(const ParsedUrdf& p, const std::string& what) {
  const YAML::Node pairs = p.closures["closed_loop"], types = p.closures["type"];
  ASSERT_EQ(pairs.size(), types.size()) << what;
  EXPECT_EQ(static_cast<int>(pairs.size()), p.text.loops) << what;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const std::string a = FrameLink(*p.urdf, pairs[i][0].as<std::string>());
    const std::string b = FrameLink(*p.urdf, pairs[i][1].as<std::string>());
    ASSERT_FALSE(a.empty() || b.empty()) << what << ": closure " << i;
    const Eigen::Isometry3d& X_A = p.home.at(a);
    const Eigen::Isometry3d& X_B = p.home.at(b);
    EXPECT_LT((X_A.translation() - X_B.translation()).norm(), kTolerance) << what << ": " << a << " " << b;
    if (types[i].as<std::string>() == "6d") {
      EXPECT_LT((X_A.linear() - X_B.linear()).norm(), kTolerance) << what << ": " << a << " " << b;
    } else {
      EXPECT_EQ(types[i].as<std::string>(), "3d") << what;
    }
  }
}

// The URDF joint of a model joint: in the tree (between the two bodies' links)
// or cut (A -> J_A, closed to J_B on B). Checks it, its axis and its limits.
// The body a link stands for: a joint frame link `B_joint_frame` (welded to
// B's link, which keeps B's frame) stands for B.
std::string Carrier(const std::string& link) {
  const std::string suffix = "_joint_frame";
  const bool frame = link.size() > suffix.size() && link.compare(link.size() - suffix.size(), suffix.size(), suffix) == 0;
  return frame ? link.substr(0, link.size() - suffix.size()) : link;
}

void ExpectJointKept(const ParsedUrdf& p, const Model& model, const Joint& joint, int* cut) {
  const std::string a = Name(model, joint.body_a), b = Name(model, joint.body_b);
  const urdf::JointConstSharedPtr u = p.urdf->getJoint(joint.name);
  const bool tree = u && ((u->parent_link_name == a && Carrier(u->child_link_name) == b) ||
                          (u->parent_link_name == b && Carrier(u->child_link_name) == a));
  if (!tree) {
    ++*cut;
    bool closed = false;
    const YAML::Node pairs = p.closures["closed_loop"];
    for (size_t i = 0; i < pairs.size(); ++i) {
      const urdf::JointConstSharedPtr weld_b = p.urdf->getJoint(pairs[i][1].as<std::string>());
      const std::string link_a = pairs[i][0].as<std::string>();
      const bool a_side = joint.type == JointType::kFixed || joint.type == JointType::kSpherical
                              ? p.urdf->getJoint(link_a) && p.urdf->getJoint(link_a)->parent_link_name == a
                              : u && u->parent_link_name == a && u->child_link_name == link_a;
      // J_A, or J_A_2, ... when the model already uses the name.
      const bool named = link_a == joint.name + "_A" || link_a.rfind(joint.name + "_A_", 0) == 0;
      closed = closed || (named && a_side && weld_b && weld_b->parent_link_name == b &&
                          p.closures["type"][i].as<std::string>() == (joint.type == JointType::kSpherical ? "3d" : "6d"));
    }
    EXPECT_TRUE(closed) << joint.name << " is neither a tree joint nor closed";
    if (joint.type == JointType::kFixed || joint.type == JointType::kSpherical) return;
  }
  ASSERT_TRUE(u) << joint.name;
  if (joint.has_coordinate()) {
    // The child link's origin is the joint point; its axis is the model's (sign: q keeps its sign).
    const Eigen::Isometry3d& X_WC = p.home.at(u->child_link_name);
    EXPECT_LT((X_WC.translation() - PointW(model, joint)).norm(), kTolerance) << joint.name;
    const double sign = u->parent_link_name == a ? 1.0 : -1.0;
    EXPECT_LT((X_WC.linear() * ToVector(u->axis) - sign * AxisW(model, joint)).norm(), kTolerance) << joint.name;
  }
  const bool prismatic = joint.type == JointType::kPrismatic;
  if (joint.limited) {
    EXPECT_EQ(u->type, prismatic ? urdf::Joint::PRISMATIC : urdf::Joint::REVOLUTE) << joint.name;
    EXPECT_EQ(u->limits->lower, joint.lower) << joint.name;
    EXPECT_EQ(u->limits->upper, joint.upper) << joint.name;
  } else if (joint.type == JointType::kRevolute) {
    EXPECT_EQ(u->type, urdf::Joint::CONTINUOUS) << joint.name;
  } else if (prismatic) {
    EXPECT_EQ(u->type, urdf::Joint::PRISMATIC) << joint.name;
    const std::regex unlimited("<joint name=\"" + joint.name + "\"[^]*?<limit effort=\"0\" velocity=\"0\"/>\\s*</joint>");
    EXPECT_TRUE(std::regex_search(p.text.urdf, unlimited)) << joint.name << ": a <limit> without lower/upper";
  }
}

void ExpectOverridesAndMotors(const ParsedUrdf& p, const Model& model) {
  std::map<std::string, std::string> overrides;
  if (p.closures["joint_name"]) {
    for (size_t i = 0; i < p.closures["joint_name"].size(); ++i) {
      overrides[p.closures["joint_name"][i].as<std::string>()] = p.closures["joint_type"][i].as<std::string>();
    }
  }
  std::vector<std::string> motors;
  for (const MobileBase& base : model.mobile_bases) {
    // A wheeled base hangs from world by a planar joint, a legged one by a
    // floating joint; either way its link is at its body frame at home.
    const Body& body = model.bodies[base.body];
    const urdf::JointConstSharedPtr from_world = p.urdf->getLink(body.name)->parent_joint;
    ASSERT_TRUE(from_world);
    EXPECT_EQ(from_world->parent_link_name, "world");
    EXPECT_LT((p.home.at(body.name).translation() - body.p_WB_home).norm(), kTolerance) << body.name;
    if (base.type == BaseType::kLegged) {
      EXPECT_EQ(from_world->type, urdf::Joint::FLOATING);
    } else {
      EXPECT_EQ(from_world->type, urdf::Joint::PLANAR);
      EXPECT_LT((ToVector(from_world->axis) - Eigen::Vector3d::UnitZ()).norm(), kTolerance);
    }
    motors.push_back(from_world->name);
  }
  for (const Joint& joint : model.joints) {
    if (joint.actuated) motors.push_back(joint.name);
    const bool replaced = joint.type == JointType::kSpherical || joint.type == JointType::kUniversal;
    if (!replaced) continue;
    const std::string expected = joint.type == JointType::kSpherical ? "SPHERICAL" : "UJOINT_XY";
    const bool cut_spherical = joint.type == JointType::kSpherical && !p.urdf->getJoint(joint.name);
    if (!cut_spherical) EXPECT_EQ(overrides[joint.name], expected) << joint.name;
  }
  EXPECT_EQ(p.closures["name_mot"].as<std::vector<std::string>>(), motors);
}

void ExpectEndEffector(const ParsedUrdf& p, const Model& model) {
  const YAML::Node ee = p.closures["end_effector"];
  ASSERT_TRUE(ee);
  const std::string link = ee["link"].as<std::string>();
  EXPECT_EQ(link, Name(model, model.end_effector.body));
  const std::vector<double> point = ee["point"].as<std::vector<double>>();
  const Eigen::Vector3d p_W = p.home.at(link) * Eigen::Vector3d(point[0], point[1], point[2]);
  EXPECT_LT((p_W - model.end_effector.p_W_home).norm(), kTolerance);
  std::vector<std::string> controlled;
  for (int c = 0; c < 6; ++c) {
    if (model.end_effector.controlled[c]) controlled.push_back(kEndEffectorComponentNames[c]);
  }
  EXPECT_EQ(ee["controlled"].as<std::vector<std::string>>(), controlled);
}

void CheckUrdf(const Model& model, const std::string& what) {
  SCOPED_TRACE(what);
  const ParsedUrdf p = ParseExport(model);
  ASSERT_TRUE(p.urdf) << "urdfdom rejects:\n" << p.text.urdf;
  EXPECT_EQ(p.urdf->getRoot()->name, "world");
  EXPECT_EQ(p.urdf->links_.size(), p.urdf->joints_.size() + 1);  // a tree
  EXPECT_EQ(static_cast<int>(p.urdf->links_.size()), p.text.links);
  EXPECT_EQ(static_cast<int>(p.urdf->joints_.size()), p.text.joints);
  EXPECT_EQ(p.home.size(), p.urdf->links_.size());  // every link reached from world
  for (int b = 0; b < model.num_bodies(); ++b) {
    const urdf::JointConstSharedPtr parent = p.urdf->getLink(model.bodies[b].name)->parent_joint;
    ASSERT_TRUE(parent) << model.bodies[b].name;
    const int j = model.FindJoint(parent->name);
    if (j >= 0 && model.joints[j].type == JointType::kUniversal) continue;  // frame along its axes
    EXPECT_LT((p.home.at(model.bodies[b].name).linear() - model.bodies[b].R_WB_home).norm(), kTolerance);
  }
  int cut = 0;
  for (const Joint& joint : model.joints) ExpectJointKept(p, model, joint, &cut);
  EXPECT_EQ(cut, p.text.loops);
  ExpectClosuresHold(p, what);
  ExpectOverridesAndMotors(p, model);
  ExpectEndEffector(p, model);
  ExpectHomePositions(p, model);
}

TEST(UrdfExport, EveryBundledModelIsAValidTreeWhoseClosuresHoldAtHome) {
  const std::vector<std::string> names = testing::BundledModels();
  ASSERT_GE(names.size(), 9u);
  for (const std::string& name : names) CheckUrdf(LoadModel(testing::ModelPath(name)), name);
}

TEST(UrdfExport, QHomeLimitsAndReversedJoints) {
  const Model model = LoadModelFromString(kLoopModel, "qhome_loop.yaml");
  CheckUrdf(model, "qhome_loop");
  const ParsedUrdf p = ParseExport(model);
  ASSERT_TRUE(p.urdf);
  // The tree keeps the first three revolutes, the universal, the slide and the
  // piston; the fourth revolute and the spherical joint close the loops.
  EXPECT_EQ(p.text.loops, 2);
  EXPECT_EQ(p.urdf->getJoint("coupler_crank")->parent_link_name, "crank");  // reversed
  EXPECT_EQ(p.urdf->getJoint("ground_leg")->parent_link_name, "world");     // reversed universal
  EXPECT_EQ(p.urdf->getJoint("piston")->parent_link_name, "crank");         // reversed prismatic
  EXPECT_EQ(p.urdf->getLink("leg_coupler_A")->parent_joint->parent_link_name, "leg_upper");  // cut spherical
  EXPECT_EQ(p.urdf->getJoint("rocker_ground")->child_link_name, "rocker_ground_A");  // cut, dummy link
  // At URDF's zero (every q = 0) the crank is turned back by q_home: the loop
  // is open there; the closure file's q_home closes it.
  const std::map<std::string, Eigen::Isometry3d> zero = UrdfPoses(*p.urdf, {});
  EXPECT_NEAR(Eigen::AngleAxisd(zero.at("crank").linear()).angle(), 0.3, 1e-12);
  EXPECT_EQ(p.closures["q_home"]["crank_joint"].as<double>(), 0.3);
  EXPECT_EQ(p.closures["q_home"]["slide"].as<double>(), 0.05);
}

TEST(UrdfExport, RotatedBodyFrames) {
  const std::string text = testing::WithBodyRpy(testing::Slurp(testing::ModelPath("6dof_asymmetric")),
                                                [](const std::string& body) {
                                                  const double k = static_cast<double>(body.size());
                                                  return Eigen::Vector3d(0.3 * k, -0.2, 0.1 * k);
                                                });
  CheckUrdf(LoadModelFromString(text, "rotated.yaml"), "6dof_asymmetric rotated");
}

TEST(UrdfExport, ClosureFileBesideTheUrdf) {
  EXPECT_EQ(ClosureFilePath("robot.urdf"), "robot.closures.yaml");
  EXPECT_EQ(ClosureFilePath("/a.b/robot.urdf"), "/a.b/robot.closures.yaml");
  EXPECT_EQ(ClosureFilePath("/a.b/robot"), "/a.b/robot.closures.yaml");
  EXPECT_EQ(ClosureFilePath("dir/.hidden"), "dir/.hidden.closures.yaml");
}


// ---------------------------------------------------------------- SDFormat --

Eigen::Isometry3d ToIsometry(const ignition::math::Pose3d& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pose.Pos().X(), pose.Pos().Y(), pose.Pos().Z());
  const ignition::math::Quaterniond& r = pose.Rot();
  X.linear() = Eigen::Quaterniond(r.W(), r.X(), r.Y(), r.Z()).toRotationMatrix();
  return X;
}

// A pose of `frame` resolved in the model frame (= world) by libsdformat.
Eigen::Isometry3d InModel(const sdf::SemanticPose& pose) {
  ignition::math::Pose3d resolved;
  const sdf::Errors errors = pose.Resolve(resolved, "__model__");
  EXPECT_TRUE(errors.empty()) << (errors.empty() ? "" : errors[0].Message());
  return ToIsometry(resolved);
}

double InitialPosition(const sdf::JointAxis& axis) {
  const sdf::ElementPtr element = axis.Element();
  return element->HasElement("initial_position") ? element->Get<double>("initial_position") : 0.0;
}

// SDFormat 1.7 gives links and joints one namespace: a joint named like a
// body is written as NAME_joint.
std::string SdfJointName(const Model& model, const Joint& joint) {
  return model.FindBody(joint.name) >= 0 ? joint.name + "_joint" : joint.name;
}

// A model joint in the SDFormat model: its ends, pose, axis, limits, q_home.
void ExpectSdfJoint(const sdf::Model& sdf_model, const Model& model, const Joint& joint) {
  const sdf::Joint* s = sdf_model.JointByName(SdfJointName(model, joint));
  ASSERT_NE(s, nullptr) << joint.name;
  const std::string a = Name(model, joint.body_a), b = Name(model, joint.body_b);
  const bool swapped = s->ParentLinkName() == b;
  EXPECT_EQ(s->ParentLinkName(), swapped ? b : a) << joint.name;
  EXPECT_EQ(s->ChildLinkName(), swapped ? a : b) << joint.name;
  EXPECT_LT((InModel(s->SemanticPose()).translation() - PointW(model, joint)).norm(), kTolerance) << joint.name;
  if (!joint.has_coordinate()) return;
  const sdf::JointAxis* axis = s->Axis(0);
  ASSERT_NE(axis, nullptr) << joint.name;
  ignition::math::Vector3d xyz;
  EXPECT_TRUE(axis->ResolveXyz(xyz, "__model__").empty());
  const Eigen::Vector3d axis_W = (swapped ? -1.0 : 1.0) * AxisW(model, joint);
  EXPECT_LT((Eigen::Vector3d(xyz.X(), xyz.Y(), xyz.Z()) - axis_W).norm(), kTolerance) << joint.name;
  EXPECT_EQ(InitialPosition(*axis), joint.q_home) << joint.name;
  if (joint.limited) {
    EXPECT_EQ(axis->Lower(), joint.lower) << joint.name;
    EXPECT_EQ(axis->Upper(), joint.upper) << joint.name;
  }
  if (joint.type == JointType::kRevolute) {
    EXPECT_EQ(s->Type(), joint.limited ? sdf::JointType::REVOLUTE : sdf::JointType::CONTINUOUS) << joint.name;
  }
}

void CheckSdf(const Model& model, const std::string& what) {
  SCOPED_TRACE(what);
  const SdformatExport e = WriteSdformat(model);
  sdf::Root root;
  // SDFormat has no planar or floating joint type: libsdformat flags each
  // base's joint (and nothing else); ccma's reader accepts both from world.
  int base_errors = 0;
  for (const sdf::Error& error : root.LoadSdfString(e.sdf)) {
    const bool base = error.Message().rfind("Joint type of planar is invalid", 0) == 0 ||
                      error.Message().rfind("Joint type of floating is invalid", 0) == 0;
    base_errors += base ? 1 : 0;
    EXPECT_TRUE(base) << "libsdformat: " << error.Message() << "\n" << e.sdf;
  }
  EXPECT_EQ(base_errors, model.num_bases());
  const sdf::Model* sdf_model = root.Model();
  ASSERT_NE(sdf_model, nullptr);
  EXPECT_EQ(static_cast<int>(sdf_model->LinkCount()), e.links);
  EXPECT_EQ(static_cast<int>(sdf_model->JointCount()), e.joints);
  EXPECT_EQ(e.links, model.num_bodies());
  EXPECT_EQ(e.joints, static_cast<int>(model.joints.size()) + model.num_bases());
  for (const Body& body : model.bodies) {
    const sdf::Link* link = sdf_model->LinkByName(body.name);
    ASSERT_NE(link, nullptr) << body.name;
    const Eigen::Isometry3d X = InModel(link->SemanticPose());
    EXPECT_LT((X.translation() - body.p_WB_home).norm(), kTolerance) << body.name;
    EXPECT_LT((X.linear() - body.R_WB_home).norm(), kTolerance) << body.name;
  }
  for (const Joint& joint : model.joints) ExpectSdfJoint(*sdf_model, model, joint);
  std::string actuated;
  for (const MobileBase& base : model.mobile_bases) {
    const bool legged = base.type == BaseType::kLegged;
    const std::string name = model.bodies[base.body].name + (legged ? "_floating" : "_planar");
    const sdf::Joint* s = sdf_model->JointByName(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_EQ(s->ParentLinkName(), "world");
    EXPECT_EQ(s->ChildLinkName(), model.bodies[base.body].name);
    EXPECT_EQ(s->Element()->Get<std::string>("type"), legged ? "floating" : "planar");
    const Eigen::Isometry3d X_WJ = InModel(s->SemanticPose());
    EXPECT_LT((X_WJ.translation() - model.bodies[base.body].p_WB_home).norm(), kTolerance);
    if (!legged) EXPECT_LT((X_WJ.linear().col(2) - Eigen::Vector3d::UnitZ()).norm(), kTolerance);  // the normal
  }
  for (const Joint& joint : model.joints) {
    if (joint.actuated) actuated += (actuated.empty() ? "" : " ") + SdfJointName(model, joint);
  }
  const sdf::ElementPtr element = sdf_model->Element();
  ASSERT_EQ(element->HasElement("ccma:actuated"), !actuated.empty());
  if (!actuated.empty()) {
    EXPECT_EQ(element->GetElement("ccma:actuated")->GetAttribute("joints")->GetAsString(), actuated);
  }
  ASSERT_TRUE(element->HasElement("ccma:end_effector"));
  EXPECT_EQ(element->GetElement("ccma:end_effector")->GetAttribute("link")->GetAsString(),
            Name(model, model.end_effector.body));
}

TEST(SdformatExport, EveryBundledModelLoadsInLibsdformat) {
  for (const std::string& name : testing::BundledModels()) CheckSdf(LoadModel(testing::ModelPath(name)), name);
}

TEST(SdformatExport, QHomeLimitsAndReversedJoints) {
  CheckSdf(LoadModelFromString(kLoopModel, "qhome_loop.yaml"), "qhome_loop");
}

TEST(SdformatExport, RotatedBodyFrames) {
  const std::string text = testing::WithBodyRpy(testing::Slurp(testing::ModelPath("stewart_gough_6ups")),
                                                [](const std::string& body) {
                                                  const double k = static_cast<double>(body.size());
                                                  return Eigen::Vector3d(-0.1 * k, 0.4, 0.2 * k);
                                                });
  CheckSdf(LoadModelFromString(text, "rotated.yaml"), "stewart_gough_6ups rotated");
}

TEST(UrdfExport, AddedNamesAvoidTheModelsOwn) {
  // A body called like the frame link the cut joint rocker_ground would get.
  std::string text = kLoopModel;
  for (const std::string& from : {std::string("{name: piston, position"), std::string("between: [piston, crank]")}) {
    text.replace(text.find(from), from.size(),
                 std::regex_replace(from, std::regex("piston"), "rocker_ground_A"));
  }
  const Model model = LoadModelFromString(text, "collision.yaml");
  ASSERT_GE(model.FindBody("rocker_ground_A"), 0);
  CheckUrdf(model, "collision");
  const ParsedUrdf p = ParseExport(model);
  ASSERT_TRUE(p.urdf);
  EXPECT_EQ(p.urdf->getJoint("rocker_ground")->child_link_name, "rocker_ground_A_2");
  EXPECT_EQ(p.urdf->getJoint("piston")->child_link_name, "rocker_ground_A");
  CheckSdf(model, "collision");
}

// ---------------------------------------------------------------- command ---

TEST(ExportCommand, WritesUrdfWithClosureFileAndSdf) {
  const std::string urdf_path = testing::ScratchPath("export", "robot.urdf");
  testing::ToolRun run = testing::RunTool({"export", "--model=" + testing::ModelPath("hybrid_ccma"), "--format=urdf",
                                           "--out=" + urdf_path});
  ASSERT_EQ(run.status, 0) << run.err;
  nlohmann::json json = nlohmann::json::parse(run.out);
  const std::string closures = testing::ScratchPath("export", "robot.closures.yaml");
  EXPECT_EQ(json["closures"], closures);
  EXPECT_EQ(json["format"], "urdf");
  const Model model = LoadModel(testing::ModelPath("hybrid_ccma"));
  const UrdfExport expected = WriteUrdf(model);
  EXPECT_EQ(testing::Slurp(urdf_path), expected.urdf);
  EXPECT_EQ(testing::Slurp(closures), expected.closures);
  EXPECT_EQ(json["links"], expected.links);
  EXPECT_EQ(json["joints"], expected.joints);
  EXPECT_EQ(json["loops"], 2);  // three legs on one end-effector
  const std::string sdf_path = testing::ScratchPath("export", "robot.sdf");
  run = testing::RunTool({"export", "--model=" + testing::ModelPath("hybrid_ccma"), "--format=sdf", "--out=" + sdf_path});
  ASSERT_EQ(run.status, 0) << run.err;
  json = nlohmann::json::parse(run.out);
  EXPECT_TRUE(json["closures"].is_null());
  EXPECT_EQ(json["loops"], 2);
  EXPECT_EQ(testing::Slurp(sdf_path), WriteSdformat(model).sdf);
}

// The closure file's name is made from --out, not given: a link planted
// there (to someone else's file) is replaced, never written through.
TEST(ExportCommand, ALinkPlantedAtTheClosureFileIsReplaced) {
  const std::string urdf_path = testing::ScratchPath("export_link", "robot.urdf");
  const std::string closures = testing::ScratchPath("export_link", "robot.closures.yaml");
  const std::string victim = testing::ScratchPath("export_link", "victim.txt");
  std::filesystem::remove(closures);
  std::ofstream(victim, std::ios::trunc) << "precious\n";
  std::filesystem::create_symlink(victim, closures);
  const testing::ToolRun run = testing::RunTool({"export", "--model=" + testing::ModelPath("hybrid_ccma"),
                                                 "--format=urdf", "--out=" + urdf_path});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(testing::Slurp(victim), "precious\n");
  EXPECT_TRUE(std::filesystem::is_regular_file(std::filesystem::symlink_status(closures)));
  EXPECT_EQ(testing::Slurp(closures), WriteUrdf(LoadModel(testing::ModelPath("hybrid_ccma"))).closures);
}

TEST(ExportCommand, BadInputExitsTwoWithNothingOnStdout) {
  const std::string out = testing::ScratchPath("export", "bad.urdf");
  const std::vector<std::vector<std::string>> cases = {
      {"export", "--model=" + testing::ModelPath("4dof_reduced"), "--format=step", "--out=" + out},
      {"export", "--model=" + testing::ModelPath("4dof_reduced"), "--out=" + out},
      {"export", "--model=" + testing::ModelPath("4dof_reduced"), "--format=urdf"},
      {"export", "--model=/nonexistent.yaml", "--format=sdf", "--out=" + out},
      {"export", "--model=" + testing::ModelPath("4dof_reduced"), "--format=urdf", "--out=" + ccma::testing::TestDir()}};
  for (const auto& args : cases) {
    const testing::ToolRun run = testing::RunTool(args);
    EXPECT_EQ(run.status, 2) << args[2] << " " << args.back();
    EXPECT_TRUE(run.out.empty()) << run.out;
    EXPECT_FALSE(run.err.empty());
  }
}

// MJCF closes a loop with an equality, which exists for a cut spherical,
// fixed or revolute joint only: a loop that only a prismatic joint closes
// is refused, naming it, and nothing is written.
TEST(ExportCommand, MjcfRefusesALoopOnlyAPrismaticJointCloses) {
  const std::string model = testing::ScratchPath("export", "two_slides.yaml");
  std::ofstream(model) << "name: two_slides\nbodies:\n  - {name: slider, position: [0, 0, 0.5]}\njoints:\n"
                          "  - {name: drive, type: prismatic, actuated: true, between: [world, slider], point: [0, 0, 0.5], "
                          "axis: [1, 0, 0]}\n"
                          "  - {name: guide, type: prismatic, between: [world, slider], point: [0, 0.2, 0.5], axis: [1, 0, 0]}\n"
                          "end_effector: {body: slider, point: [0, 0, 0.5], controlled: [x]}\n";
  const std::string out = testing::ScratchPath("export", "two_slides.xml");
  std::remove(out.c_str());
  const testing::ToolRun run = testing::RunTool({"export", "--model=" + model, "--format=mjcf", "--out=" + out});
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_NE(run.err.find("joint 'guide': a loop of this model can only be cut at this prismatic joint"), std::string::npos)
      << run.err;
  EXPECT_FALSE(std::ifstream(out).good());
  // The same model with the guide a revolute joint about x is written.
  std::string text = testing::Slurp(model);
  const std::string prismatic = "{name: guide, type: prismatic";
  text.replace(text.find(prismatic), prismatic.size(), "{name: guide, type: revolute");
  std::ofstream(model) << text;
  EXPECT_EQ(testing::RunTool({"export", "--model=" + model, "--format=mjcf", "--out=" + out}).status, 0);
}

// ------------------------------------------------------------- round trip ---
// export -> import (analyses/robot_import.h, with the end-effector that the
// export stored) gives back the same mechanism: the same end-effector pose
// at the same controls, at home and at seeded controls near home.

// Home, then seeded controls near home that the original assembles: its
// effective controls moved by up to 0.03 (m or rad) when it assembles there,
// else (most CCMAs: their bases are tied together by the chain) the controls
// its controller finds for an end-effector target moved as much.
std::vector<Eigen::VectorXd> SeededControls(const Model& model, unsigned seed) {
  std::vector<Eigen::VectorXd> controls = {model.home_controls()};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-0.03, 0.03);
  const EndEffectorPose home = ComputeEndEffectorPose(model, State::Home(model));
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd u = model.home_controls();
    for (int i : model.effective_control_indices()) u[i] += offset(rng);
    ForwardProblem forward(model);
    if (forward.Assemble(u).assembled) {
      controls.push_back(u);
      continue;
    }
    ControlProblem control(model);
    PoseTarget target;
    target.position = home.position + Eigen::Vector3d{offset(rng), offset(rng), offset(rng)};
    target.rpy = home.rpy + Eigen::Vector3d{offset(rng), offset(rng), offset(rng)};
    EXPECT_TRUE(control.MoveTo(target).assembled) << model.name << " target " << k;
    controls.push_back(control.controls());
  }
  return controls;
}

// R_EE is the end-effector body's rotation since home: the imported
// rotations are compared relative to the imported model assembled at the
// original's home controls (the identity when the homes are the same, as
// both exports keep them).
void ExpectSameMechanism(const Model& original, const Model& imported, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(imported.num_controls(), original.num_controls());
  ForwardProblem reference(imported);
  ASSERT_TRUE(reference.Assemble(original.home_controls()).assembled);
  const Eigen::Matrix3d R_home = reference.end_effector().rotation;
  for (const Eigen::VectorXd& u : SeededControls(original, 7)) {
    ForwardProblem a(original), b(imported);
    const ForwardResult ra = a.Assemble(u), rb = b.Assemble(u);
    ASSERT_TRUE(ra.assembled && rb.assembled) << ra.residual_energy << " " << rb.residual_energy;
    const EndEffectorPose pa = a.end_effector(), pb = b.end_effector();
    EXPECT_LT((pa.position - pb.position).norm(), kTolerance) << u.transpose();
    EXPECT_LT((pa.rotation - pb.rotation * R_home.transpose()).norm(), kTolerance) << u.transpose();
  }
}

// The same home controls: a base's heading is read back from its link's
// rotation, in (-pi, pi], so headings compare modulo 2 pi.
void ExpectSameHomeControls(const Model& original, const Model& imported, const std::string& what) {
  const Eigen::VectorXd a = original.home_controls(), b = imported.home_controls();
  ASSERT_EQ(a.size(), b.size()) << what;
  Eigen::VectorXd difference = a - b;
  for (int k = 0; k < original.num_bases(); ++k) {
    const int heading = original.base_control(k) + kBaseHeading;
    difference[heading] = std::remainder(difference[heading], 2 * M_PI);
  }
  EXPECT_LT(difference.norm(), 1e-12) << what;
}

Model ImportUrdfExport(const Model& model) {
  const UrdfExport e = WriteUrdf(model);
  const std::string urdf_path = testing::ScratchPath("export_round_trip", model.name + ".urdf");
  const std::string closure_path = ClosureFilePath(urdf_path);
  std::ofstream(urdf_path) << e.urdf;
  std::ofstream(closure_path) << e.closures;
  return ImportRobot(ReadUrdf(urdf_path, closure_path), ImportOptions{}).model;
}

// The import has the model's bodies, no more (the URDF's frame links are
// fused back: closure file `frames`), each at its home pose, and as many joints.
void ExpectSameBodies(const Model& original, const Model& imported, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(imported.num_bodies(), original.num_bodies());
  EXPECT_EQ(imported.joints.size(), original.joints.size());
  for (const Body& body : original.bodies) {
    const int b = imported.FindBody(body.name);
    ASSERT_GE(b, 0) << body.name;
    EXPECT_LT((imported.bodies[b].p_WB_home - body.p_WB_home).norm(), kTolerance) << body.name;
    EXPECT_LT((imported.bodies[b].R_WB_home - body.R_WB_home).norm(), kTolerance) << body.name;
  }
}

TEST(ExportRoundTrip, UrdfGivesBackTheSameMechanism) {
  for (const std::string& name : testing::BundledModels()) {
    const Model model = LoadModel(testing::ModelPath(name));
    const Model imported = ImportUrdfExport(model);
    ExpectSameBodies(model, imported, name);
    ExpectSameHomeControls(model, imported, name);
    ExpectSameMechanism(model, imported, name + " (urdf)");
  }
  const Model loop = LoadModelFromString(kLoopModel, "qhome_loop.yaml");
  const Model imported = ImportUrdfExport(loop);
  ExpectSameBodies(loop, imported, "qhome_loop");
  // Every revolute and prismatic joint keeps its name, the cut ones too.
  for (const Joint& joint : loop.joints) {
    if (joint.has_coordinate()) EXPECT_GE(imported.FindJoint(joint.name), 0) << joint.name;
  }
  // The closure file's q_home puts the links at home: the same home controls
  // (crank_joint's q_home is 0.3), every joint with its coordinate.
  EXPECT_LT((imported.home_controls() - loop.home_controls()).norm(), 1e-12);
  for (const Joint& joint : loop.joints) {
    if (!joint.has_coordinate()) continue;
    const int j = imported.FindJoint(joint.name);
    ASSERT_GE(j, 0) << joint.name;
    EXPECT_NEAR(imported.joints[j].q_home, joint.q_home, 1e-12) << joint.name;
  }
  ExpectSameMechanism(loop, imported, "qhome_loop (urdf)");
}

// The SDFormat export, read back with no --actuated: the reader takes the
// actuated joints the file names (<ccma:actuated>, the model's control order).
Model ImportSdformatExport(const Model& model) {
  const SdformatExport e = WriteSdformat(model);
  const std::string path = testing::ScratchPath("export_round_trip", model.name + ".sdf");
  std::ofstream(path) << e.sdf;
  return ImportRobot(ReadSdformat(path, {}), ImportOptions{}).model;
}

// Every body's link keeps the body's frame: naming the end-effector by its
// body and its point in that body's frame (what a user of the original model
// knows) gives back the same mechanism, through URDF and SDFormat.
TEST(ExportRoundTrip, EndEffectorNamedByBodyAndPointInItsFrame) {
  for (const std::string& name : testing::BundledModels()) {
    const Model model = LoadModel(testing::ModelPath(name));
    ImportOptions options;
    options.end_effector_link = model.bodies[model.end_effector.body].name;
    options.end_effector_point_L = model.end_effector.p_B;
    for (int c = 0; c < 6; ++c) {
      if (model.end_effector.controlled[c]) options.controlled.push_back(kEndEffectorComponentNames[c]);
    }
    const UrdfExport urdf = WriteUrdf(model);
    const std::string urdf_path = testing::ScratchPath("export_body_frames", name + ".urdf");
    std::ofstream(urdf_path) << urdf.urdf;
    std::ofstream(ClosureFilePath(urdf_path)) << urdf.closures;
    ExpectSameMechanism(model, ImportRobot(ReadUrdf(urdf_path, ClosureFilePath(urdf_path)), options).model,
                        name + " (urdf, end-effector by body)");
    const std::string sdf_path = testing::ScratchPath("export_body_frames", name + ".sdf");
    std::ofstream(sdf_path) << WriteSdformat(model).sdf;
    ExpectSameMechanism(model, ImportRobot(ReadSdformat(sdf_path, {}), options).model,
                        name + " (sdf, end-effector by body)");
  }
}

TEST(ExportRoundTrip, SdformatGivesBackTheSameMechanism) {
  for (const std::string& name : testing::BundledModels()) {
    const Model model = LoadModel(testing::ModelPath(name));
    const Model imported = ImportSdformatExport(model);
    ExpectSameHomeControls(model, imported, name);
    ExpectSameMechanism(model, imported, name + " (sdf)");
  }
  const Model loop = LoadModelFromString(kLoopModel, "qhome_loop.yaml");
  const Model imported = ImportSdformatExport(loop);
  // SDFormat keeps the home (initial_position = q_home): the same home controls.
  EXPECT_LT((imported.home_controls() - loop.home_controls()).norm(), 1e-12);
  ExpectSameMechanism(loop, imported, "qhome_loop (sdf)");
}

TEST(ExportRoundTrip, ImportCommandReadsTheStoredEndEffector) {
  const std::string urdf_path = testing::ScratchPath("export_cli_round_trip", "hybrid.urdf");
  const std::string model_path = testing::ScratchPath("export_cli_round_trip", "hybrid.yaml");
  ASSERT_EQ(testing::RunTool({"export", "--model=" + testing::ModelPath("hybrid_ccma"), "--format=urdf",
                              "--out=" + urdf_path}).status, 0);
  const testing::ToolRun run = testing::RunTool({"import", "--from=" + urdf_path, "--closures=" +
                                                 ClosureFilePath(urdf_path), "--out=" + model_path});
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["actuated"], nlohmann::json({"base0_planar", "base1_planar", "base2_planar", "shoulder0"}));
  const Model imported = LoadModel(model_path);
  const Model original = LoadModel(testing::ModelPath("hybrid_ccma"));
  EXPECT_EQ(imported.end_effector.controlled, original.end_effector.controlled);
  EXPECT_LT((imported.end_effector.p_W_home - original.end_effector.p_W_home).norm(), kTolerance);
  EXPECT_LT((imported.home_controls() - original.home_controls()).norm(), 1e-12);
}

}  // namespace
}  // namespace ccma
