// The nonlinear loaded equilibrium (problems/loaded_equilibrium.h, `ccma
// simulate --loaded`) and the joints' deviations it stretches springs by
// (ccma/internal/joint_deviation.h): the deviations' derivatives against
// JointSpringDirections by central differences (and a wrong row caught), a
// bend by theta measured as theta; a cantilever on two torsion springs under
// a large tip force against its closed-form equilibrium; the linear
// deflection of `ccma statics` recovered as the load shrinks (ratio -> 1);
// virtual work at the loaded equilibrium of a 6-DOF CCMA; rigid and unheld
// mechanisms; the tool's JSON.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <Eigen/LU>

#include "analyses/statics.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/dense_factorizations.h"
#include "ccma/internal/joint_deviation.h"
#include "ccma/internal/joint_spring_directions.h"
#include "ccma/loads.h"
#include "ccma/rotation.h"
#include "formats/model_loader.h"
#include "problems/forward_problem.h"
#include "problems/compensated_control.h"
#include "problems/compensated_trajectory.h"
#include "problems/internal/compliant_equilibrium.h"
#include "problems/loaded_equilibrium.h"
#include "model_text.h"
#include "tool_run.h"
#include "tests/tool_run.h"

namespace ccma {
namespace loaded_equilibrium_test {

// Every joint type in one chain, axes oblique.
constexpr const char* kChain =
    "name: chain\nbodies:\n"
    "  - {name: b0, position: [0, 0, 0.5]}\n  - {name: b1, position: [0.3, 0, 0.5]}\n"
    "  - {name: b2, position: [0.6, 0, 0.5]}\n  - {name: b3, position: [0.9, 0, 0.5]}\n"
    "  - {name: b4, position: [1.2, 0, 0.5]}\njoints:\n"
    "  - {name: weld, type: fixed, between: [world, b0], point: [0, 0, 0.5]}\n"
    "  - {name: hinge, type: revolute, actuated: true, between: [b0, b1], point: [0.15, 0, 0.5], axis: [0.2, 1, 0.1]}\n"
    "  - {name: cross, type: universal, between: [b1, b2], point: [0.45, 0, 0.5], axes: [[0, 1, 0], [0, 0, 1]]}\n"
    "  - {name: slide, type: prismatic, between: [b2, b3], point: [0.75, 0, 0.5], axis: [1, 0.3, 0]}\n"
    "  - {name: ball, type: spherical, between: [b3, b4], point: [1.05, 0, 0.5]}\n"
    "end_effector: {body: b4, point: [1.3, 0, 0.5], controlled: [x]}\n";

// The joint's 12-vector [dphi_A, dp_A, dphi_B, dp_B] placed in a state tangent.
Eigen::VectorXd OnState(const Joint& joint, const Eigen::Matrix<double, 12, 1>& d, int tangent_size) {
  Eigen::VectorXd ds = Eigen::VectorXd::Zero(tangent_size);
  if (joint.body_a != kWorld) ds.segment<6>(6 * joint.body_a) = d.head<6>();
  if (joint.body_b != kWorld) ds.segment<6>(6 * joint.body_b) = d.tail<6>();
  return ds;
}

// max over seeded directions and the rows [first, last) of |central
// difference of the deviation - D d|, relative to max |D d|.
double DerivativeMismatch(const Joint& joint, const State& s, const SpringDirections& d, int first, int last,
                          std::mt19937* rng) {
  std::normal_distribution<double> normal;
  double worst = 0;
  for (int trial = 0; trial < 8; ++trial) {
    Eigen::Matrix<double, 12, 1> dir;
    for (int i = 0; i < 12; ++i) dir[i] = normal(*rng);
    const Eigen::VectorXd ds = OnState(joint, dir, s.tangent_size());
    const double h = 1e-6;
    State plus = s, minus = s;
    plus.Plus(h * ds);
    minus.Plus(-h * ds);
    const Eigen::VectorXd numeric = (JointDeviation(joint, plus) - JointDeviation(joint, minus)) / (2 * h);
    const Eigen::VectorXd analytic = d.D.topRows(d.rows()) * dir;
    const double scale = std::max(1e-12, analytic.segment(first, last - first).cwiseAbs().maxCoeff());
    worst = std::max(worst, (numeric - analytic).segment(first, last - first).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

TEST(JointDeviation, IsZeroWhereJointsHoldAndItsDerivativeIsTheSpringDirections) {
  const Model model = LoadModelFromString(kChain, "chain.yaml");
  const State home = State::Home(model);
  std::mt19937 rng(7);
  for (const Joint& joint : model.joints) {
    const Eigen::VectorXd e = JointDeviation(joint, home);
    ASSERT_EQ(e.size(), TranslationSpringCount(joint.type) + RotationSpringCount(joint.type)) << joint.name;
    EXPECT_LT(e.size() ? e.cwiseAbs().maxCoeff() : 0.0, 1e-15) << joint.name;
    const SpringDirections d = JointSpringDirections(joint, home);
    EXPECT_LT(DerivativeMismatch(joint, home, d, 0, d.rows(), &rng), 1e-8) << joint.name;
    // The checker sees a wrong row: one rotation (else translation) row flipped.
    SpringDirections wrong = d;
    wrong.D.row(d.rows() - 1) *= -1;
    EXPECT_GT(DerivativeMismatch(joint, home, wrong, 0, d.rows(), &rng), 0.5) << joint.name;
  }
  // Far from holding, the translations' derivatives are still exact.
  State far = home;
  std::normal_distribution<double> normal;
  Eigen::VectorXd ds(far.tangent_size());
  for (int i = 0; i < ds.size(); ++i) ds[i] = 0.2 * normal(rng);
  far.Plus(ds);
  for (const Joint& joint : model.joints) {
    const SpringDirections d = JointSpringDirections(joint, far);
    EXPECT_LT(DerivativeMismatch(joint, far, d, 0, d.translations, &rng), 1e-8) << joint.name;
  }
}

// Turns body b by theta about the world axis through point P.
void TurnBody(State* s, int b, const Eigen::Vector3d& axis, double theta, const Eigen::Vector3d& P) {
  const Eigen::Quaterniond turn = QuaternionExp(theta * axis.normalized());
  s->SetPose(b, turn * s->q_WB(b), P + turn * (s->p_WB(b) - P));
}

TEST(JointDeviation, ABendByThetaIsTheta) {
  const Model model = LoadModelFromString(kChain, "chain.yaml");
  const State home = State::Home(model);
  const double theta = 0.7;
  State s = home;  // the weld bent about y through its point
  TurnBody(&s, 0, Eigen::Vector3d::UnitY(), theta, Eigen::Vector3d(0, 0, 0.5));
  const Eigen::VectorXd weld = JointDeviation(model.joints[0], s);
  EXPECT_LT(weld.head<3>().norm(), 1e-15);
  EXPECT_NEAR(weld[4], theta, 1e-14);
  EXPECT_NEAR(weld[3], 0.0, 1e-14);
  EXPECT_NEAR(weld[5], 0.0, 1e-14);
  const Joint& hinge = model.joints[1];  // the hinge's axis tilted about its n1
  s = home;
  const Eigen::Vector3d n1 = FirstNormal(hinge.a_A);
  TurnBody(&s, 1, n1, theta, hinge.p_A);
  Eigen::VectorXd e = JointDeviation(hinge, s);
  EXPECT_NEAR(e[3], theta, 1e-14);
  EXPECT_NEAR(e[4], 0.0, 1e-14);
  const Joint& cross = model.joints[2];  // the cross's axes out of square about a x b
  s = home;
  TurnBody(&s, 2, Eigen::Vector3d::UnitY().cross(Eigen::Vector3d::UnitZ()), 0.4, Eigen::Vector3d(0.45, 0, 0.5));
  e = JointDeviation(cross, s);
  EXPECT_NEAR(e[3], 0.4, 1e-14);
}

// The cantilever of tests/model_text.h: a motor (k1) at the origin, a weld
// with rotation stiffness k2 at x = a, the tip at x = L.
std::string Cantilever(double k1, double k2, double a, double L) {
  std::ostringstream weld;
  weld.precision(17);
  weld << "{rotation: " << k2 << "}";
  return testing::Cantilever(k1, a, weld.str(), L);
}

LoadedEquilibrium LoadedAtHome(const Model& model, const ExternalWrench& w) {
  ForwardProblem forward(model);
  EXPECT_TRUE(forward.Solve(model.home_controls()).assembled);
  return SolveLoadedEquilibrium(model, forward.state(), forward.controls(), w);
}

ExternalWrench Down(double F) {
  ExternalWrench w;
  w.force = Eigen::Vector3d(0, 0, -F);
  return w;
}

// The hub turns by t1 and the beam by t2 more (both about y, the tip going
// down): k2 t2 = F (L - a) cos(t1 + t2), k1 t1 = F (a cos t1 + (L - a) cos(t1 + t2)).
Eigen::Vector2d CantileverAngles(double k1, double k2, double a, double L, double F) {
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  for (int i = 0; i < 50; ++i) {
    const double c1 = std::cos(t[0]), c12 = std::cos(t[0] + t[1]), s1 = std::sin(t[0]), s12 = std::sin(t[0] + t[1]);
    const Eigen::Vector2d r(k1 * t[0] - F * (a * c1 + (L - a) * c12), k2 * t[1] - F * (L - a) * c12);
    Eigen::Matrix2d J;
    J << k1 + F * (a * s1 + (L - a) * s12), F * (L - a) * s12, F * (L - a) * s12, k2 + F * (L - a) * s12;
    t -= J.lu().solve(r);
  }
  return t;
}

TEST(LoadedEquilibrium, ACantileverUnderALargeForceSettlesWhereItsClosedFormSays) {
  const double k1 = 2e3, k2 = 5e3, a = 0.3, L = 1.2, F = 600;
  const Model model = LoadModelFromString(Cantilever(k1, k2, a, L), "cantilever.yaml");
  const LoadedEquilibrium r = LoadedAtHome(model, Down(F));
  ASSERT_TRUE(r.converged) << r.message;
  const Eigen::Vector2d t = CantileverAngles(k1, k2, a, L, F);
  ASSERT_GT(t[0], 0.2);  // a large bend: far from linear
  const double x = a * std::cos(t[0]) + (L - a) * std::cos(t[0] + t[1]);
  const double z = -a * std::sin(t[0]) - (L - a) * std::sin(t[0] + t[1]);
  EXPECT_NEAR(r.deflection[0], x - L, 1e-10);
  EXPECT_NEAR(r.deflection[2], z, 1e-10);
  EXPECT_NEAR(r.deflection[4], t[0] + t[1], 1e-10);  // pitch, about +y
  EXPECT_NEAR(std::abs(r.yields[0]), t[0], 1e-10);
  // The beam's frame (its middle) moves farthest.
  const Eigen::Vector3d middle(a * std::cos(t[0]) + (L - a) / 2 * std::cos(t[0] + t[1]), 0,
                               -a * std::sin(t[0]) - (L - a) / 2 * std::sin(t[0] + t[1]));
  EXPECT_NEAR(r.max_body_m, (middle - Eigen::Vector3d((a + L) / 2, 0, 0)).norm(), 1e-10);
  EXPECT_GT(r.iterations, 1);
  // The linear answer is off by far more than the tolerance at this load.
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  const StaticsReport linear = ComputeStatics(model, forward.state(), forward.controls(), Down(F));
  EXPECT_GT(std::abs(linear.compliance.deflection[2] - z), 1e-2);
}

TEST(LoadedEquilibrium, SmallLoadsGiveTheLinearDeflection) {
  const Model model = LoadModelFromString(Cantilever(2e3, 5e3, 0.3, 1.2), "cantilever.yaml");
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  double last = 1.0;
  for (const double F : {60.0, 6.0, 0.6, 0.06}) {
    ExternalWrench w = Down(F);
    w.force.x() = 0.3 * F;
    w.moment.y() = 0.1 * F;
    const LoadedEquilibrium r = LoadedAtHome(model, w);
    ASSERT_TRUE(r.converged) << r.message;
    const Eigen::Matrix<double, 6, 1> linear =
        ComputeStatics(model, forward.state(), forward.controls(), w).compliance.deflection;
    const double gap = (r.deflection - linear).norm() / linear.norm();
    EXPECT_LT(gap, 0.2 * last) << F;  // shrinks with the load, about in proportion
    last = gap;
  }
  EXPECT_LT(last, 1e-4);
}

// The 6-DOF CCMA with stiff bases and compliant hinges under a large wrench:
// the springs' forces and the loads do no work along the motions the rigid
// rows allow at the loaded configuration, and the rigid rows hold there.
TEST(LoadedEquilibrium, SpringsAndLoadsDoNoWorkAlongAllowedMotionsOfACcma) {
  Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/6dof_asymmetric.yaml");
  const Eigen::Vector3d k_base(2e4, 3e4, 600);
  for (MobileBase& base : model.mobile_bases) base.stiffness.k = k_base;
  for (Joint& joint : model.joints) {
    if (joint.type == JointType::kRevolute) joint.stiffness.rotation = {3e3, 4e3};
  }
  ExternalWrench w;  // about 2 cm and 0.05 rad of deflection
  w.force = Eigen::Vector3d(3, -2, -4);
  w.moment = Eigen::Vector3d(0.2, 0.1, -0.3);
  const LoadedEquilibrium r = LoadedAtHome(model, w);
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_GT(r.deflection.head<3>().norm(), 1e-3);
  const Eigen::VectorXd u = model.home_controls() + r.yields;
  const ConstraintSet set(model);
  const CompliantEquilibrium system(model, set, r.state, u);
  // e: the controls' yields, then the hinges' deviations (S's rows).
  std::vector<double> stretch;
  for (const int c : system.compliant_controls()) stretch.push_back(r.yields[c]);
  for (const Joint& joint : model.joints) {
    if (!joint.stiffness.has_springs()) continue;
    const Eigen::VectorXd e = JointDeviation(joint, r.state);
    for (int i = 3; i < e.size(); ++i) stretch.push_back(e[i]);
  }
  const Eigen::VectorXd e = Eigen::Map<Eigen::VectorXd>(stretch.data(), static_cast<int>(stretch.size()));
  ASSERT_EQ(e.size(), system.S().rows());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(system.size());
  f.head(model.state_size()) = GeneralizedLoads(model, r.state, w);
  const double load = f.cwiseAbs().maxCoeff();
  f -= system.S().transpose() * (system.k().asDiagonal() * e);
  MinimumNormSolver cod;
  cod.setThreshold(1e-10).compute(system.A());
  const Eigen::MatrixXd Z = cod.nullSpace();
  ASSERT_GT(Z.cols(), 0);
  EXPECT_LT((Z.transpose() * f).cwiseAbs().maxCoeff(), 1e-8 * load);
  Eigen::VectorXd C;
  set.Evaluate(r.state, u, &C);
  for (size_t j = 0, b = 0; j < model.joints.size(); ++j) {
    const ConstraintBlock& block = set.blocks()[b];
    if (!model.joints[j].stiffness.has_springs()) {
      EXPECT_LT(C.segment(block.row, block.rows).cwiseAbs().maxCoeff(), 1e-11) << model.joints[j].name;
    }
    b += model.joints[j].actuated ? 2 : 1;
  }
}

TEST(LoadedEquilibrium, ARigidModelIsItsAssembly) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/6dof_asymmetric.yaml");
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  const LoadedEquilibrium r = SolveLoadedEquilibrium(model, forward.state(), forward.controls(), Down(10));
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.deflection.norm(), 0.0);
  EXPECT_EQ(r.yields.norm(), 0.0);
}

TEST(LoadedEquilibrium, AnUnheldMechanismIsSaid) {
  const Model model = LoadModelFromString(
      "name: free_arm\nbodies:\n  - {name: post, position: [0, 0, 0.5]}\n"
      "  - {name: arm, position: [0.3, 0, 1.0], mass: 1}\nmobile_bases:\n"
      "  - {name: base0, type: omni, actuation: complete, pose: [0, 0, 0], stiffness: [2.0e4, 2.0e4, 500]}\n"
      "joints:\n  - {type: fixed, between: [base0, post], point: [0, 0, 0.2]}\n"
      "  - {name: spin, type: revolute, between: [post, arm], point: [0, 0, 1.0], axis: [0, 0, 1]}\n"
      "end_effector: {body: arm, point: [0.6, 0, 1.0], controlled: [x, y, z]}\n",
      "free_arm.yaml");
  ExternalWrench push;
  push.force = Eigen::Vector3d(0, 5, 0);  // turns the arm about its free hinge
  const LoadedEquilibrium r = LoadedAtHome(model, push);
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.held);
  EXPECT_NE(r.message.find("not held"), std::string::npos) << r.message;
  EXPECT_TRUE(r.deflection.allFinite());
}

// The 6-DOF CCMA of the bundled model with stiff bases (text).
std::string CompliantSixDof() {
  return testing::InsertAfterEach(testing::ReadModel("6dof_asymmetric"), "type: omni,",
                                  {" stiffness: [2.0e4, 3.0e4, 600],", " stiffness: [1.0e4, 1.0e4, 400],",
                                   " stiffness: [3.0e4, 2.0e4, 900],"});
}

// The compliant 6-DOF CCMA with compliant hinges too (deflects by centimetres).
Model CompliantSixDofWithHinges() {
  Model model = LoadModelFromString(CompliantSixDof(), "6dof.yaml");
  for (Joint& joint : model.joints) {
    if (joint.type == JointType::kRevolute) joint.stiffness.rotation = {3e3, 4e3};
  }
  return model;
}

// The sparse Newton path (problems/internal/loaded_newton.h) and the dense
// load steps find the same equilibrium: the 6-DOF CCMA under a large wrench
// (redundant rigid rows: the bases' planar and motor rows), and the
// cantilever bent by 0.4 rad; a warm start from a nearby equilibrium lands
// there too, in fewer iterations.
TEST(LoadedEquilibrium, TheSparseAndTheDensePathsAgree) {
  ExternalWrench w;
  w.force = Eigen::Vector3d(3, -2, -8);
  w.moment = Eigen::Vector3d(0.2, 0.1, -0.3);
  const Model ccma = CompliantSixDofWithHinges();
  const Model cantilever = LoadModelFromString(Cantilever(2e3, 5e3, 0.3, 1.2), "cantilever.yaml");
  // One workspace for every solve below, of both models: the results are
  // those of solves with their own, to the equilibrium's tolerance (forces
  // within 1e-10 of the loads leave the springs 1e-12 m apart).
  LoadedOptions shared;
  shared.workspace = NewLoadedWorkspace();
  for (const auto& [model, wrench] : {std::make_pair(&ccma, w), std::make_pair(&cantilever, Down(600))}) {
    ForwardProblem forward(*model);
    ASSERT_TRUE(forward.Solve(model->home_controls()).assembled);
    LoadedOptions dense_only;
    dense_only.sparse = false;
    const LoadedEquilibrium sparse = SolveLoadedEquilibrium(*model, forward.state(), forward.controls(), wrench);
    const LoadedEquilibrium dense =
        SolveLoadedEquilibrium(*model, forward.state(), forward.controls(), wrench, dense_only);
    ASSERT_TRUE(sparse.converged && dense.converged) << sparse.message << dense.message;
    ASSERT_GT(dense.deflection.norm(), 1e-2) << model->name;
    EXPECT_LT((sparse.deflection - dense.deflection).cwiseAbs().maxCoeff(), 1e-10) << model->name;
    EXPECT_LT((sparse.yields - dense.yields).cwiseAbs().maxCoeff(), 1e-10) << model->name;
    for (int b = 0; b < model->num_bodies(); ++b) {
      EXPECT_LT((sparse.state.p_WB(b) - dense.state.p_WB(b)).norm(), 1e-10) << model->name << " body " << b;
    }
    EXPECT_TRUE(sparse.held && dense.held);
    const double load = GeneralizedLoads(*model, forward.state(), wrench).lpNorm<Eigen::Infinity>();
    EXPECT_LE(sparse.unbalanced, 1e-10 * (1 + load));
    for (int repeat = 0; repeat < 2; ++repeat) {
      const LoadedEquilibrium again = SolveLoadedEquilibrium(*model, forward.state(), forward.controls(), wrench, shared);
      ASSERT_TRUE(again.converged);
      EXPECT_LT((again.deflection - sparse.deflection).cwiseAbs().maxCoeff(), 1e-11) << model->name;
      EXPECT_LT((again.yields - sparse.yields).cwiseAbs().maxCoeff(), 1e-11) << model->name;
    }
    // Warm: the controls moved a little; start from the equilibrium above.
    Eigen::VectorXd u = forward.controls();
    u[0] += 1e-3;
    ASSERT_TRUE(forward.Solve(u).assembled);
    LoadedOptions warm = shared;
    warm.start_state = sparse.state;
    warm.start_yields = sparse.yields;
    const LoadedEquilibrium cold = SolveLoadedEquilibrium(*model, forward.state(), u, wrench);
    const LoadedEquilibrium hot = SolveLoadedEquilibrium(*model, forward.state(), u, wrench, warm);
    ASSERT_TRUE(cold.converged && hot.converged);
    EXPECT_LT((cold.deflection - hot.deflection).cwiseAbs().maxCoeff(), 1e-10) << model->name;
    EXPECT_LE(hot.iterations, cold.iterations) << model->name;
  }
}

// --compensate: the loaded end-effector lands on the target (1e-6 m is the
// acceptance; it gets far closer), the rigid one misses it by about the
// deflection.
TEST(CompensatedControl, PutsTheLoadedEndEffectorOnTheTarget) {
  const Model model = CompliantSixDofWithHinges();
  ExternalWrench w;
  w.force = Eigen::Vector3d(3, -2, -8);
  w.moment = Eigen::Vector3d(0.2, 0.1, -0.3);
  ControlProblem control(model);
  ASSERT_TRUE(control.SetControls(model.home_controls()).assembled);
  PoseTarget target = control.CurrentPose();
  target.position += Eigen::Vector3d(0.02, -0.01, 0.015);
  target.rpy += Eigen::Vector3d(0.01, -0.02, 0.03);
  const CompensatedResult r = MoveToCompensated(&control, target, w);
  ASSERT_TRUE(r.converged) << r.warning;
  const EndEffectorPose loaded = ComputeEndEffectorPose(model, r.loaded.state);
  EXPECT_LT((loaded.position - target.position).norm(), 1e-9);
  EXPECT_LT((loaded.rpy - target.rpy).cwiseAbs().maxCoeff(), 1e-9);
  const double deflection = r.loaded.deflection.head<3>().norm();
  ASSERT_GT(deflection, 1e-3);
  const double rigid_miss = (control.forward().end_effector().position - target.position).norm();
  EXPECT_NEAR(rigid_miss, deflection, 0.1 * deflection);
  EXPECT_GE(r.rounds, 2);
  EXPECT_LE(r.rounds, 12);
}

// Differential bases head where they drive, so a round that moves the
// controls by the aim's tiny correction is ill-conditioned (their headings
// swing by radians between rounds): such a round is solved again from the
// start. 4dof_differential with compliant bases and motors under a wrench,
// seeded targets near the loaded home; without the retry, the first target
// stopped at round 4 with the rigid end-effector 7e-10 m from its aim.
TEST(CompensatedControl, ReachesTheTargetOnDifferentialBases) {
  Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_differential.yaml");
  for (MobileBase& base : model.mobile_bases) base.stiffness.k = Eigen::Vector3d(2e4, 2e4, 500);
  for (Joint& joint : model.joints) {
    if (joint.type == JointType::kRevolute && !joint.actuated) joint.stiffness.rotation = {2e3, 2e3};
  }
  ASSERT_TRUE(model.compliant());
  ExternalWrench w;
  w.force = Eigen::Vector3d(5, -3, -40);
  w.moment = Eigen::Vector3d(0.5, 0.2, -0.3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> offset(-0.02, 0.02);
  for (int trial = 0; trial < 3; ++trial) {
    ControlProblem control(model);
    ASSERT_TRUE(control.SetControls(model.home_controls()).assembled);
    PoseTarget target = control.CurrentPose();
    if (trial == 0) {  // the case that stopped: 1 cm from the loaded home, 0.02 rad of yaw
      const LoadedEquilibrium home =
          SolveLoadedEquilibrium(model, control.forward().state(), control.controls(), w);
      ASSERT_TRUE(home.converged);
      target.position = ComputeEndEffectorPose(model, home.state).position + Eigen::Vector3d(0.01, -0.01, 0.01);
      target.rpy = ComputeEndEffectorPose(model, home.state).rpy + Eigen::Vector3d(0, 0, 0.02);
    } else {
      const double dx = offset(rng), dy = offset(rng), dz = offset(rng), dyaw = offset(rng);
      target.position += Eigen::Vector3d(dx, dy, dz);
      target.rpy[2] += dyaw;
    }
    const CompensatedResult r = MoveToCompensated(&control, target, w);
    ASSERT_TRUE(r.converged) << "trial " << trial << ": " << r.warning;
    const EndEffectorPose loaded = ComputeEndEffectorPose(model, r.loaded.state);
    EXPECT_LT((loaded.position - target.position).norm(), 1e-9) << "trial " << trial;
    EXPECT_LT(std::abs(std::remainder(loaded.rpy[2] - target.rpy[2], 2 * M_PI)), 1e-9) << "trial " << trial;
    EXPECT_GT(r.loaded.deflection.head<3>().norm(), 1e-3) << "trial " << trial;
  }
}

// A compensated trajectory: every step's loaded end-effector on that step's
// target (the rows), while the rigid end-effector at the same controls is off
// by about the deflection.
TEST(CompensatedTrajectory, EveryStepsLoadedEndEffectorIsOnItsTarget) {
  const Model model = CompliantSixDofWithHinges();
  ExternalWrench w;
  w.force = Eigen::Vector3d(3, -2, -8);
  ControlProblem control(model);
  ASSERT_TRUE(control.SetControls(model.home_controls()).assembled);
  const PoseTarget home = control.CurrentPose();
  std::vector<Waypoint> waypoints(2);
  waypoints[0].time = 0;
  waypoints[0].position = home.position;
  waypoints[0].rpy = home.rpy;
  waypoints[1].time = 1;
  waypoints[1].position = home.position + Eigen::Vector3d(0.03, -0.01, 0.01);
  waypoints[1].rpy = home.rpy + Eigen::Vector3d(0, 0, 0.02);
  std::vector<TrajectoryStep> steps;
  CompensatedPath path;
  const TrajectoryResult r =
      FollowWaypointsCompensated(control, waypoints, w, [&](const TrajectoryStep& s) { steps.push_back(s); }, &path);
  ASSERT_TRUE(r.converged) << r.warning;
  ASSERT_GE(steps.size(), 4u);
  ForwardProblem rigid(model);
  for (const TrajectoryStep& s : steps) {
    ASSERT_TRUE(rigid.Solve(s.controls).assembled);
    const LoadedEquilibrium loaded = SolveLoadedEquilibrium(model, rigid.state(), s.controls, w);
    const EndEffectorPose p = ComputeEndEffectorPose(model, loaded.state);
    EXPECT_LT((p.position - s.target.position).norm(), 1e-9) << s.time;
    EXPECT_LT((s.reached.position - s.target.position).norm(), 1e-9) << s.time;
    const double rigid_miss = (rigid.end_effector().position - s.target.position).norm();
    EXPECT_NEAR(rigid_miss, loaded.deflection.head<3>().norm(), 0.1 * loaded.deflection.head<3>().norm()) << s.time;
  }
  EXPECT_LE(path.max_miss, 1e-10);
}

TEST(LoadedTool, SimulateLoadedAndControlCompensatePrintTheLoadedConfiguration) {
  const std::string cantilever = ccma::testing::TestDir() + "/cantilever_loaded.yaml";
  std::ofstream(cantilever) << Cantilever(2e3, 5e3, 0.3, 1.2);
  testing::ToolRun run = testing::RunTool({"simulate", "--model=" + cantilever, "--loaded", "--wrench=0,0,-600,0,0,0"});
  ASSERT_EQ(run.status, 0) << run.err;
  nlohmann::json out = nlohmann::json::parse(run.out);
  const Eigen::Vector2d t = CantileverAngles(2e3, 5e3, 0.3, 1.2, 600);
  const double z = -0.3 * std::sin(t[0]) - 0.9 * std::sin(t[0] + t[1]);
  EXPECT_NEAR(out.at("deflection").at("end_effector")[2].get<double>(), z, 1e-10);
  EXPECT_NEAR(out.at("end_effector").at("position")[2].get<double>(), z, 1e-10);
  EXPECT_TRUE(out.at("loaded").at("converged").get<bool>());
  EXPECT_TRUE(out.at("deflection").at("held").get<bool>());
  EXPECT_EQ(out.at("controls")[0].get<double>(), 0.0);  // as commanded
  // --wrench alone is refused: simulate has no loads without --loaded.
  run = testing::RunTool({"simulate", "--model=" + cantilever, "--wrench=0,0,-600,0,0,0"});
  EXPECT_EQ(run.status, 2);
  EXPECT_TRUE(run.out.empty());
  const std::string six = ccma::testing::TestDir() + "/6dof_compliant.yaml";
  std::ofstream(six) << CompliantSixDof();
  run = testing::RunTool({"control", "--model=" + six, "--target=0.03,-0.02,0.62,0,0,0.05", "--compensate",
                          "--wrench=3,-2,-8,0,0,0"});
  ASSERT_EQ(run.status, 0) << run.err;
  out = nlohmann::json::parse(run.out);
  EXPECT_TRUE(out.at("converged").get<bool>()) << run.err;
  EXPECT_LT(out.at("error").get<double>(), 1e-6);
  EXPECT_NEAR(out.at("end_effector").at("position")[2].get<double>(), 0.62, 1e-6);
  EXPECT_GT(std::abs(out.at("compensation").at("rigid_end_effector").at("position")[2].get<double>() - 0.62), 1e-4);
  // trajectory --compensate: every row's end-effector (the loaded one) on its target.
  const std::string path = ccma::testing::TestDir() + "/compensated_path.csv", rows = ccma::testing::TestDir() + "/rows.csv";
  std::ofstream(path) << "time,x,y,z,roll,pitch,yaw\n0,0.03,-0.02,0.62,0,0,0.05\n1,0.04,-0.02,0.63,0,0,0.05\n";
  run = testing::RunTool({"trajectory", "--model=" + six, "--waypoints=" + path, "--out=" + rows, "--compensate",
                          "--wrench=3,-2,-8,0,0,0"});
  ASSERT_EQ(run.status, 0) << run.err;
  out = nlohmann::json::parse(run.out);
  EXPECT_TRUE(out.at("converged").get<bool>());
  EXPECT_LT(out.at("compensation").at("max_miss").get<double>(), 1e-6);
  EXPECT_NEAR(out.at("end_effector").at("position")[2].get<double>(), 0.63, 1e-6);
  run = testing::RunTool({"trajectory", "--model=" + six, "--waypoints=" + path, "--out=" + rows, "--wrench=3,-2,-8,0,0,0"});
  EXPECT_EQ(run.status, 2);  // --wrench without --compensate
  EXPECT_TRUE(run.out.empty());
}

// A compensated move that fails (the target 8 m away, beyond the legs'
// limits) reports the real distance of the end-effector it prints, in
// `error`, `compensation.miss`, the trajectory's `max_error` and its CSV
// rows, never 0.
TEST(LoadedTool, AFailedCompensationReportsTheRealDistance) {
  const std::string stewart = std::string(CCMA_SOURCE_DIR) + "/examples/statics/stewart_gough_compliant.yaml";
  testing::ToolRun run = testing::RunTool({"control", "--model=" + stewart, "--compensate", "--target=5,5,5,0,0,0"});
  ASSERT_EQ(run.status, 0) << run.err;
  nlohmann::json out = nlohmann::json::parse(run.out);
  EXPECT_FALSE(out.at("converged").get<bool>());
  const nlohmann::json& p = out.at("end_effector").at("position");
  const double distance = std::max({5 - p[0].get<double>(), 5 - p[1].get<double>(), 5 - p[2].get<double>()});
  EXPECT_GT(distance, 4);
  EXPECT_NEAR(out.at("error").get<double>(), distance, 1e-12);
  EXPECT_NEAR(out.at("compensation").at("miss").get<double>(), distance, 1e-12);
  EXPECT_NE(run.err.find("--compensate"), std::string::npos) << run.err;
  // The same through trajectory --compensate: the last row is the step that failed.
  const std::string path = ccma::testing::TestDir() + "/far_path.csv", rows = ccma::testing::TestDir() + "/far_rows.csv";
  std::ofstream(path) << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,0\n1,0.0,0.0,1.5,0,0,0\n";
  run = testing::RunTool({"trajectory", "--model=" + stewart, "--waypoints=" + path, "--out=" + rows, "--compensate"});
  ASSERT_EQ(run.status, 0) << run.err;
  out = nlohmann::json::parse(run.out);
  EXPECT_FALSE(out.at("converged").get<bool>());
  EXPECT_GT(out.at("max_error").get<double>(), 1e-4);
  std::ifstream csv(rows);
  std::string header, line, last;
  std::getline(csv, header);
  while (std::getline(csv, line)) last = line;
  const auto split = [](const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
    return out;
  };
  const std::vector<std::string> columns = split(header), values = split(last);
  const size_t error_column = std::find(columns.begin(), columns.end(), "error_m_or_rad") - columns.begin();
  ASSERT_LT(error_column, values.size()) << header;
  EXPECT_GT(std::stod(values[error_column]), 1e-4) << last;
  EXPECT_NEAR(std::stod(values[error_column]), out.at("max_error").get<double>(), 1e-9);
}

}  // namespace
}  // namespace ccma
