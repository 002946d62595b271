// `ccma export` then `ccma import` on every robot of example-parallel-robots
// (every URDF under models/robots/example-parallel-robots, with the closure
// file beside it; a robot added there is tested without editing this file):
// imported, exported as URDF + closure file and as SDFormat, and imported
// again, it is the same mechanism (docs/cli.md, `ccma export`):
//  * the exported file, read at its joint positions, has every link where the
//    original has its body at home: the loops are closed in the file and the
//    import needs no continuation;
//  * the re-imported home is the original's: every body's pose (the
//    end-effector's among them), every joint coordinate and the controls;
//  * at seeded controls near home, every body that the controls determine
//    (that no free motion of the original moves at home: a rod spinning
//    about its axis is left where the solver happens to stop), and the
//    end-effector, is where the original puts it; and the configuration each
//    model reaches is one of the other's at those controls (their
//    constraints hold on it), which covers the bodies free motions move.
// A robot that does not import at all is skipped with import's message as
// the reason, and only when docs/import.md names it, for that reason.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analyses/internal/sparse_rank.h"
#include "analyses/robot_import.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/joint_coordinates.h"
#include "formats/model_loader.h"
#include "formats/sdformat_reader.h"
#include "formats/sdformat_writer.h"
#include "formats/urdf_reader.h"
#include "formats/urdf_writer.h"
#include "problems/forward_problem.h"
#include "ccma/internal/dense_factorizations.h"
#include "tests/tool_run.h"

