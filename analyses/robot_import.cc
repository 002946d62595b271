// ImportRobot: build the robot as a Model at the source's configuration
// (internal/robot_model_builder.h), assemble it with the motors held, move
// home to the assembled configuration and write it as a model file.
#include "analyses/robot_import.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <Eigen/Geometry>
#include <string>
#include <utility>

#include "analyses/internal/import_collision.h"
#include "analyses/internal/import_masses.h"
#include "analyses/internal/import_mesh_paths.h"
#include "analyses/internal/import_report.h"
#include "analyses/internal/robot_model_builder.h"
#include "analyses/moved_components.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/format.h"
#include "ccma/joint_coordinates.h"
#include "formats/joint_geometry.h"
#include "formats/model_loader.h"
#include "formats/model_writer.h"
#include "problems/forward_problem.h"

namespace ccma {
namespace {

// Assembled: E below this [m^2] (closures then hold to about 1e-12 m).
constexpr double kAssembledEnergy = 1e-24;

// A joint's world point and axes in state s (A's copy of the point; a
// closure's point is the middle of its two copies).
void WorldGeometry(const Joint& joint, const State& s, bool closure, Eigen::Vector3d* p_W, Eigen::Vector3d* a_W,
                   Eigen::Vector3d* b_W) {
  const auto R = [&](int body) -> Eigen::Matrix3d {
    return body == kWorld ? Eigen::Matrix3d::Identity() : s.R_WB(body);
  };
  const auto p = [&](int body) -> Eigen::Vector3d { return body == kWorld ? Eigen::Vector3d::Zero() : s.p_WB(body); };
  const Eigen::Vector3d p_A = R(joint.body_a) * joint.p_A + p(joint.body_a);
  const Eigen::Vector3d p_B = R(joint.body_b) * joint.p_B + p(joint.body_b);
  *p_W = closure ? Eigen::Vector3d(0.5 * (p_A + p_B)) : p_A;
  *a_W = (R(joint.body_a) * joint.a_A).normalized();
  const Eigen::Vector3d b = R(joint.body_b) * joint.b_B;
  *b_W = (b - b.dot(*a_W) * *a_W).normalized();
}

// The closure joint with the largest residual at s, for the message.
std::string WorstClosure(const internal::RobotModel& built, const State& s) {
  std::string worst;
  double largest = -1;
  for (std::size_t j = 0; j < built.model.joints.size(); ++j) {
    if (!built.closure[j]) continue;
    Eigen::Vector3d p_W, a_W, b_W, q_W, c_W, d_W;
    const Joint& joint = built.model.joints[j];
    WorldGeometry(joint, s, false, &p_W, &a_W, &b_W);
    Joint swapped = joint;
    std::swap(swapped.body_a, swapped.body_b);
    std::swap(swapped.p_A, swapped.p_B);
    WorldGeometry(swapped, s, false, &q_W, &c_W, &d_W);
    const double gap = (p_W - q_W).norm();
    if (gap > largest) {
      largest = gap;
      worst = "closure " + Quote(joint.name) + " (its frames' origins " + FormatG(gap) + " m apart)";
    }
  }
  return worst;
}

// The model with home moved to state s: bodies, bases and joints re-posed,
// each revolute/prismatic joint's q_home its coordinate at s.
Model Rehome(const internal::RobotModel& built, const State& s, bool motors_held) {
  Model model = built.model;
  for (int b = 0; b < model.num_bodies(); ++b) {
    model.bodies[b].R_WB_home = s.R_WB(b);
    model.bodies[b].p_WB_home = s.p_WB(b);
  }
  for (MobileBase& base : model.mobile_bases) {
    const Eigen::Matrix3d R = s.R_WB(base.body);
    base.home_pose = Eigen::Vector3d(s.p_WB(base.body).x(), s.p_WB(base.body).y(), std::atan2(R(1, 0), R(0, 0)));
  }
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const Joint& before = built.model.joints[j];
    Joint& joint = model.joints[j];
    Eigen::Vector3d p_W, a_W, b_W;
    WorldGeometry(before, s, built.closure[j], &p_W, &a_W, &b_W);
    SetJointGeometry(model, p_W, a_W, b_W, &joint);
    // A held motor's coordinate is its control (exactly, not to the solver's tolerance).
    const bool held = joint.actuated && motors_held;
    if (joint.has_coordinate()) joint.q_home = held ? before.q_home : JointCoordinate(before, s);
  }
  const Body& ee = model.bodies[model.end_effector.body];
  model.end_effector.p_W_home = ee.R_WB_home * model.end_effector.p_B + ee.p_WB_home;
  return model;
}

// A limited joint's assembled position must lie within its limits.
void CheckLimits(const Model& model, const std::string& source) {
  for (const Joint& joint : model.joints) {
    if (!joint.limited) continue;
    const double q = LimitCoordinate(joint, joint.q_home);
    if (q < joint.lower - 1e-9 || q > joint.upper + 1e-9) {
      throw ModelError(source + ": joint " + Quote(joint.name) + ": its position at home, " + FormatG(joint.q_home) +
                       ", is outside its limits [" + FormatG(joint.lower) + ", " + FormatG(joint.upper) + "]");
    }
  }
}

// The closure joints of `model` with their B side moved by the fraction t
// of the way from `open` (where A's frame is at the source's configuration,
// so that they hold there) to `closed` (the true geometry).
void BlendClosures(const internal::RobotModel& built, const Model& open, double t, Model* model) {
  for (std::size_t j = 0; j < model->joints.size(); ++j) {
    if (!built.closure[j]) continue;
    const Joint &from = open.joints[j], &to = built.model.joints[j];
    Joint& joint = model->joints[j];
    joint.p_B = (1 - t) * from.p_B + t * to.p_B;
    Eigen::Matrix3d R_from, R_to;
    R_from << from.d1_B, from.d2_B, from.d1_B.cross(from.d2_B);
    R_to << to.d1_B, to.d2_B, to.d1_B.cross(to.d2_B);
    const Eigen::AngleAxisd turn(R_from.transpose() * R_to);
    const Eigen::Matrix3d R = R_from * Eigen::AngleAxisd(t * turn.angle(), turn.axis()).toRotationMatrix();
    joint.d1_B = R.col(0);
    joint.d2_B = R.col(1);
  }
}

// Closures far apart at the source's configuration may defeat one solve
// from there: close them in kContinuationSteps steps instead, each solve
// starting from the last. Returns the final state; *energy its E.
State AssembleByContinuation(const internal::RobotModel& built, const ForwardOptions& options, double* energy) {
  constexpr int kContinuationSteps = 20;
  const State source = State::Home(built.model);
  Model open = built.model;
  for (std::size_t j = 0; j < open.joints.size(); ++j) {
    if (!built.closure[j]) continue;
    Joint& joint = open.joints[j];
    const auto R = [&](int b) -> Eigen::Matrix3d { return b == kWorld ? Eigen::Matrix3d::Identity() : source.R_WB(b); };
    const auto p = [&](int b) -> Eigen::Vector3d { return b == kWorld ? Eigen::Vector3d::Zero() : source.p_WB(b); };
    const Eigen::Matrix3d R_BA = R(joint.body_b).transpose() * R(joint.body_a);
    joint.p_B = R(joint.body_b).transpose() * (R(joint.body_a) * joint.p_A + p(joint.body_a) - p(joint.body_b));
    joint.d1_B = R_BA * joint.d1_A;
    joint.d2_B = R_BA * joint.d2_A;
  }
  State s = source;
  Model step = built.model;
  for (int k = 1; k <= kContinuationSteps; ++k) {
    BlendClosures(built, open, static_cast<double>(k) / kContinuationSteps, &step);
    ForwardProblem problem(step, options);
    problem.SetState(s);
    *energy = problem.Solve(step.home_controls()).residual_energy;
    s = problem.state();
  }
  return s;
}

// The robot assembled with its motors held (if it has any): one solve from
// the source's configuration, else by continuation. *energy: E at the end.
State Assemble(const internal::RobotModel& built, const ForwardOptions& options, double* energy) {
  ForwardProblem problem(built.model, options);
  *energy = problem.Solve(built.model.home_controls()).residual_energy;
  if (*energy < kAssembledEnergy) return problem.state();
  return AssembleByContinuation(built, options, energy);
}

// "x y z" for the components set in `components`.
std::string ComponentNames(const ComponentSet& components) {
  std::string names;
  for (int c = 0; c < 6; ++c) {
    if (components[c]) names += std::string(names.empty() ? "" : " ") + kEndEffectorComponentNames[c];
  }
  return names;
}

// The controlled components at home (analyses/moved_components.h): the given
// ones, refused when the controls cannot move them independently there; the
// stored ones, kept (the exported model's own), with a warning in that case;
// else the ones the controls move, translations first. An end-effector the
// controls do not move at all is refused unless its components are stored.
void SetControlled(const internal::RobotModel& built, const std::string& source, Model* home,
                   std::vector<std::string>* warnings) {
  using Controlled = internal::RobotModel::Controlled;
  ComponentSet& controlled = home->end_effector.controlled;
  const MovedComponents moved = AnalyzeMovedComponents(*home, State::Home(*home), home->home_controls(), controlled);
  const int count = static_cast<int>(std::count(controlled.begin(), controlled.end(), true));
  if (moved.rank == 0 && built.controlled != Controlled::kStored) {
    throw ModelError(source + ": the controls move no component of the end-effector " +
                     Quote(home->bodies[home->end_effector.body].name) + " at home: choose another end-effector link");
  }
  const std::string cannot = "the controls cannot move the controlled components " + ComponentNames(controlled) +
                             " independently at home (rank " + std::to_string(moved.given_rank) + " of " +
                             std::to_string(count) + "): they move " + std::to_string(moved.rank) +
                             " end-effector DOF, for example " + ComponentNames(moved.chosen);
  if (built.controlled == Controlled::kGiven && moved.given_rank < count) {
    throw ModelError(source + ": " + cannot + " (the default when none are given)");
  }
  if (built.controlled == Controlled::kStored && moved.given_rank < count) {
    warnings->push_back(source + ": the stored end-effector components: " + cannot);
  }
  if (built.controlled == Controlled::kToChoose) controlled = moved.chosen;
}

}  // namespace

