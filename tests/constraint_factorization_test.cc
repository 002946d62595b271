// ConstraintFactorization (problems/internal/constraint_factorization.h):
// its sparse path (refined normal equations through the block LDL^T of H)
// gives the dense complete orthogonal decomposition's minimum-norm
// solutions on every bundled model, at home and at seeded random assembled
// controls; a rank-deficient J_s (the tripod's idle leg spins) takes the
// dense path, and its answers are Equilibrium's bit for bit.
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "ccma/ccma.h"
#include "ccma/internal/constraint_set.h"
#include "problems/internal/constraint_factorization.h"
#include "problems/internal/equilibrium.h"
#include "problems/internal/hessian_solver.h"
#include "tests/bundled_models.h"

namespace ccma {
namespace constraint_factorization_test {

double FactorizationGap(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / (1.0 + b.lpNorm<Eigen::Infinity>());
}

class BundledFactorization : public ::testing::TestWithParam<std::string> {};

TEST_P(BundledFactorization, SparsePathGivesTheMinimumNormSolutions) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + GetParam() + ".yaml");
  const ConstraintSet set(model);
  const HessianSolver symbolic(set);
  std::mt19937 rng(52);
  std::uniform_real_distribution<double> d(-1, 1);
  ForwardProblem forward(model);
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd u = model.home_controls();
    for (Eigen::Index i = 0; trial > 0 && i < u.size(); ++i) u[i] += 0.02 * d(rng);
    if (!forward.Assemble(u).assembled) continue;
    const State& s = forward.state();
    const ConstraintFactorization factored(set, symbolic, s, forward.controls());
    const Equilibrium dense(set, s, forward.controls());
    ASSERT_TRUE(factored.sparse()) << "every bundled model has full column rank away from singularities";
    ASSERT_EQ(dense.rank(), s.tangent_size());
    Eigen::VectorXd Q(s.tangent_size()), x(s.tangent_size()), du(model.num_controls());
    for (Eigen::Index i = 0; i < Q.size(); ++i) Q[i] = 10 * d(rng);
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = d(rng);
    for (Eigen::Index i = 0; i < du.size(); ++i) du[i] = d(rng);
    const Eigen::VectorXd b = dense.J_s() * x;  // consistent: x is the answer
    EXPECT_LT(FactorizationGap(factored.StateSolution(b), x), 1e-11) << trial;
    EXPECT_LT(FactorizationGap(factored.StateSolution(b), dense.StateSolution(b)), 1e-11) << trial;
    EXPECT_LT(FactorizationGap(factored.StateMotion(du), dense.StateMotion(du)), 1e-11) << trial;
    const Eigen::VectorXd lambda = factored.Multipliers(Q);
    EXPECT_LT(FactorizationGap(lambda, dense.Multipliers(Q)), 1e-11) << trial;
    EXPECT_LT(FactorizationGap(factored.Efforts(lambda), dense.Efforts(dense.Multipliers(Q))), 1e-11) << trial;
    // An inconsistent right-hand side: the least-squares solution, whose
    // residual is orthogonal to J_s's columns.
    Eigen::VectorXd noisy = b;
    for (Eigen::Index i = 0; i < noisy.size(); ++i) noisy[i] += 0.1 * d(rng);
    const Eigen::VectorXd y = factored.StateSolution(noisy);
    EXPECT_LT((dense.J_s().transpose() * (noisy - dense.J_s() * y)).lpNorm<Eigen::Infinity>(), 1e-11) << trial;
  }
}

INSTANTIATE_TEST_SUITE_P(Models, BundledFactorization, ::testing::ValuesIn(testing::BundledModels()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(ConstraintFactorization, RankDeficientJacobianTakesTheDensePath) {
  const Model model = LoadModel(std::string(CCMA_SOURCE_DIR) + "/examples/statics/tripod.yaml");
  const ConstraintSet set(model);
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Assemble(model.home_controls()).assembled);
  const State& s = forward.state();
  const ConstraintFactorization factored(set, HessianSolver(set), s, forward.controls());
  const Equilibrium dense(set, s, forward.controls());
  EXPECT_FALSE(factored.sparse());
  EXPECT_EQ(factored.rank(), dense.rank());
  EXPECT_LT(factored.rank(), s.tangent_size());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1, 1);
  Eigen::VectorXd Q(s.tangent_size()), du(model.num_controls());
  for (Eigen::Index i = 0; i < Q.size(); ++i) Q[i] = d(rng);
  for (Eigen::Index i = 0; i < du.size(); ++i) du[i] = d(rng);
  EXPECT_EQ(factored.Multipliers(Q), dense.Multipliers(Q));
  EXPECT_EQ(factored.StateMotion(du), dense.StateMotion(du));
}

}  // namespace constraint_factorization_test
}  // namespace ccma
