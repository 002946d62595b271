// The block LDL^T of dG/ds (problems/internal/hessian_solver.h) against
// Eigen's scalar SimplicialLDLT of the same permuted matrix in natural order:
// the same pivots (they are read as the conditioning figure `rcond`), the
// same solves and forward substitutions, on every bundled model, at seeded
// random states (exact Hessians, positive definite or not) and on random
// symmetric matrices of the same pattern (indefinite); and failure on a zero
// or non-finite pivot.
#include <random>
#include <string>

#include <Eigen/SparseCholesky>
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include "formats/model_loader.h"
#include "problems/internal/hessian_solver.h"
#include "tests/bundled_models.h"

namespace ccma {
namespace hessian_solver_test {

using Reference = Eigen::SimplicialLDLT<SparseColMajor, Eigen::Lower, Eigen::NaturalOrdering<int>>;

double MaxAbs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

// H with its values replaced by a random symmetric matrix of the same
// pattern, diagonal shifted by `shift` (large: positive definite).
SparseColMajor RandomSymmetric(const SparseColMajor& pattern, double shift, std::mt19937* rng) {
  std::uniform_real_distribution<double> value(-1, 1);
  SparseColMajor lower = pattern.triangularView<Eigen::Lower>();
  for (int k = 0; k < lower.nonZeros(); ++k) lower.valuePtr()[k] = value(*rng);
  SparseColMajor full = lower.selfadjointView<Eigen::Lower>();
  for (int i = 0; i < full.rows(); ++i) full.coeffRef(i, i) += shift;
  full.makeCompressed();
  // Back into the pattern's own layout (same nonzeros, same order).
  SparseColMajor out = pattern;
  for (int c = 0; c < out.outerSize(); ++c) {
    for (SparseColMajor::InnerIterator it(out, c); it; ++it) it.valueRef() = full.coeff(it.row(), c);
  }
  return out;
}

// Checks solver (factorised from H) against the reference factorisation of
// P H P^T.
void ExpectSameFactorisation(const HessianSolver& solver, const SparseColMajor& H, std::mt19937* rng,
                             const std::string& where) {
  SCOPED_TRACE(where);
  const auto& P = solver.permutation();
  SparseColMajor permuted(H.rows(), H.cols());
  permuted.selfadjointView<Eigen::Lower>() = H.selfadjointView<Eigen::Lower>().twistedBy(P);
  const Reference reference(permuted);
  ASSERT_EQ(reference.info(), Eigen::Success);
  const Eigen::VectorXd D = reference.vectorD();
  const double scale = MaxAbs(D);
  EXPECT_LE(MaxAbs(solver.pivots() - D), 1e-11 * scale);
  EXPECT_NEAR(solver.pivot_ratio(), D.minCoeff() / scale, 1e-11);

  std::normal_distribution<double> normal;
  Eigen::VectorXd v(H.rows());
  for (Eigen::Index i = 0; i < v.size(); ++i) v[i] = normal(*rng);
  // Solve: against the reference and by its residual.
  const Eigen::VectorXd x = solver.Solve(v);
  const Eigen::VectorXd x_reference = P.transpose() * reference.solve(P * v);
  EXPECT_LE(MaxAbs(x - x_reference), 1e-9 * MaxAbs(x_reference));
  EXPECT_LE(MaxAbs(H * x - v), 1e-9 * MaxAbs(H) * MaxAbs(x));
  // L^-1 P v, dense.
  Eigen::VectorXd y_reference = P * v;
  reference.matrixL().solveInPlace(y_reference);
  EXPECT_LE(MaxAbs(solver.ForwardSubstitute(v) - y_reference), 1e-10 * MaxAbs(y_reference));
  // L^-1 P M for sparse columns (one block's columns, the ground's side
  // included), entry lists against the dense substitution.
  const int columns = std::min<int>(9, static_cast<int>(H.rows()));
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(H.rows(), columns);
  for (int c = 0; c < columns; ++c) {
    for (int r = 6 * c % static_cast<int>(H.rows()); r < 6 * c % static_cast<int>(H.rows()) + 6; ++r) {
      M(r, c) = normal(*rng);
    }
  }
  const SparseColMajor M_sparse = M.sparseView();
  std::vector<int> chosen;
  for (int c = columns - 1; c >= 0; c -= 2) chosen.push_back(c);  // any subset, any order
  HessianSolver::SparseFactorColumns out;
  solver.ForwardSubstitute(M_sparse, chosen, &out);
  Eigen::MatrixXd from_lists = Eigen::MatrixXd::Zero(H.rows(), static_cast<Eigen::Index>(chosen.size()));
  for (size_t r = 0; r < out.rows.size(); ++r) {
    for (const auto& [column, value] : out.rows[r]) from_lists(static_cast<Eigen::Index>(r), column) = value;
  }
  for (size_t g = 0; g < chosen.size(); ++g) {
    Eigen::VectorXd expected = P * M.col(chosen[g]);
    reference.matrixL().solveInPlace(expected);
    EXPECT_LE(MaxAbs(from_lists.col(static_cast<Eigen::Index>(g)) - expected), 1e-10 * std::max(MaxAbs(expected), 1.0));
  }
}

class HessianSolverAgainstEigen : public ::testing::TestWithParam<std::string> {};

TEST_P(HessianSolverAgainstEigen, SamePivotsSolvesAndSubstitutions) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + GetParam() + ".yaml");
  const ConstraintSet constraints(model);
  HessianSolver solver(constraints);
  std::mt19937 rng(20261123);
  std::normal_distribution<double> normal;
  const Eigen::VectorXd u = model.home_controls();
  EnergyDerivatives d;
  for (int trial = 0; trial < 4; ++trial) {
    // Exact Hessians at home (assembled: E = 0) and at seeded random states
    // around it (E > 0: the second-order terms make H indefinite in
    // general). Far from any assembly (random poses) an LDL^T without
    // pivoting has no useful accuracy bound, in either implementation.
    State s = State::Home(model);
    if (trial > 0) {
      Eigen::VectorXd ds(s.tangent_size());
      for (Eigen::Index i = 0; i < ds.size(); ++i) ds[i] = 0.05 * trial * normal(rng);
      s.Plus(ds);
    }
    constraints.EvaluateDerivatives(s, u, &d);
    if (!solver.Factorize(d.H)) {
      ADD_FAILURE() << "state " << trial << ": factorisation failed";
      continue;
    }
    ExpectSameFactorisation(solver, d.H, &rng, "state " + std::to_string(trial));
  }
  for (double shift : {50.0, 0.0}) {  // positive definite, indefinite
    const SparseColMajor H = RandomSymmetric(constraints.hessian_pattern(), shift, &rng);
    ASSERT_TRUE(solver.Factorize(H));
    if (shift > 0) EXPECT_GT(solver.pivot_ratio(), 0);
    ExpectSameFactorisation(solver, H, &rng, "random, shift " + std::to_string(shift));
  }
}