namespace ccma {
namespace collection_round_trip_test {

namespace fs = std::filesystem;

const std::string kCollection = std::string(CCMA_MODELS_DIR) + "/robots/example-parallel-robots";

// Positions [m] and rotation matrices (Frobenius norm of the difference) agree to this.
constexpr double kTolerance = 1e-9;

struct CollectionRobot {
  std::string name;      // its folder, relative to the collection ("old/digit_like_2legs")
  std::string urdf;      // the URDF
  std::string closures;  // robot.yaml beside it, or "" (none)
};

// gtest (and CTest's test names) show a robot by its folder.
void PrintTo(const CollectionRobot& robot, std::ostream* os) { *os << robot.name; }

// Every URDF of the collection, sorted by folder.
std::vector<CollectionRobot> CollectionRobots() {
  std::vector<CollectionRobot> robots;
  for (const auto& entry : fs::recursive_directory_iterator(kCollection)) {
    if (entry.path().extension() != ".urdf") continue;
    CollectionRobot robot;
    robot.name = fs::relative(entry.path().parent_path(), kCollection).string();
    robot.urdf = entry.path().string();
    const fs::path closures = entry.path().parent_path() / "robot.yaml";
    if (fs::exists(closures)) robot.closures = closures.string();
    robots.push_back(robot);
  }
  std::sort(robots.begin(), robots.end(),
            [](const CollectionRobot& a, const CollectionRobot& b) { return a.name < b.name; });
  return robots;
}

// The end-effector: the link with the most joints between it and the root
// (the first such in file order), a link far down some chain.
std::string DeepestLink(const RobotDescription& robot) {
  std::map<std::string, std::string> parent;
  for (const RobotJoint& joint : robot.joints) parent[joint.child] = joint.parent;
  std::string deepest;
  int most = -1;
  for (const RobotLink& link : robot.links) {
    int depth = 0;
    for (std::string at = link.name; parent.count(at) && depth <= static_cast<int>(robot.joints.size()); ++depth) {
      at = parent[at];
    }
    if (depth > most) most = depth, deepest = link.name;
  }
  return deepest;
}

// `name` as import maps it (docs/import.md): other characters than
// [A-Za-z0-9_-] become '_'.
std::string CcmaName(std::string name) {
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
  }
  return name;
}

// The imported robot, and the bodies that some free motion moves at home
// (the controls do not determine their poses: a rod spinning about its
// axis, say).
struct Original {
  Model model;
  std::set<int> free;
};

// The bodies that the null space of dC/ds at home moves (a component above
// 1e-6 of a unit direction, as `ccma check` counts them; column-pivoting QR,
// for speed: these robots have up to 100 bodies).
std::set<int> FreeBodies(const Model& model) {
  Eigen::VectorXd C;
  Eigen::MatrixXd J_s, J_u;
  ConstraintSet(model).Evaluate(State::Home(model), model.home_controls(), &C, &J_s, &J_u);
  const double threshold = 1e-8 * std::max(1.0, LargestSingularValue(SparseMatrixCol(J_s.sparseView())));
  const Eigen::MatrixXd null =
      RankRevealingDecomposition(J_s, {threshold, 0.0}, RankRevealingDecomposition::Method::kPivotedQr).nullSpace();
  std::set<int> free;
  for (int b = 0; b < model.num_bodies(); ++b) {
    if (null.middleRows(kPoseTangentSize * b, kPoseTangentSize).norm() > 1e-6) free.insert(b);
  }
  return free;
}

// The robot imported with, as end-effector, its deepest link that no free
// motion moves at home (its frame's origin), so that the end-effector pose
// is the controls' to set.
Original ImportOriginal(const CollectionRobot& robot) {
  RobotDescription description = ReadUrdf(robot.urdf, robot.closures);
  ImportOptions options;
  options.end_effector_link = DeepestLink(description);
  Original out;
  Model& model = out.model;
  model = ImportRobot(description, options).model;
  out.free = FreeBodies(model);
  description.links.erase(std::remove_if(description.links.begin(), description.links.end(),
                                         [&](const RobotLink& link) {
                                           return out.free.count(model.FindBody(CcmaName(link.name))) > 0;
                                         }),
                          description.links.end());
  const int body = model.FindBody(CcmaName(DeepestLink(description)));
  EXPECT_GE(body, 0) << robot.name << ": every link moves in a free motion";
  if (body < 0) return out;
  model.end_effector.body = body;
  model.end_effector.p_B.setZero();
  model.end_effector.p_W_home = model.bodies[body].p_WB_home;
  return out;
}

// The exported robot read back (the end-effector and motors it stored).
struct ReadBack {
  RobotDescription description;
  Model model;
};

ReadBack ThroughUrdf(const Model& model, const std::string& name) {
  const UrdfExport e = WriteUrdf(model);
  const std::string path = testing::ScratchPath("collection_round_trip", name + ".urdf");
  std::ofstream(path) << e.urdf;
  std::ofstream(ClosureFilePath(path)) << e.closures;
  ReadBack out;
  out.description = ReadUrdf(path, ClosureFilePath(path));
  out.model = ImportRobot(out.description, ImportOptions{}).model;
  return out;
}

ReadBack ThroughSdformat(const Model& model, const std::string& name) {
  const std::string path = testing::ScratchPath("collection_round_trip", name + ".sdf");
  std::ofstream(path) << WriteSdformat(model).sdf;
  ReadBack out;
  out.description = ReadSdformat(path, {});
  out.model = ImportRobot(out.description, ImportOptions{}).model;
  return out;
}

// Every body of `original` (by name) but those in `skip` has the same pose
// in `back` at states sa and sb, and so has the end-effector unless its body
// is skipped.
void ExpectSamePoses(const Model& original, const State& sa, const Model& back, const State& sb,
                     const std::set<int>& skip, const std::string& where) {
  for (int b = 0; b < original.num_bodies(); ++b) {
    if (skip.count(b)) continue;
    const std::string& name = original.bodies[b].name;
    const int c = back.FindBody(name);
    ASSERT_GE(c, 0) << where << ": no body " << name;
    EXPECT_LT((sa.p_WB(b) - sb.p_WB(c)).norm(), kTolerance) << where << ": body " << name;
    EXPECT_LT((sa.R_WB(b) - sb.R_WB(c)).norm(), kTolerance) << where << ": body " << name;
  }
  if (skip.count(original.end_effector.body)) return;
  const EndEffectorPose ea = ComputeEndEffectorPose(original, sa), eb = ComputeEndEffectorPose(back, sb);
  EXPECT_LT((ea.position - eb.position).norm(), kTolerance) << where << ": end-effector";
  EXPECT_LT((ea.rotation - eb.rotation).norm(), kTolerance) << where << ": end-effector";
}

// The exported file read at its joint positions: every link that is a body of
// the original where that body is at home (so the loops are closed there).
void ExpectReadAtHome(const Model& original, const RobotDescription& read, const std::string& where) {
  for (const Body& body : original.bodies) {
    const int link = read.FindLink(body.name);
    ASSERT_GE(link, 0) << where << ": no link " << body.name;
    const Eigen::Isometry3d& X = read.links[link].X_WL;
    EXPECT_LT((X.translation() - body.p_WB_home).norm(), kTolerance) << where << ": link " << body.name;
    EXPECT_LT((X.linear() - body.R_WB_home).norm(), kTolerance) << where << ": link " << body.name;
  }
}

// Joint coordinates by joint name; SDFormat renames a joint named like a
// body NAME_joint (docs/cli.md).
void ExpectSameCoordinates(const Model& original, const Model& back, const std::string& where) {
  const State home = State::Home(back);
  std::map<std::string, double> q_back;
  for (const JointCoordinateReport& r : JointCoordinates(back, home)) q_back[back.joints[r.joint].name] = r.q;
  for (const Joint& joint : original.joints) {
    if (!joint.has_coordinate()) continue;
    const auto it = q_back.count(joint.name) ? q_back.find(joint.name) : q_back.find(joint.name + "_joint");
    ASSERT_NE(it, q_back.end()) << where << ": no joint " << joint.name;
    EXPECT_NEAR(it->second, joint.q_home, kTolerance) << where << ": joint " << joint.name;
  }
  ASSERT_EQ(back.num_controls(), original.num_controls()) << where;
  EXPECT_LT((back.home_controls() - original.home_controls()).norm(), 1e-12) << where << ": home controls";
}

// The original assembled at some controls.
struct Sample {
  Eigen::VectorXd u;
  State s;
};

// The effective controls that move alone from home: the original assembles
// with that control moved by 5e-3 or 3e-4 (rad or m), one way or the other.
// The others are locked at home (disney_robot's left leg, whose loops closed
// with its motors free, at a fold).
std::vector<int> MovableControls(const Model& model) {
  std::vector<int> movable;
  for (const int i : model.effective_control_indices()) {
    for (const double step : {5e-3, -5e-3, 3e-4, -3e-4}) {
      Eigen::VectorXd u = model.home_controls();
      u[i] += step;
      ForwardProblem forward(model);
      if (forward.Assemble(u).assembled) {
        movable.push_back(i);
        break;
      }
    }
  }
  return movable;
}

// Home, then seeded controls near home and the original's configuration
// there: each movable control moved by up to 0.02 (rad or m), the move
// shrunk fourfold until the original assembles (wl16_like, assembled with
// its motors free, moves only by about 1e-4 m from home).
std::vector<Sample> SeededSamples(const Model& model, const std::vector<int>& movable, unsigned seed) {
  std::vector<Sample> samples = {{model.home_controls(), State::Home(model)}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-0.02, 0.02);
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd du = Eigen::VectorXd::Zero(model.num_controls());
    for (const int i : movable) du[i] = offset(rng);
    for (int shrink = 0; shrink < 5; ++shrink, du /= 4) {
      ForwardProblem forward(model);
      if (forward.Assemble(model.home_controls() + du).assembled) {
        samples.push_back({model.home_controls() + du, forward.state()});
        break;
      }
    }
  }
  return samples;
}

