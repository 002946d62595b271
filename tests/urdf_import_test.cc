// `ccma import` on real robots (models/robots/example-parallel-robots, from
// LAAS-CNRS/INRIA, BSD-3-Clause): each imports, is assembled, its closures
// hold, an independent forward kinematics through the URDF tree with the
// reported q reproduces every body pose, the motors move it, control
// reaches an end-effector target, and the controlled components are those
// the motors move. Plus the errors a user can make.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include "analyses/mobility.h"
#include "analyses/robot_import.h"
#include "ccma/joint_coordinates.h"
#include "formats/closure_file.h"
#include "formats/model_loader.h"
#include "formats/sdformat_reader.h"
#include "formats/urdf_reader.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"

namespace ccma {
namespace urdf_import_test {

const std::string kRobots = std::string(CCMA_MODELS_DIR) + "/robots/example-parallel-robots/";

struct Robot {
  std::string folder, end_effector;
  std::vector<std::string> moved;  // the components the motors move at home, as import chooses them
};
// gtest (and CTest's test names) show a robot by its folder.
void PrintTo(const Robot& robot, std::ostream* os) { *os << robot.folder; }
// battobot_6d replaces joints by universal and spherical ones (joint_name /
// joint_type) and has a link named 'toe_a_2/2'; 5bar_linkage_iso3d closes
// its loop with a 3d closure. The five-bar and the delta (two motors each)
// move in the world's y-z plane, 5bar_linkage_iso3d in x-z; cassie_like's
// five motors move the foot in all but yaw; battobot_6d's twelve, all six.
const Robot kCopied[] = {{"5bar_linkage", "effector", {"y", "z"}},
                         {"robot_delta", "eff", {"y", "z"}},
                         {"cassie_like", "foot", {"x", "y", "z", "roll", "pitch"}},
                         {"5bar_linkage_iso3d", "effector", {"x", "z"}},
                         {"battobot_6d", "foot_left", {"x", "y", "z", "roll", "pitch", "yaw"}}};

// The ccma name of a URDF name (docs/import.md): other characters than
// [A-Za-z0-9_-] become '_'.
std::string CcmaName(std::string name) {
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
  }
  return name;
}

ImportedRobot Import(const Robot& robot) {
  const RobotDescription description =
      ReadUrdf(kRobots + robot.folder + "/robot.urdf", kRobots + robot.folder + "/robot.yaml");
  ImportOptions options;
  options.end_effector_link = robot.end_effector;
  return ImportRobot(description, options);
}

// ---- An independent forward kinematics: urdfdom's tree, a few lines of Eigen ----
Eigen::Isometry3d Origin(const urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z).toRotationMatrix();
  X.translation() << pose.position.x, pose.position.y, pose.position.z;
  return X;
}

// Every link's pose with joint positions q(name); the root at the identity.
// A joint without a q (made spherical or universal by the closure file) takes
// its child's rotation from `R_child` (its point is still checked).
std::map<std::string, Eigen::Isometry3d> UrdfFk(
    const urdf::ModelInterface& urdf, const std::function<const double*(const std::string&)>& q,
    const std::function<Eigen::Matrix3d(const std::string&)>& R_child) {
  std::map<std::string, Eigen::Isometry3d> X;
  std::vector<urdf::LinkConstSharedPtr> pending = {urdf.getRoot()};
  X[urdf.getRoot()->name] = Eigen::Isometry3d::Identity();
  while (!pending.empty()) {
    const urdf::LinkConstSharedPtr link = pending.back();
    pending.pop_back();
    for (const urdf::JointSharedPtr& j : link->child_joints) {
      const Eigen::Vector3d axis = Eigen::Vector3d(j->axis.x, j->axis.y, j->axis.z).normalized();
      Eigen::Isometry3d X_child = X[link->name] * Origin(j->parent_to_joint_origin_transform);
      const double* value = q(j->name);
      if (j->type != urdf::Joint::FIXED && value == nullptr) {
        X_child.linear() = R_child(j->child_link_name);
      } else if (j->type == urdf::Joint::REVOLUTE || j->type == urdf::Joint::CONTINUOUS) {
        X_child.linear() = X_child.linear() * Eigen::AngleAxisd(*value, axis).toRotationMatrix();
      } else if (j->type == urdf::Joint::PRISMATIC) {
        X_child.translation() += X_child.linear() * (*value * axis);
      }
      X[j->child_link_name] = X_child;
      pending.push_back(urdf.getLink(j->child_link_name));
    }
  }
  return X;
}