bool ImportOptions::IsValid(std::string* why) const {
  for (const auto& [what, names] : {std::pair{"actuated", &actuated}, std::pair{"controlled", &controlled}}) {
    for (const std::string& name : *names) {
      if (name.empty() || name.size() > kMaxImportNameBytes) {
        *why = std::string(what) + ": empty or overlong name " + Quote(name);
        return false;
      }
    }
  }
  if (end_effector_link.size() > kMaxImportNameBytes) {
    *why = "end_effector: overlong name " + Quote(end_effector_link);
    return false;
  }
  if (!end_effector_point_L.allFinite() || end_effector_point_L.cwiseAbs().maxCoeff() > 1e4) {
    *why = "point must be finite, within 1e4 m";
    return false;
  }
  if (!(collision_radius == 0 || (collision_radius >= 1e-4 && collision_radius <= 10))) {
    *why = "collision_radius: must be 0 or in [1e-4, 10] m, got " + FormatG(collision_radius);
    return false;
  }
  return true;
}

namespace {

// The source's configuration assembled: with the motors held, else (a CAD
// export whose loops do not close at the motors' zero) with them free, as
// near as the solver gets; *motors_held says which. Throws ModelError when
// neither closes the loops.
State AssembleTheSource(const RobotDescription& robot, const internal::RobotModel& built, bool* motors_held) {
  ForwardOptions forward;
  forward.max_iterations = 500;
  double energy = 0;
  State assembled = Assemble(built, forward, &energy);
  *motors_held = true;
  if (!(energy < kAssembledEnergy)) {
    // CAD files are not always exported with the loops closable at the
    // motors' zero: close them with the motors free, as near the source's
    // configuration as the solver finds, and say so.
    internal::RobotModel free = built;
    for (Joint& joint : free.model.joints) joint.actuated = false, joint.control = -1;
    double free_energy = 0;
    const State loose = Assemble(free, forward, &free_energy);
    if (!(free_energy < kAssembledEnergy)) {
      throw ModelError(robot.source + ": cannot assemble " + WorstClosure(built, assembled) +
                       " with the motors at their source position: residual energy " + FormatG(energy) +
                       " m^2 (" + FormatG(free_energy) + " m^2 with the motors free)");
    }
    assembled = loose;
    *motors_held = false;
  }
  return assembled;
}

// ImportedRobot::closure_gaps and motor_moves, and a warning for each beyond
// kImportTolerance; ModelError naming them all instead with options.strict.
void ReportChanges(const RobotDescription& robot, const Model& source, const Model& home, const ImportOptions& options,
                   ImportedRobot* out) {
  out->closure_gaps = internal::ClosureGaps(robot);
  out->motor_moves = internal::MotorMoves(source, home);
  const std::vector<std::string> changes = internal::ImportChanges(out->closure_gaps, out->motor_moves);
  if (options.strict && !changes.empty()) {
    std::string all;
    for (const std::string& line : changes) all += (all.empty() ? "" : "; ") + line;
    throw ModelError(robot.source + ": --strict: the import would change the mechanism: " + all);
  }
  out->warnings.insert(out->warnings.end(), changes.begin(), changes.end());
}

}  // namespace