// A state of `to` with every body that `from` has (by name) posed as in s;
// the bodies only `to` has (the frames and welded links an export adds) are
// each rigidly held, through fixed joints, to one that is posed: they keep
// their home offset to it.
State Transfer(const Model& from, const State& s, const Model& to) {
  State out = State::Home(to);
  std::vector<bool> posed(to.num_bodies(), false);
  for (int b = 0; b < to.num_bodies(); ++b) {
    const int c = from.FindBody(to.bodies[b].name);
    if (c < 0) continue;
    out.SetPose(b, s.q_WB(c), s.p_WB(c));
    posed[b] = true;
  }
  const auto home = [&](int b) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = to.bodies[b].R_WB_home;
    X.translation() = to.bodies[b].p_WB_home;
    return X;
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (const Joint& joint : to.joints) {
      if (joint.type != JointType::kFixed || joint.body_a == kWorld || posed[joint.body_a] == posed[joint.body_b]) {
        continue;
      }
      const int known = posed[joint.body_a] ? joint.body_a : joint.body_b;
      const int other = known == joint.body_a ? joint.body_b : joint.body_a;
      Eigen::Isometry3d X_known = Eigen::Isometry3d::Identity();
      X_known.linear() = out.R_WB(known);
      X_known.translation() = out.p_WB(known);
      const Eigen::Isometry3d X = X_known * home(known).inverse() * home(other);
      out.SetPose(other, Eigen::Quaterniond(X.linear()), X.translation());
      posed[other] = changed = true;
    }
  }
  for (int b = 0; b < to.num_bodies(); ++b) EXPECT_TRUE(posed[b]) << "body " << to.bodies[b].name << " not posed";
  return out;
}

