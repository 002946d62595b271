// The assembled, sparse derivatives of E = 1/2 C^T C (ConstraintSet::
// EvaluateDerivatives) on every bundled model, at seeded random states that
// are not assembled (E > 0, so the second-order terms count):
//  * J_s, J_u, C equal the dense Evaluate() (the patterns hold every entry);
//  * G = dE/ds and dE/du against central differences of E;
//  * H = d2E/ds2 against second differences of E(s (+) delta), and
//    dG/du against central differences of G in u;
//  * the patterns stay fixed: a second evaluation allocates nothing new.
// Plus a check that the comparison fails on a wrong H.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ccma/internal/constraint_set.h"
#include "formats/model_loader.h"
#include "problems/forward_problem.h"
#include "tests/bundled_models.h"

namespace ccma {
namespace energy_derivatives_test {

constexpr double kStep = 1e-4;  // [m, rad]

double RelativeError(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric) {
  return (analytic - numeric).cwiseAbs().maxCoeff() / std::max(numeric.cwiseAbs().maxCoeff(), 1e-12);
}

struct Point {
  State s;
  Eigen::VectorXd u;
};

// The home state moved by a seeded random tangent step of `scale` (m, rad),
// controls moved by a tenth of it.
Point RandomPoint(const Model& model, unsigned seed, double scale) {
  ForwardProblem forward(model);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd ds(model.state_size());
  for (int i = 0; i < ds.size(); ++i) ds[i] = scale * unit(rng);
  Point p{forward.state(), model.home_controls()};
  p.s.Plus(ds);
  for (int i = 0; i < p.u.size(); ++i) p.u[i] += 0.1 * scale * unit(rng);
  return p;
}

State Moved(const State& s, int i, double hi, int j = -1, double hj = 0) {
  Eigen::VectorXd ds = Eigen::VectorXd::Zero(s.tangent_size());
  ds[i] += hi;
  if (j >= 0) ds[j] += hj;
  State moved = s;
  moved.Plus(ds);
  return moved;
}

// d2E/ds2 by second differences of E(s (+) delta) (a single retraction).
Eigen::MatrixXd NumericHessian(const ConstraintSet& constraints, const Point& p) {
  const int n = constraints.state_size();
  Eigen::MatrixXd H(n, n);
  const double h = kStep;
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      const double pp = constraints.Energy(Moved(p.s, i, h, j, h), p.u);
      const double pm = constraints.Energy(Moved(p.s, i, h, j, -h), p.u);
      const double mp = constraints.Energy(Moved(p.s, i, -h, j, h), p.u);
      const double mm = constraints.Energy(Moved(p.s, i, -h, j, -h), p.u);
      H(i, j) = H(j, i) = (pp - pm - mp + mm) / (4 * h * h);
    }
  }
  return H;
}

class EnergyDerivativesTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { model_ = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + GetParam() + ".yaml"); }
  Model model_;
};

