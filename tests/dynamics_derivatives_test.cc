// The second-order terms inverse dynamics adds (analyses/dynamics.h) against
// numeric differentiation at seeded random and hard states, each with a
// test that the same checker fails on a wrong term:
// - the motors' control curvature d^2 r / dt^2 along u + t du
//   (FramedCost::AddControlCurvature);
// - the constraints' curvature along a motion of state and controls
//   (ConstraintSet::CurvatureAlong), on every bundled model;
// - the mechanism's acceleration q'' = S u'' + S'(u', u') (ControlMotion)
//   against second differences of configurations the forward solver
//   assembles along u(t) = u0 + t u' + t^2/2 u''.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ccma/ccma.h"
#include "ccma/internal/constraint_set.h"
#include "cost_functions/actuated_revolute_cost.h"
#include "cost_functions/legged_base_motor_cost.h"
#include "cost_functions/omni_base_motor_cost.h"
#include "problems/forward_problem.h"
#include "problems/internal/control_motion.h"
#include "tests/bundled_models.h"

namespace ccma {
namespace dynamics_derivatives_test {

// Richardson-extrapolated central second difference of f at 0, step h.
template <typename F>
Eigen::VectorXd SecondDerivative(const F& f, double h) {
  const Eigen::VectorXd f0 = f(0.0);
  const auto d2 = [&](double k) -> Eigen::VectorXd { return ((f(k) - f0) + (f(-k) - f0)) / (k * k); };
  return (4.0 * d2(h) - d2(2 * h)) / 3.0;
}

Eigen::VectorXd Residual(const ceres::CostFunction& cost, const std::vector<std::vector<double>>& blocks) {
  std::vector<const double*> params;
  for (const auto& b : blocks) params.push_back(b.data());
  Eigen::VectorXd r(cost.num_residuals());
  cost.Evaluate(params.data(), r.data(), nullptr);
  return r;
}

// The analytic control curvature of `cost` (poses then one control block)
// minus the numeric one, largest entry.
double ControlCurvatureError(const ceres::CostFunction& cost, const std::vector<std::vector<double>>& blocks,
                             const std::vector<double>& du, bool flip_sign = false) {
  const auto* framed = dynamic_cast<const FramedCost*>(&cost);
  std::vector<const double*> params;
  for (const auto& b : blocks) params.push_back(b.data());
  Eigen::VectorXd analytic = Eigen::VectorXd::Zero(cost.num_residuals());
  framed->AddControlCurvature(params.data(), du.data(), analytic.data());
  if (flip_sign) analytic = -analytic;
  const Eigen::VectorXd numeric = SecondDerivative(
      [&](double t) {
        std::vector<std::vector<double>> moved = blocks;
        for (size_t i = 0; i < du.size(); ++i) moved.back()[i] += t * du[i];
        return Residual(cost, moved);
      },
      1e-3);
  return (analytic - numeric).cwiseAbs().maxCoeff();
}

std::vector<double> RandomPose(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Eigen::Quaterniond q{n(rng), n(rng), n(rng), n(rng)};
  q.normalize();
  std::uniform_real_distribution<double> p(-1, 1);
  return {q.x(), q.y(), q.z(), q.w(), p(rng), p(rng), p(rng)};
}

std::vector<double> RandomControls(std::mt19937& rng, int size, double scale) {
  std::uniform_real_distribution<double> d(-scale, scale);
  std::vector<double> u(static_cast<size_t>(size));
  for (double& v : u) v = d(rng);
  return u;
}

constexpr double kCurvatureTolerance = 1e-8;

TEST(ControlCurvature, MotorsMatchNumericSecondDifferences) {
  const ActuatedRevoluteCost revolute(Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d(0.6, 0.8, 0),
                                      0.4);
  const OmniBaseMotorCost omni;
  const LeggedBaseMotorCost legged;
  for (int seed = 0; seed < 100; ++seed) {
    std::mt19937 rng(seed);
    const std::vector<double> A = RandomPose(rng), B = RandomPose(rng);
    const std::vector<double> u1 = RandomControls(rng, 1, 4.0), du1 = RandomControls(rng, 1, 3.0);
    EXPECT_LT(ControlCurvatureError(revolute, {A, B, u1}, du1), kCurvatureTolerance) << seed;
    const std::vector<double> u3 = RandomControls(rng, 3, 4.0), du3 = RandomControls(rng, 3, 3.0);
    EXPECT_LT(ControlCurvatureError(omni, {A, u3}, du3), kCurvatureTolerance) << seed;
    std::vector<double> u6 = RandomControls(rng, 6, 1.5);
    const std::vector<double> du6 = RandomControls(rng, 6, 2.0);
    if (seed % 4 == 1) u6[5] = M_PI / 2 - 1e-9;  // pitched to the z-y-x angles' singularity
    if (seed % 4 == 2) u6[2] = M_PI;             // heading at the wrap
    EXPECT_LT(ControlCurvatureError(legged, {A, u6}, du6), kCurvatureTolerance) << seed;
  }
}

TEST(DerivativeChecker, RejectsAWrongControlCurvature) {
  std::mt19937 rng(7);
  const OmniBaseMotorCost omni;
  const LeggedBaseMotorCost legged;
  const std::vector<double> A = RandomPose(rng);
  EXPECT_GT(ControlCurvatureError(omni, {A, {0.1, 0.2, 0.7}}, {0.3, -0.2, 1.5}, true), 0.1);
  EXPECT_GT(ControlCurvatureError(legged, {A, {0.1, 0.2, 0.7, 0.4, 0.3, -0.2}}, {0, 0, 1.0, 0, 0.8, 0.5}, true), 0.1);
}

// Every bundled model, perturbed away from assembly (the curvature holds
// everywhere, not only where C = 0).
struct PerturbedModel {
  Model model;
  State s;
  Eigen::VectorXd u, ds, du;
};

PerturbedModel Perturbed(const std::string& name, int seed) {
  PerturbedModel m{LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"), {}, {}, {}, {}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1, 1);
  m.s = State::Home(m.model);
  Eigen::VectorXd offset(m.s.tangent_size());
  for (Eigen::Index i = 0; i < offset.size(); ++i) offset[i] = 0.05 * d(rng);
  m.s.Plus(offset);
  m.u = m.model.home_controls();
  m.ds.resize(m.s.tangent_size());
  m.du.resize(m.u.size());
  for (Eigen::Index i = 0; i < m.u.size(); ++i) m.u[i] += 0.3 * d(rng);
  for (Eigen::Index i = 0; i < m.ds.size(); ++i) m.ds[i] = d(rng);
  for (Eigen::Index i = 0; i < m.du.size(); ++i) m.du[i] = d(rng);
  return m;
}

Eigen::VectorXd NumericCurvature(const ConstraintSet& set, const PerturbedModel& m) {
  return SecondDerivative(
      [&](double t) {
        State moved = m.s;
        moved.Plus(t * m.ds);
        Eigen::VectorXd C;
        set.Evaluate(moved, m.u + t * m.du, &C);
        return C;
      },
      1e-3);
}

TEST(CurvatureAlong, MatchesNumericOnEveryBundledModel) {
  for (const std::string& name : testing::BundledModels()) {
    for (int seed = 0; seed < 5; ++seed) {
      const PerturbedModel m = Perturbed(name, 100 + seed);
      const ConstraintSet set(m.model);
      Eigen::VectorXd h;
      BodyFrames frames;
      set.CurvatureAlong(m.s, m.u, m.ds, m.du, &h, &frames);
      const Eigen::VectorXd numeric = NumericCurvature(set, m);
      EXPECT_LT((h - numeric).cwiseAbs().maxCoeff(), 1e-7 * (1 + numeric.cwiseAbs().maxCoeff())) << name << " " << seed;
    }
  }
}

TEST(DerivativeChecker, RejectsACurvatureWithoutItsControlPart) {
  // The same comparison without the motors' control curvature fails.
  const PerturbedModel m = Perturbed("4dof_reduced", 3);
  const ConstraintSet set(m.model);
  Eigen::VectorXd h;
  BodyFrames frames;
  set.CurvatureAlong(m.s, m.u, m.ds, Eigen::VectorXd::Zero(m.du.size()), &h, &frames);
  const Eigen::VectorXd numeric = NumericCurvature(set, m);
  EXPECT_GT((h - numeric).cwiseAbs().maxCoeff(), 1e-2);
}

// A smooth motion of the controls from an assembled configuration: its
// analytic and its numeric acceleration of the state. `drop_curvature`
// leaves out S'(u', u') (the checker must then fail).
struct AccelerationCheck {
  bool usable = false;  // controls fix the mechanism and every rate is admissible
  double error = 0, scale = 0;
};

AccelerationCheck CheckAcceleration(const Model& model, int seed, bool drop_curvature) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1, 1);
  const Eigen::VectorXd home = model.home_controls();
  Eigen::VectorXd u0 = home, du(home.size()), ddu(home.size());
  for (Eigen::Index i = 0; i < home.size(); ++i) u0[i] += 0.05 * d(rng);
  for (Eigen::Index i = 0; i < home.size(); ++i) du[i] = d(rng);
  for (Eigen::Index i = 0; i < home.size(); ++i) ddu[i] = d(rng);
  ForwardProblem forward(model);
  AccelerationCheck out;
  if (!forward.Assemble(u0).assembled) return out;
  const State s0 = forward.state();
  const ConstraintSet set(model);
  const ControlMotion motion(set, HessianSolver(set), s0, u0);
  const Eigen::VectorXd ds = motion.Velocity(du);
  if (motion.rank() < s0.tangent_size() || motion.Inconsistency(ds, du) > 1e-9) return out;
  const Eigen::VectorXd dds = drop_curvature ? motion.Velocity(ddu) : motion.Acceleration(du, ddu, ds);
  bool assembled = true;
  // A step the motion's own speed scales: truncation O(step^4 |ds|^6).
  const double step = 1e-3 / std::max(1.0, ds.cwiseAbs().maxCoeff());
  const Eigen::VectorXd numeric = SecondDerivative(
      [&](double t) {
        if (t == 0.0) return Eigen::VectorXd::Zero(s0.tangent_size()).eval();
        assembled = forward.Assemble(u0 + t * du + 0.5 * t * t * ddu).assembled && assembled;
        return forward.state().Minus(s0);
      },
      step);
  out.usable = assembled;
  out.error = (dds - numeric).cwiseAbs().maxCoeff();
  out.scale = 1 + numeric.cwiseAbs().maxCoeff();
  return out;
}

TEST(SecondOrderMotion, MatchesAssembledConfigurationsOnBundledModels) {
  int checked = 0;
  for (const std::string& name : testing::BundledModels()) {
    const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
    for (int seed = 0; seed < 3; ++seed) {
      const AccelerationCheck c = CheckAcceleration(model, 200 + seed, false);
      if (!c.usable) continue;  // over-actuated or idle motions: see ControlMotion
      ++checked;
      EXPECT_LT(c.error, 1e-6 * c.scale) << name << " seed " << seed;
    }
  }
  EXPECT_GE(checked, 10);  // the bundled models whose controls fix them, three states each
}

TEST(DerivativeChecker, RejectsAnAccelerationWithoutItsCurvatureTerm) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/stewart_gough_6ups.yaml");
  const AccelerationCheck c = CheckAcceleration(model, 200, true);
  ASSERT_TRUE(c.usable);
  EXPECT_GT(c.error, 1e-3 * c.scale);
}

}  // namespace dynamics_derivatives_test
}  // namespace ccma