urdf::ModelInterfaceSharedPtr ParseUrdfFile(const std::string& path) {
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return urdf::parseURDF(text);
}

// Body poses at s against the FK with the q ccma reports at s, to 1e-9.
void ExpectFkMatches(const Model& model, const State& s, const urdf::ModelInterface& urdf) {
  std::map<std::string, double> q;
  for (const JointCoordinateReport& r : JointCoordinates(model, s)) q[model.joints[r.joint].name] = r.q;
  const auto X = UrdfFk(
      urdf,
      [&](const std::string& name) -> const double* {
        const auto it = q.find(CcmaName(name));
        return it == q.end() ? nullptr : &it->second;
      },
      [&](const std::string& link) { return s.R_WB(model.FindBody(CcmaName(link))); });
  int checked = 0;
  for (const auto& [link, X_WL] : X) {
    const int b = model.FindBody(CcmaName(link));
    ASSERT_GE(b, 0) << link;
    EXPECT_LT((s.p_WB(b) - X_WL.translation()).norm(), 1e-9) << link;
    EXPECT_LT((s.R_WB(b) - X_WL.linear()).norm(), 1e-9) << link;
    ++checked;
  }
  EXPECT_EQ(checked, model.num_bodies());
}

// The frames of every closure (links here) coincide at s, to 1e-9: their
// origins (3d, a spherical joint), and their orientations too (6d, fixed).
void ExpectClosuresHold(const Model& model, const State& s) {
  int closures = 0;
  for (const Joint& joint : model.joints) {
    if (joint.name.find("__") == std::string::npos || joint.body_a == kWorld) continue;
    ++closures;
    EXPECT_LT((s.p_WB(joint.body_a) - s.p_WB(joint.body_b)).norm(), 1e-9) << joint.name;
    if (joint.type == JointType::kFixed) {
      EXPECT_LT((s.R_WB(joint.body_a) - s.R_WB(joint.body_b)).norm(), 1e-9) << joint.name;
    }
  }
  EXPECT_GT(closures, 0);
}

class CopiedRobot : public ::testing::TestWithParam<Robot> {};

TEST_P(CopiedRobot, ImportsAssembledAndMatchesItsUrdfTree) {
  const ImportedRobot imported = Import(GetParam());
  const urdf::ModelInterfaceSharedPtr urdf = ParseUrdfFile(kRobots + GetParam().folder + "/robot.urdf");
  ASSERT_TRUE(urdf);
  EXPECT_LT(imported.residual_energy, 1e-24);
  // Every revolute and prismatic joint carries q_home in the written file.
  int coordinates = 0;
  for (const Joint& joint : imported.model.joints) coordinates += joint.has_coordinate();
  std::size_t written = 0;
  for (std::size_t at = imported.yaml.find("q_home:"); at != std::string::npos; at = imported.yaml.find("q_home:", at + 1)) {
    ++written;
  }
  EXPECT_EQ(written, static_cast<std::size_t>(coordinates));
  EXPECT_EQ(imported.model.num_controls(), static_cast<int>(imported.actuated.size()));
  // Motors at the source's zero: the home controls are 0.
  EXPECT_LT(imported.model.home_controls().cwiseAbs().maxCoeff(), 1e-12);
  const State home = State::Home(imported.model);
  ExpectClosuresHold(imported.model, home);
  ExpectFkMatches(imported.model, home, *urdf);
}

TEST_P(CopiedRobot, MotorsMoveItAndTheTreeStillMatches) {
  const ImportedRobot imported = Import(GetParam());
  const urdf::ModelInterfaceSharedPtr urdf = ParseUrdfFile(kRobots + GetParam().folder + "/robot.urdf");
  ForwardProblem problem(imported.model);
  const EndEffectorPose before = problem.end_effector();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> delta(-0.08, 0.08);
  Eigen::VectorXd u = imported.model.home_controls();
  for (int i = 0; i < u.size(); ++i) u[i] += delta(random);
  const ForwardResult result = problem.Assemble(u);
  ASSERT_TRUE(result.assembled) << result.message;
  EXPECT_FALSE(result.branch_jump);
  EXPECT_GT((problem.end_effector().position - before.position).norm(), 1e-4);
  ExpectClosuresHold(imported.model, problem.state());
  ExpectFkMatches(imported.model, problem.state(), *urdf);
  // An actuated joint's q is its control.
  for (const JointCoordinateReport& r : JointCoordinates(imported.model, problem.state())) {
    const Joint& joint = imported.model.joints[r.joint];
    if (joint.actuated) EXPECT_NEAR(r.q, u[joint.control], 1e-9) << joint.name;
  }
}