TEST_P(EnergyDerivativesTest, SparseMatricesEqualTheDenseEvaluation) {
  const ConstraintSet constraints(model_);
  for (unsigned seed : {1u, 2u}) {
    const Point p = RandomPoint(model_, seed, 0.05);
    EnergyDerivatives d;
    constraints.EvaluateDerivatives(p.s, p.u, &d);
    Eigen::VectorXd C;
    Eigen::MatrixXd J_s, J_u;
    constraints.Evaluate(p.s, p.u, &C, &J_s, &J_u);
    EXPECT_EQ((d.C - C).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ((Eigen::MatrixXd(d.J_s) - J_s).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ((Eigen::MatrixXd(d.J_u) - J_u).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LT((d.G - J_s.transpose() * C).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT((d.dE_du - J_u.transpose() * C).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_NEAR(d.energy, 0.5 * C.squaredNorm(), 1e-16);
    EXPECT_GT(d.energy, 1e-8);  // not assembled: the second-order terms count
    // Linear in the mechanism's size: a handful of 6 x 6 blocks per body.
    EXPECT_LE(d.H.nonZeros(), 36 * (model_.num_bodies() + 2 * static_cast<int>(constraints.blocks().size())));
  }
}

TEST_P(EnergyDerivativesTest, GradientsMatchCentralDifferences) {
  const ConstraintSet constraints(model_);
  const Point p = RandomPoint(model_, 3, 0.05);
  EnergyDerivatives d;
  constraints.EvaluateDerivatives(p.s, p.u, &d);
  const int n = constraints.state_size();
  Eigen::VectorXd G(n);
  for (int i = 0; i < n; ++i) {
    G[i] = (constraints.Energy(Moved(p.s, i, kStep), p.u) - constraints.Energy(Moved(p.s, i, -kStep), p.u)) /
           (2 * kStep);
  }
  EXPECT_LT(RelativeError(d.G, G), 1e-7);
  Eigen::VectorXd dE_du(constraints.num_controls());
  Eigen::MatrixXd dG_du(n, constraints.num_controls());
  for (int c = 0; c < constraints.num_controls(); ++c) {
    Eigen::VectorXd up = p.u, down = p.u;
    up[c] += kStep;
    down[c] -= kStep;
    dE_du[c] = (constraints.Energy(p.s, up) - constraints.Energy(p.s, down)) / (2 * kStep);
    EnergyDerivatives at_up, at_down;
    constraints.EvaluateDerivatives(p.s, up, &at_up);
    constraints.EvaluateDerivatives(p.s, down, &at_down);
    dG_du.col(c) = (at_up.G - at_down.G) / (2 * kStep);
  }
  EXPECT_LT(RelativeError(d.dE_du, dE_du), 1e-7);
  EXPECT_LT(RelativeError(Eigen::MatrixXd(d.dG_du), dG_du), 1e-6);
}

TEST_P(EnergyDerivativesTest, HessianMatchesSecondDifferences) {
  const ConstraintSet constraints(model_);
  for (double scale : {0.05, 0.5}) {  // near assembly, and far from it
    const Point p = RandomPoint(model_, 4, scale);
    EnergyDerivatives d;
    constraints.EvaluateDerivatives(p.s, p.u, &d);
    const Eigen::MatrixXd H = NumericHessian(constraints, p);
    const Eigen::MatrixXd analytic(d.H);
    EXPECT_LT(RelativeError(analytic, H), 1e-6) << "scale " << scale;
    EXPECT_LT((analytic - analytic.transpose()).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST_P(EnergyDerivativesTest, ReusedWorkspaceKeepsItsPatterns) {
  const ConstraintSet constraints(model_);
  EnergyDerivatives d;
  const Point a = RandomPoint(model_, 5, 0.05), b = RandomPoint(model_, 6, 0.05);
  constraints.EvaluateDerivatives(a.s, a.u, &d);
  const double* H_values = d.H.valuePtr();
  const double* J_values = d.J_s.valuePtr();
  constraints.EvaluateDerivatives(b.s, b.u, &d);
  EXPECT_EQ(d.H.valuePtr(), H_values);
  EXPECT_EQ(d.J_s.valuePtr(), J_values);
  EnergyDerivatives fresh;
  constraints.EvaluateDerivatives(b.s, b.u, &fresh);
  EXPECT_EQ((Eigen::MatrixXd(d.H) - Eigen::MatrixXd(fresh.H)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((Eigen::MatrixXd(d.dG_du) - Eigen::MatrixXd(fresh.dG_du)).cwiseAbs().maxCoeff(), 0.0);
}

// Energy and EvaluateDerivatives read every body's frame from a workspace
// (BodyFrames) that keeps a rotation while its quaternion's bits are
// unchanged. One workspace reused along a sequence of states (random, then
// only translated, then only rotated, then a quaternion set to NaN) must give
// what the cost functions give with their own frames (dense Evaluate).
TEST_P(EnergyDerivativesTest, SharedFramesGiveTheCostFunctionsResiduals) {
  const ConstraintSet constraints(model_);
  BodyFrames frames;
  EnergyDerivatives d;
  const Point p = RandomPoint(model_, 7, 0.05);
  State translated = p.s, rotated = p.s, not_finite = p.s;
  for (int b = 0; b < translated.num_bodies(); ++b) translated.pose(b)[4] += 0.01 * (b + 1);
  Eigen::VectorXd turn = Eigen::VectorXd::Zero(p.s.tangent_size());
  turn[0] = 0.02;  // body 0's rotation only
  rotated.Plus(turn);
  not_finite.pose(0)[3] = std::nan("");
  for (const State* s : {&p.s, static_cast<const State*>(&translated), static_cast<const State*>(&rotated), &p.s}) {
    Eigen::VectorXd C;
    Eigen::MatrixXd J_s;
    constraints.Evaluate(*s, p.u, &C, &J_s);
    const double E = 0.5 * C.squaredNorm();
    EXPECT_NEAR(constraints.Energy(*s, p.u, &frames), E, 1e-15 * E);
    constraints.EvaluateDerivatives(*s, p.u, &d);
    EXPECT_EQ((d.C - C).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ((Eigen::MatrixXd(d.J_s) - J_s).cwiseAbs().maxCoeff(), 0.0);
  }
  // The moves changed the energy: a stale rotation would have shown.
  EXPECT_NE(constraints.Energy(translated, p.u), constraints.Energy(p.s, p.u));
  EXPECT_NE(constraints.Energy(rotated, p.u), constraints.Energy(p.s, p.u));
  EXPECT_TRUE(std::isnan(constraints.Energy(not_finite, p.u, &frames)));
  EXPECT_FALSE(std::isnan(constraints.Energy(p.s, p.u, &frames)));
}

INSTANTIATE_TEST_SUITE_P(BundledModels, EnergyDerivativesTest, ::testing::ValuesIn(testing::BundledModels()));

TEST(EnergyDerivativesChecker, RejectsAWrongHessian) {
  // The same comparison with one 6 x 6 block's second-order terms dropped
  // (Gauss-Newton J^T J there) must fail: the check can see such a slip.
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_complete.yaml");
  const ConstraintSet constraints(model);
  const Point p = RandomPoint(model, 7, 0.5);
  EnergyDerivatives d;
  constraints.EvaluateDerivatives(p.s, p.u, &d);
  const Eigen::MatrixXd H = NumericHessian(constraints, p);
  Eigen::MatrixXd wrong(d.H);
  const Eigen::MatrixXd J_s(d.J_s);
  wrong.topLeftCorner<6, 6>() = (J_s.transpose() * J_s).topLeftCorner<6, 6>();
  EXPECT_LT(RelativeError(Eigen::MatrixXd(d.H), H), 1e-6);
  EXPECT_GT(RelativeError(wrong, H), 1e-4);
}

}  // namespace
}  // namespace ccma
