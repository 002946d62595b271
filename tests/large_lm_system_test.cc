// The control step of many controls without the dense matrix
// (problems/internal/large_lm_system.h) against the dense step formed here
// from ds/du itself: J_e = F S, C = J_u^T J_u + B^T S, g = J_e^T e +
// lambda (S^T G + dE/du), du = -(J_e^T J_e + lambda C + mu I)^-1 g, on
// generated and bundled models at their home and at seeded perturbed
// controls, over damping from 1e-9 to 1 of the largest eigenvalue; a system
// given a wrong J_e is caught by the same comparison. And the control
// problem itself on a model above kMinLargeLmControls reaches its target.
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "problems/internal/large_lm_system.h"
#include "problems/internal/sensitivity.h"

namespace ccma {
namespace large_lm_system_test {

struct DenseModel {
  Eigen::MatrixXd M;  // J_e^T J_e + lambda C
  Eigen::VectorXd g;
  Eigen::MatrixXd J_e;
};

constexpr double kLambda = 0.5;

// The dense model at the sensitivity's point, with F the end-effector
// Jacobian and e seeded.
DenseModel Dense(const Sensitivity& sensitivity, const std::vector<int>& effective, const Eigen::MatrixXd& F,
                 const Eigen::VectorXd& e) {
  const EnergyDerivatives& d = sensitivity.derivatives();
  const Eigen::MatrixXd S = sensitivity.StateSensitivity();
  const int k = static_cast<int>(effective.size());
  Eigen::MatrixXd B(d.dG_du.rows(), k), J_u(d.J_u.rows(), k);
  const Eigen::MatrixXd dG_du = Eigen::MatrixXd(d.dG_du), J_u_all = Eigen::MatrixXd(d.J_u);
  Eigen::VectorXd dE_du(k);
  for (int c = 0; c < k; ++c) {
    B.col(c) = dG_du.col(effective[c]);
    J_u.col(c) = J_u_all.col(effective[c]);
    dE_du[c] = d.dE_du[effective[c]];
  }
  DenseModel out;
  out.J_e = F * S;
  const Eigen::MatrixXd BtS = B.transpose() * S;
  const Eigen::MatrixXd C = J_u.transpose() * J_u + 0.5 * (BtS + BtS.transpose());
  out.M = out.J_e.transpose() * out.J_e + kLambda * C;
  out.g = out.J_e.transpose() * e + kLambda * (S.transpose() * d.G + dE_du);
  return out;
}

struct Case {
  const char* name;
  std::string text;
};

std::vector<Case> Cases() {
  StewartOptions wheeled;
  wheeled.agents = 12;
  LeggedOptions legged;
  legged.agents = 5;
  StewartOptions ups;
  ups.agents = 8;
  return {{"wheeled_12", GenerateStewartModel(wheeled)},
          {"legged_5", GenerateLeggedModel(legged)},
          {"ups_8", GenerateStewartGoughModel(ups)}};
}

// max over damping values of |du_large - du_dense| / |du_dense| at (s, u),
// the large system built with J_e scaled by `wrong` (1: right).
double WorstMismatch(const Model& model, const State& s, const Eigen::VectorXd& u, std::mt19937* rng,
                     double wrong = 1.0) {
  const ConstraintSet set(model);
  const std::vector<int> effective = model.effective_control_indices();
  auto sensitivity = std::make_shared<Sensitivity>(set, s, u, effective);
  EXPECT_FALSE(sensitivity->singular());
  const Eigen::MatrixXd F = EndEffectorJacobian(model, s);
  std::normal_distribution<double> normal(0.0, 1e-2);
  Eigen::VectorXd e(F.rows());
  for (Eigen::Index i = 0; i < e.size(); ++i) e[i] = normal(*rng);
  const DenseModel dense = Dense(*sensitivity, effective, F, e);
  LargeLmWorkspace workspace;
  const LargeLmSystem large(sensitivity, effective, wrong * dense.J_e, dense.g, kLambda, &workspace);
  const double largest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense.M).eigenvalues().maxCoeff();
  EXPECT_LE(largest, large.LargestEigenvalueBound() * (1 + 1e-12));
  double worst = 0;
  for (const double relative : {1e-9, 1e-6, 1e-3, 1.0}) {
    const double mu = relative * largest;
    const Eigen::MatrixXd M = dense.M + mu * Eigen::MatrixXd::Identity(dense.M.rows(), dense.M.cols());
    const Eigen::VectorXd expected = -M.fullPivLu().solve(dense.g);
    Eigen::VectorXd du;
    if (!large.Step(mu, &du)) return std::numeric_limits<double>::infinity();
    // The dense solve itself is accurate to about cond(M) eps.
    worst = std::max(worst, (du - expected).norm() / expected.norm() / std::max(1.0, 1e-6 / relative));
  }
  return worst;
}

TEST(LargeLmSystem, StepsEqualTheDenseOnesAtSeededStates) {
  std::mt19937 rng(20261205);
  for (const Case& c : Cases()) {
    const Model model = LoadModelFromString(c.text, std::string(c.name) + ".yaml");
    ForwardProblem forward(model);
    ASSERT_TRUE(forward.Solve(model.home_controls()).assembled) << c.name;
    EXPECT_LT(WorstMismatch(model, forward.state(), forward.controls(), &rng), 1e-8) << c.name << " home";
    // Another assembled state: the end-effector moved by a seeded 2 cm and
    // 0.02 rad (an over-actuated mechanism assembles only on its manifold).
    std::uniform_real_distribution<double> move(-0.02, 0.02);
    ControlProblem control(model);
    PoseTarget target = control.CurrentPose();
    target.position += Eigen::Vector3d{move(rng), move(rng), move(rng)};
    target.rpy += Eigen::Vector3d{move(rng), move(rng), move(rng)};
    ASSERT_TRUE(control.MoveTo(target).converged) << c.name;
    const ForwardProblem& moved = control.forward();
    EXPECT_LT(WorstMismatch(model, moved.state(), moved.controls(), &rng), 1e-8) << c.name << " moved";
  }
}

TEST(LargeLmSystem, TheComparisonCatchesAWrongJacobian) {
  std::mt19937 rng(7);
  const Case c = Cases().front();
  const Model model = LoadModelFromString(c.text, "wheeled.yaml");
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  EXPECT_GT(WorstMismatch(model, forward.state(), forward.controls(), &rng, 1.001), 1e-6);
}

// A model above the threshold: the control problem takes the large path
// and reaches a target 1 cm and 0.01 rad away as the dense one would.
TEST(LargeLmSystem, AControlStepOfManyControlsReachesItsTarget) {
  LeggedOptions options;
  options.agents = 40;  // 240 controls
  const Model model = LoadModelFromString(GenerateLeggedModel(options), "legged_40.yaml");
  ASSERT_GE(static_cast<int>(model.effective_control_indices().size()), kMinLargeLmControls);
  ControlProblem control(model);
  PoseTarget target = control.CurrentPose();
  target.position += Eigen::Vector3d(0.01, -0.005, 0.008);
  target.rpy += Eigen::Vector3d(0.01, 0.0, -0.01);
  const ControlResult r = control.MoveTo(target);
  EXPECT_TRUE(r.converged) << r.warning;
  EXPECT_LT((control.CurrentPose().position - target.position).norm(), 1e-8);
}

}  // namespace large_lm_system_test
}  // namespace ccma