TEST_P(CopiedRobot, ControlReachesAnEndEffectorTarget) {
  const ImportedRobot imported = Import(GetParam());
  // A reachable target: where seeded motor moves put the end-effector.
  ForwardProblem forward(imported.model);
  Eigen::VectorXd u = imported.model.home_controls();
  std::mt19937 random(11);
  std::uniform_real_distribution<double> delta(-0.05, 0.05);
  for (int i = 0; i < u.size(); ++i) u[i] += delta(random);
  ASSERT_TRUE(forward.Assemble(u).assembled);
  const Eigen::Vector3d target = forward.end_effector().position;
  ControlProblem control(imported.model);
  PoseTarget goal;
  goal.position = target;
  const ControlResult result = control.MoveTo(goal);
  EXPECT_TRUE(result.converged) << result.warning;
  EXPECT_LT((control.forward().end_effector().position - target).norm(), 1e-6);
}

// Without controlled components, import chooses those the motors move at
// home (translations first), and `ccma check`'s analysis counts exactly that
// many end-effector DOF: every target of that many components is reachable
// to first order.
TEST_P(CopiedRobot, ControlsTheComponentsTheMotorsMove) {
  const ImportedRobot imported = Import(GetParam());
  EXPECT_TRUE(imported.controlled_chosen);
  EXPECT_EQ(imported.controlled, GetParam().moved);
  std::vector<std::string> in_model;
  for (int c = 0; c < 6; ++c) {
    if (imported.model.end_effector.controlled[c]) in_model.push_back(kEndEffectorComponentNames[c]);
  }
  EXPECT_EQ(in_model, GetParam().moved);
  const Model& m = imported.model;
  const MobilityReport mobility = AnalyzeMobility(m, State::Home(m), m.home_controls());
  EXPECT_EQ(mobility.end_effector_dof, static_cast<int>(GetParam().moved.size()));
  // Given, the same components are kept; one more is refused, naming those.
  ImportOptions options;
  options.end_effector_link = GetParam().end_effector;
  options.controlled = GetParam().moved;
  const RobotDescription description = ReadUrdf(kRobots + GetParam().folder + "/robot.urdf",
                                                kRobots + GetParam().folder + "/robot.yaml");
  const ImportedRobot given = ImportRobot(description, options);
  EXPECT_FALSE(given.controlled_chosen);
  EXPECT_EQ(given.controlled, GetParam().moved);
  if (GetParam().moved.size() == 6) return;
  for (const char* extra : {"x", "y", "z", "roll", "pitch", "yaw"}) {
    if (std::count(options.controlled.begin(), options.controlled.end(), extra) == 0) {
      options.controlled.push_back(extra);
      break;
    }
  }
  std::string moved;
  for (const std::string& c : GetParam().moved) moved += (moved.empty() ? "" : " ") + c;
  try {
    ImportRobot(description, options);
    FAIL() << "accepted components the motors cannot move";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("independently at home (rank " + std::to_string(GetParam().moved.size()) +
                                         " of " + std::to_string(options.controlled.size()) + "): they move " +
                                         std::to_string(GetParam().moved.size()) +
                                         " end-effector DOF, for example " + moved + " "),
              std::string::npos)
        << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(ExampleParallelRobots, CopiedRobot, ::testing::ValuesIn(kCopied),
                         [](const auto& info) { return info.param.folder; });

}  // namespace
}  // namespace ccma