ImportedRobot ImportRobot(const RobotDescription& robot, const ImportOptions& options) {
  if (std::string why; !options.IsValid(&why)) throw std::invalid_argument(why);
  internal::RobotModel built = internal::BuildRobotModel(robot, options);
  const std::string implausible = internal::InertialsBeyondAModel(robot);
  if (!implausible.empty()) internal::DropMasses(&built.model);
  bool motors_held = true;
  const State assembled = AssembleTheSource(robot, built, &motors_held);
  Model home = Rehome(built, assembled, motors_held);
  ImportedRobot out;
  ReportChanges(robot, built.model, home, options, &out);
  if (!implausible.empty()) {
    out.warnings.push_back(robot.source + ": " + implausible + ": no masses imported (statics weighs nothing; give "
                           "mass, com and inertia in the model file)");
  }
  CheckLimits(home, robot.source);
  SetControlled(built, robot.source, &home, &out.warnings);
  out.controlled_chosen = built.controlled == internal::RobotModel::Controlled::kToChoose;
  for (int c = 0; c < 6; ++c) {
    if (home.end_effector.controlled[c]) out.controlled.push_back(kEndEffectorComponentNames[c]);
  }
  const std::string folder = options.model_folder.empty()
                                 ? std::filesystem::absolute(robot.source).parent_path().string()
                                 : options.model_folder;
  const std::vector<std::string> undrawable = internal::UndrawableMeshes(robot.source, home);
  out.warnings.insert(out.warnings.end(), undrawable.begin(), undrawable.end());
  const std::string outside = internal::RelateMeshPaths(folder, robot.source, &home);
  if (options.collision_radius > 0) {
    const internal::ImportCollisionCounts counts =
        internal::AddImportCollision(options.collision_radius, robot.source, &home);
    out.collision_capsules = counts.capsules;
    out.collision_ignored_pairs = counts.ignored_pairs;
  }
  out.yaml = WriteModelYaml(home, "Written by `ccma import` from " + robot.source +
                                      ". Joint positions q equal the source's (q_home).");
  out.model = LoadModelFromString(out.yaml, robot.source + " (imported)");
  ForwardProblem check(out.model);
  out.residual_energy = check.Energy();
  out.actuated = built.actuated;
  if (!motors_held) {
    out.warnings.push_back(robot.source + ": the loops cannot be closed with the motors at their source position; "
                           "home has the motors where the closed loops put them (controls at home: the "
                           "motors' source positions there)");
  }
  // Independent loops of the joint graph (bodies and the ground; a base is
  // an edge to the ground): the closure file's pairs for a URDF, the loops an
  // SDFormat file closes itself.
  out.closures = static_cast<int>(home.joints.size()) + home.num_bases() - home.num_bodies();
  if (!outside.empty()) out.warnings.push_back(outside);
  return out;
}

}  // namespace ccma