// E of `model` at state s and controls u [m^2].
double EnergyAt(const Model& model, const State& s, const Eigen::VectorXd& u) {
  ForwardProblem problem(model);
  problem.Restore(s, u);
  return problem.Energy();
}

void ExpectSameMechanism(const Original& original, const std::vector<Sample>& samples, const ReadBack& back,
                         const std::string& where) {
  SCOPED_TRACE(where);
  const Model& model = original.model;
  ExpectReadAtHome(model, back.description, where);
  ForwardProblem check(back.model);
  EXPECT_LT(check.Energy(), 1e-24) << where << ": not assembled at home";
  ExpectSamePoses(model, State::Home(model), back.model, State::Home(back.model), {}, where + " at home");
  ExpectSameCoordinates(model, back.model, where);
  for (const Sample& sample : samples) {
    const std::string at = where + " at controls " + ::testing::PrintToString(sample.u);
    ForwardProblem b(back.model);
    ASSERT_TRUE(b.Assemble(sample.u).assembled) << at;
    ExpectSamePoses(model, sample.s, back.model, b.state(), original.free, at);
    EXPECT_LT(EnergyAt(model, Transfer(back.model, b.state(), model), sample.u), 1e-20) << at;
    EXPECT_LT(EnergyAt(back.model, Transfer(model, sample.s, back.model), sample.u), 1e-20) << at;
  }
}

// The robots of the collection that docs/import.md says do not import, and
// a part of the reason import gives.
const std::map<std::string, std::string> kRefused = {
    {"kangaroo_like", "cannot assemble closure"},
    {"kangaroo_like_2legs", "cannot assemble closure"},
    {"kangaroo_like_2leg", "no actuated joint"},            // no closure file
    {"true_talos_2_legs", "mesh scale must be positive"},  // mirrored meshes, scale 1 -1 1
};

class CollectionRoundTrip : public ::testing::TestWithParam<CollectionRobot> {};

TEST_P(CollectionRoundTrip, UrdfAndSdformatGiveBackTheSameMechanism) {
  const CollectionRobot& robot = GetParam();
  const auto refused = kRefused.find(robot.name);
  Original original;
  try {
    original = ImportOriginal(robot);
  } catch (const ModelError& e) {
    ASSERT_NE(refused, kRefused.end()) << robot.name << " does not import: " << e.what();
    ASSERT_NE(std::string(e.what()).find(refused->second), std::string::npos) << e.what();
    GTEST_SKIP() << robot.name << " does not import: " << e.what();
  }
  EXPECT_EQ(refused, kRefused.end()) << robot.name << " imports: docs/import.md says it does not";
  const Model& model = original.model;
  const std::vector<int> movable = MovableControls(model);
  ASSERT_FALSE(movable.empty()) << robot.name << ": no control moves";
  if (movable.size() < model.effective_control_indices().size()) {
    std::cout << robot.name << ": " << model.effective_control_indices().size() - movable.size()
              << " control(s) locked at home, not moved\n";
  }
  const std::vector<Sample> samples = SeededSamples(model, movable, 11);
  EXPECT_EQ(samples.size(), 4u) << robot.name << ": some seeded controls do not assemble";
  ExpectSameMechanism(original, samples, ThroughUrdf(model, model.name), robot.name + " (urdf)");
  ExpectSameMechanism(original, samples, ThroughSdformat(model, model.name), robot.name + " (sdf)");
}

std::string TestName(const ::testing::TestParamInfo<CollectionRobot>& info) {
  std::string name = info.param.name;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(ExampleParallelRobots, CollectionRoundTrip, ::testing::ValuesIn(CollectionRobots()), TestName);

}  // namespace
}  // namespace ccma