namespace ccma {
namespace urdf_import_test {

// ---- The closure file's q_home (ccma's own key, written by `ccma export`) ----

// world -j1 (revolute about z at (1,0,0), origin turned 0.3 about z)-> a
// -j2 (prismatic along a's x, at (0,2,0) in a)-> b -j3 (fixed, (0,0,1) in b)-> c.
const char* kChain = R"(<robot name="chain">
  <link name="world"/><link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="continuous"><parent link="world"/><child link="a"/>
    <origin xyz="1 0 0" rpy="0 0 0.3"/><axis xyz="0 0 1"/></joint>
  <joint name="j2" type="prismatic"><parent link="a"/><child link="b"/>
    <origin xyz="0 2 0"/><axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="0" velocity="0"/></joint>
  <joint name="j3" type="fixed"><parent link="b"/><child link="c"/><origin xyz="0 0 1"/></joint>
</robot>)";

RobotDescription ChainWith(const std::string& closures) {
  RobotDescription robot = ReadUrdfFromString(kChain, "chain.urdf");
  ApplyClosureFile(ParseClosureFile(closures, "chain.yaml"), &robot);
  return robot;
}

const RobotLink& LinkOf(const RobotDescription& robot, const std::string& name) {
  return robot.links[robot.FindLink(name)];
}

TEST(ClosureFileQHome, LinksAreReadAtTheGivenJointPositions) {
  const RobotDescription robot = ChainWith("name_mot: ['j1']\nq_home: {'j1': 0.5, 'j2': 0.25}\n");
  // Closed form: a turned 0.3 + 0.5 about z at (1,0,0); b shifted 0.25 along a's x.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d p_a(1, 0, 0), p_b = p_a + R * Eigen::Vector3d(0.25, 2, 0);
  EXPECT_LT((LinkOf(robot, "a").X_WL.translation() - p_a).norm(), 1e-15);
  EXPECT_LT((LinkOf(robot, "a").X_WL.linear() - R).norm(), 1e-15);
  EXPECT_LT((LinkOf(robot, "b").X_WL.translation() - p_b).norm(), 1e-15);
  EXPECT_LT((LinkOf(robot, "c").X_WL.translation() - (p_b + Eigen::Vector3d(0, 0, 1))).norm(), 1e-15);
  EXPECT_LT((LinkOf(robot, "c").X_WL.linear() - R).norm(), 1e-15);
  const RobotJoint& j2 = robot.joints[robot.FindJoint("j2")];
  EXPECT_EQ(j2.position, 0.25);
  EXPECT_LT((j2.axis_W - R.col(0)).norm(), 1e-15);
  // Imported (and written and read back: rounding to 1e-15), the joints read
  // those positions at home and motor j1's control is 0.5.
  ImportOptions options;
  options.end_effector_link = "c";
  const ImportedRobot imported = ImportRobot(robot, options);
  EXPECT_EQ(imported.model.home_controls(), Eigen::VectorXd::Constant(1, 0.5));
  const State home = State::Home(imported.model);
  for (const JointCoordinateReport& r : JointCoordinates(imported.model, home)) {
    const std::string& name = imported.model.joints[r.joint].name;
    EXPECT_NEAR(r.q, name == "j1" ? 0.5 : 0.25, 1e-12) << name;
  }
  EXPECT_LT((home.p_WB(imported.model.FindBody("c")) - (p_b + Eigen::Vector3d(0, 0, 1))).norm(), 1e-12);
}

void ExpectRefused(const std::string& closures, const std::string& message) {
  try {
    ChainWith(closures);
    ADD_FAILURE() << "accepted: " << closures;
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

// ---- The closure file's frames (ccma's own key, written by `ccma export`) ----

// c, welded to b by the fixed j3, is a frame: it is fused into b, j3 goes,
// and a closure that named c names b, at the same world frames.
TEST(ClosureFileFrames, AFrameLinkIsFusedIntoTheBodyItIsWeldedTo) {
  const RobotDescription robot = ChainWith("closed_loop: [['c', 'a']]\ntype: ['3d']\nframes: ['c']\n");
  EXPECT_LT(robot.FindLink("c"), 0);
  EXPECT_LT(robot.FindJoint("j3"), 0);
  ASSERT_EQ(robot.links.size(), 2u);  // a, b
  ASSERT_EQ(robot.closures.size(), 1u);
  EXPECT_EQ(robot.closures[0].link_a, "b");
  // The closure's frame A is still c's frame: b's origin raised by 1 along z.
  EXPECT_LT((robot.closures[0].X_WA.translation() - (LinkOf(robot, "b").X_WL.translation() +
                                                      Eigen::Vector3d(0, 0, 1))).norm(), 1e-15);
  // The same chain without `frames` keeps c and j3: the key is what fuses.
  const RobotDescription kept = ChainWith("closed_loop: [['c', 'a']]\ntype: ['3d']\n");
  EXPECT_GE(kept.FindLink("c"), 0);
  EXPECT_GE(kept.FindJoint("j3"), 0);
}

TEST(ClosureFileFrames, HostileEntriesAreRefusedWithFileLineAndLink) {
  ExpectRefused("frames: ['nope']\n", "chain.yaml:1: frames: 'nope' is not a link of chain.urdf");
  ExpectRefused("frames: ['world']\n", "chain.yaml:1: frames: 'world' is not a link of chain.urdf");
  ExpectRefused("frames: ['a']\n", "chain.yaml:1: frames: link 'a' is welded (by a fixed joint or a 6d closure) to no body");
  ExpectRefused("frames: ['b', 'c']\n", "frames: link 'b' is welded (by a fixed joint or a 6d closure) to no body");
  ExpectRefused("frames: 'c'\n", "chain.yaml:1: frames: must be a list");
}

TEST(ClosureFileQHome, HostileEntriesAreRefusedWithFileLineAndJoint) {
  ExpectRefused("q_home: {'nope': 1}\n", "chain.yaml:1: q_home: unknown joint 'nope' (not a joint of chain.urdf)");
  ExpectRefused("name_mot: ['j1']\nq_home: {'j3': 1}\n", "chain.yaml:2: q_home: joint 'j3' is not revolute or prismatic");
  ExpectRefused("q_home: {'j1': abc}\n", "chain.yaml:1: q_home['j1']: must be a number, got 'abc'");
  ExpectRefused("q_home: {'j1': .nan}\n", "q_home['j1']: must be a finite number");
  ExpectRefused("q_home: {'j1': 1e5}\n", "must lie in [-10000, 10000] (rad or m)");
  ExpectRefused("q_home: [1, 2]\n", "chain.yaml:1: q_home: must be a mapping");
  ExpectRefused("q_home: {'j1': 1, 'j1': 2}\n", "chain.yaml:1");  // a repeated key
  ExpectRefused("q_home: {'sh\x1b[31m': 1}\n", "must be a name of at most");
  // Within the file's rules but outside the joint's limits: import refuses it.
  RobotDescription robot = ChainWith("name_mot: ['j1']\nq_home: {'j2': 1.5}\n");
  ImportOptions options;
  options.end_effector_link = "c";
  try {
    ImportRobot(robot, options);
    ADD_FAILURE() << "accepted j2 at 1.5";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'j2': its position at home, 1.5, is outside its limits"),
              std::string::npos)
        << e.what();
  }
}

// ---- The imported model's name (docs/import.md, "Model name") ----

std::string ImportedName(const std::string& robot_name, const std::string& path) {
  std::string text = kChain;
  text.replace(text.find("\"chain\""), 7, "\"" + robot_name + "\"");
  RobotDescription robot = ReadUrdfFromString(text, path);
  ApplyClosureFile(ParseClosureFile("name_mot: ['j1']\n", "chain.yaml"), &robot);
  ImportOptions options;
  options.end_effector_link = "c";
  return ImportRobot(robot, options).model.name;  // loaded back from the written file
}

TEST(ImportedModelName, TheFilesRobotNameElseItsStemElseItsFolder) {
  EXPECT_EQ(ImportedName("chain", "robots/arm/robot.urdf"), "chain");
  EXPECT_EQ(ImportedName("Onshape", "robots/arm/my_arm.urdf"), "my_arm");  // an exporter's name
  EXPECT_EQ(ImportedName("", "robots/arm/robot.urdf"), "arm");
  EXPECT_EQ(ImportedName("robot", "robots/arm/model.urdf"), "arm");
  EXPECT_EQ(ImportedName("my arm (v2)", "x.urdf"), "my_arm__v2_");  // made a ccma name
  EXPECT_EQ(ImportedName(std::string(100, 'n'), "x.urdf"), std::string(64, 'n'));
  // Names that plain YAML reads as null or as a list entry are written quoted.
  EXPECT_EQ(ImportedName("null", "x.urdf"), "null");
  EXPECT_EQ(ImportedName("-", "x.urdf"), "-");
  // The collection's files are all <robot name="onshape"> in robot.urdf.
  ImportOptions options;
  options.end_effector_link = "effector";
  EXPECT_EQ(ImportRobot(ReadUrdf(kRobots + "5bar_linkage/robot.urdf", kRobots + "5bar_linkage/robot.yaml"), options)
                .model.name,
            "5bar_linkage");
  options.end_effector_link = "coupler";
  EXPECT_EQ(ImportRobot(ReadSdformat(std::string(CCMA_MODELS_DIR) + "/robots/four_bar_loop.sdf", {"crank"}), options)
                .model.name,
            "four_bar_loop");  // <model name="four_bar_loop">
}

}  // namespace
}  // namespace ccma
