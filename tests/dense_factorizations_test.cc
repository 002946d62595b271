// The compiled-once wrappers of Eigen's dense decompositions
// (tests/dense_factorizations.h) against what defines them: A = U S V^T
// with orthonormal factors, A v = lambda v, the minimum-norm least-squares
// solution and null spaces, ranks and complementary orthonormal bases, the
// largest singular value, on seeded random rank-deficient matrices.
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "ccma/internal/dense_factorizations.h"

namespace ccma {
namespace dense_factorizations_test {

// rows x cols of rank r (r <= min(rows, cols)), entries of order 1.
Eigen::MatrixXd RankDeficient(int rows, int cols, int r, std::mt19937* rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd L(rows, r), R(r, cols);
  for (int i = 0; i < L.size(); ++i) L.data()[i] = normal(*rng);
  for (int i = 0; i < R.size(); ++i) R.data()[i] = normal(*rng);
  return L * R;
}

double Orthonormality(const Eigen::MatrixXd& Q) {
  return (Q.transpose() * Q - Eigen::MatrixXd::Identity(Q.cols(), Q.cols())).cwiseAbs().maxCoeff();
}

TEST(DenseFactorizations, SvdsRebuildTheMatrix) {
  std::mt19937 rng(7);
  const Eigen::MatrixXd A = RankDeficient(9, 6, 4, &rng);
  const JacobiSvd jacobi(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const JacobiSvd full(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  EXPECT_LT((jacobi.matrixU() * jacobi.singularValues().asDiagonal() * jacobi.matrixV().transpose() - A)
                .cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(Orthonormality(full.matrixU()), 1e-12);
  EXPECT_LT(Orthonormality(full.matrixV()), 1e-12);
  EXPECT_EQ(full.matrixU().cols(), 9);
  EXPECT_EQ(full.singularValues(), jacobi.singularValues());
  EXPECT_LT(jacobi.singularValues()[4], 1e-12);  // rank 4
  EXPECT_GT(jacobi.singularValues()[3], 1e-3);
  EXPECT_EQ(JacobiSvd(A).singularValues(), jacobi.singularValues());  // values alone: the same numbers
}

TEST(DenseFactorizations, SymmetricEigenSolverDiagonalises) {
  std::mt19937 rng(8);
  const Eigen::MatrixXd B = RankDeficient(7, 7, 7, &rng);
  const Eigen::MatrixXd A = B + B.transpose();
  SymmetricEigenSolver eigen;
  eigen.compute(A);
  const Eigen::MatrixXd& V = eigen.eigenvectors();
  EXPECT_LT((A * V - V * eigen.eigenvalues().asDiagonal()).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LT(Orthonormality(V), 1e-12);
  for (int i = 1; i < 7; ++i) EXPECT_LE(eigen.eigenvalues()[i - 1], eigen.eigenvalues()[i]);
  const SymmetricEigenSolver copy = eigen;  // deep copy: the same numbers
  EXPECT_EQ(copy.eigenvalues(), eigen.eigenvalues());
}

TEST(DenseFactorizations, MinimumNormSolverAndNullSpaces) {
  std::mt19937 rng(9);
  for (const auto& [rows, cols, r] : {std::tuple{8, 5, 3}, std::tuple{5, 8, 3}, std::tuple{6, 6, 6}}) {
    const Eigen::MatrixXd A = RankDeficient(rows, cols, r, &rng);
    MinimumNormSolver solver;
    solver.setThreshold(1e-10).compute(A);
    ASSERT_EQ(solver.rank(), r);
    const Eigen::MatrixXd N = solver.nullSpace(), L = solver.leftNullSpace();
    ASSERT_EQ(N.rows(), cols);
    ASSERT_EQ(N.cols(), cols - r);
    ASSERT_EQ(L.rows(), rows);
    ASSERT_EQ(L.cols(), rows - r);
    if (N.size() > 0) {
      EXPECT_LT((A * N).cwiseAbs().maxCoeff(), 1e-12);
      EXPECT_LT(Orthonormality(N), 1e-12);
    }
    if (L.size() > 0) {
      EXPECT_LT((A.transpose() * L).cwiseAbs().maxCoeff(), 1e-12);
      EXPECT_LT(Orthonormality(L), 1e-12);
    }
    // Least squares (normal equations) and minimum norm (nothing along null(A)).
    Eigen::VectorXd b(rows);
    for (int i = 0; i < rows; ++i) b[i] = std::normal_distribution<double>()(rng);
    const Eigen::VectorXd x = solver.solve(b);
    EXPECT_LT((A.transpose() * (A * x - b)).cwiseAbs().maxCoeff(), 1e-11);
    if (N.size() > 0) EXPECT_LT((N.transpose() * x).cwiseAbs().maxCoeff(), 1e-12);
    const Eigen::MatrixXd X = solver.solveMatrix(Eigen::MatrixXd(b.replicate(1, 2)));
    EXPECT_LT((X.col(1) - x).cwiseAbs().maxCoeff(), 1e-14);
  }
}

// solveTransposed: the minimum-norm least-squares solution of A^T y = c from
// A's decomposition (normal equations, nothing along null(A^T)), as a
// decomposition of A^T gives it.
TEST(DenseFactorizations, MinimumNormSolverSolvesTheTransposedSystem) {
  std::mt19937 rng(10);
  for (const auto& [rows, cols, r] : {std::tuple{8, 5, 3}, std::tuple{5, 8, 3}, std::tuple{6, 6, 6}}) {
    const Eigen::MatrixXd A = RankDeficient(rows, cols, r, &rng);
    MinimumNormSolver solver, transposed;
    solver.setThreshold(1e-10).compute(A);
    transposed.setThreshold(1e-10).compute(A.transpose());
    Eigen::VectorXd c(cols);
    for (int i = 0; i < cols; ++i) c[i] = std::normal_distribution<double>()(rng);
    const Eigen::VectorXd y = solver.solveTransposed(c);
    ASSERT_EQ(y.size(), rows);
    EXPECT_LT((A * (A.transpose() * y - c)).cwiseAbs().maxCoeff(), 1e-11);
    const Eigen::MatrixXd L = solver.leftNullSpace();
    if (L.size() > 0) EXPECT_LT((L.transpose() * y).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((y - transposed.solve(c)).cwiseAbs().maxCoeff(), 1e-11);
  }
}

// Both methods: the rank of L R (rank r, singular values of order 1 and
// rounding), orthonormal bases of null(A) and its complement.
TEST(DenseFactorizations, RankRevealingDecompositionsGiveRankAndBases) {
  std::mt19937 rng(10);
  using Method = RankRevealingDecomposition::Method;
  for (const Method method : {Method::kJacobiSvd, Method::kPivotedQr}) {
    for (const auto& [rows, cols, r] : {std::tuple{8, 5, 3}, std::tuple{5, 8, 3}, std::tuple{30, 40, 22},
                                        std::tuple{6, 6, 6}, std::tuple{4, 7, 0}}) {
      const Eigen::MatrixXd A = RankDeficient(rows, cols, r, &rng);
      const RankRevealingDecomposition d(A, {1e-9, 0.0}, method);
      ASSERT_EQ(d.rank(), r) << rows << "x" << cols;
      const Eigen::MatrixXd& N = d.nullSpace();
      const Eigen::MatrixXd& W = d.rowSpace();
      ASSERT_EQ(N.rows(), cols);
      ASSERT_EQ(N.cols(), cols - r);
      ASSERT_EQ(W.rows(), cols);
      ASSERT_EQ(W.cols(), r);
      Eigen::MatrixXd both(cols, cols);
      both << W, N;
      EXPECT_LT(Orthonormality(both), 1e-12);
      if (N.size() > 0) EXPECT_LT((A * N).cwiseAbs().maxCoeff(), 1e-12);
      // The row space: A's rows lie in it (A W W^T = A).
      EXPECT_LT((A * W * W.transpose() - A).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
}

// The threshold: max(absolute, relative * scale), scale sigma_max (SVD) or
// the largest pivot (QR, between sigma_max / 2 and sigma_max here);
// singular values 10, 1, 1e-3, 1e-7.
TEST(DenseFactorizations, RankThresholdIsAbsoluteOrRelative) {
  std::mt19937 rng(11);
  const Eigen::MatrixXd U = JacobiSvd(RankDeficient(7, 4, 4, &rng), Eigen::ComputeThinU).matrixU();
  const Eigen::MatrixXd V = JacobiSvd(RankDeficient(6, 4, 4, &rng), Eigen::ComputeThinU).matrixU();
  const Eigen::MatrixXd A = U * Eigen::Vector4d(10, 1, 1e-3, 1e-7).asDiagonal() * V.transpose();  // 7 x 6
  using Method = RankRevealingDecomposition::Method;
  for (const Method method : {Method::kJacobiSvd, Method::kPivotedQr}) {
    EXPECT_EQ(RankRevealingDecomposition(A, {0.5, 0.0}, method).rank(), 2);
    EXPECT_EQ(RankRevealingDecomposition(A, {1e-5, 0.0}, method).rank(), 3);
    EXPECT_EQ(RankRevealingDecomposition(A, {1e-9, 0.0}, method).rank(), 4);
    EXPECT_EQ(RankRevealingDecomposition(Eigen::MatrixXd::Zero(3, 5), {0.0, 0.0}, method).rank(), 0);
    EXPECT_EQ(RankRevealingDecomposition(Eigen::MatrixXd::Zero(3, 5), {0.0, 0.0}, method).nullSpace().cols(), 5);
    EXPECT_EQ(RankRevealingDecomposition(Eigen::MatrixXd(0, 4), {1e-9, 0.0}, method).nullSpace().cols(), 4);
  }
  EXPECT_EQ(RankRevealingDecomposition(A, {1e-9, 1e-5}, Method::kJacobiSvd).rank(), 3);  // 1e-4 absolute
  const RankRevealingDecomposition d(A, {1e-9, 1e-2}, Method::kJacobiSvd);
  EXPECT_NEAR(d.threshold(), 0.1, 1e-12);
  EXPECT_EQ(d.rank(), 2);
  const RankRevealingDecomposition qr(A, {1e-9, 1e-5}, Method::kPivotedQr);
  EXPECT_EQ(qr.rank(), 3);
  EXPECT_GE(qr.threshold(), 1e-5 * 10 / 2);
  EXPECT_LE(qr.threshold(), 1e-5 * 10 * (1 + 1e-12));
}

}  // namespace
}  // namespace ccma