INSTANTIATE_TEST_SUITE_P(Bundled, HessianSolverAgainstEigen, ::testing::ValuesIn(testing::BundledModels()));

TEST(HessianSolver, FailsOnAZeroOrNonFinitePivot) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const ConstraintSet constraints(model);
  HessianSolver solver(constraints);
  std::mt19937 rng(7);
  SparseColMajor H = RandomSymmetric(constraints.hessian_pattern(), 50, &rng);
  ASSERT_TRUE(solver.Factorize(H));
  EXPECT_TRUE(solver.factorized());
  // The first eliminated coordinate's diagonal entry is its first pivot.
  int first = 0;
  while (solver.permutation().indices()[first] != 0) ++first;
  SparseColMajor zero = H;
  zero.coeffRef(first, first) = 0;
  EXPECT_FALSE(solver.Factorize(zero));
  EXPECT_FALSE(solver.factorized());
  SparseColMajor nan = H;
  nan.coeffRef(first, first) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(solver.Factorize(nan));
  ASSERT_TRUE(solver.Factorize(H));  // and recovers
  EXPECT_GT(solver.pivot_ratio(), 0);
}

// The comparison itself can fail: a factorisation of H checked against a
// matrix that differs from H in one entry by 1e-6 of its size.
TEST(HessianSolver, ComparisonFailsForAnotherMatrix) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/6dof_symmetric.yaml");
  const ConstraintSet constraints(model);
  HessianSolver solver(constraints);
  std::mt19937 rng(11);
  const SparseColMajor H = RandomSymmetric(constraints.hessian_pattern(), 50, &rng);
  ASSERT_TRUE(solver.Factorize(H));
  SparseColMajor other = H;
  other.coeffRef(5, 5) += 1e-6 * H.coeffs().cwiseAbs().maxCoeff();
  ::testing::TestPartResultArray failures;
  {
    const ::testing::ScopedFakeTestPartResultReporter intercept(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &failures);
    ExpectSameFactorisation(solver, other, &rng, "another matrix");
  }
  EXPECT_GE(failures.size(), 1);  // the pivots at least
  ASSERT_TRUE(solver.Factorize(other));
  ExpectSameFactorisation(solver, other, &rng, "the same matrix");
}

}  // namespace
}  // namespace ccma
