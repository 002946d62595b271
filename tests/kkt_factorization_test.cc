// The loaded equilibrium's KKT factorisation (problems/internal/
// kkt_factorization.h) against a dense LU of the same matrices: seeded
// quasi-definite KKT systems, the analysis kept while the pattern stays
// within the one analysed (numeric zeros that come and go) and redone for a
// new entry or size, and the LU taking over where the LDL^T has no pivot.
#include <random>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "problems/internal/kkt_factorization.h"

namespace ccma {
namespace kkt_factorization_test {

using Sparse = KktFactorization::Sparse;

// [H, A^T; A, -eps I] with H = B B^T + I (n x n, a band of 3) and A (m x n,
// 3 entries a row), seeded; `drop` entries of A set to exact zeros (kept in
// the pattern only if `keep_zeros`).
Sparse RandomKkt(int n, int m, double eps, unsigned seed, int drop = 0, bool keep_zeros = false) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1, 1);
  std::uniform_int_distribution<int> column(0, n - 1);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = std::max(0, i - 1); j <= std::min(n - 1, i + 1); ++j) B(i, j) = value(rng);
  }
  const Eigen::MatrixXd H = B * B.transpose() + Eigen::MatrixXd::Identity(n, n);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (H(i, j) != 0) t.emplace_back(i, j, H(i, j));
    }
  }
  int dropped = 0;
  for (int r = 0; r < m; ++r) {
    for (int k = 0; k < 3; ++k) {
      const int c = column(rng);
      double a = value(rng);
      if (dropped < drop && k == 0) {
        a = 0;
        ++dropped;
        if (!keep_zeros) continue;
      }
      t.emplace_back(n + r, c, a);
      t.emplace_back(c, n + r, a);
    }
    t.emplace_back(n + r, n + r, -eps);
  }
  Sparse K(n + m, n + m);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

double SolveError(KktFactorization& kkt, const Sparse& K, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, 1);
  Eigen::VectorXd rhs(K.rows());
  for (Eigen::Index i = 0; i < rhs.size(); ++i) rhs[i] = n(rng);
  const Eigen::VectorXd expected = Eigen::MatrixXd(K).partialPivLu().solve(rhs);
  return (kkt.Solve(rhs) - expected).lpNorm<Eigen::Infinity>() / expected.lpNorm<Eigen::Infinity>();
}

TEST(KktFactorization, SolvesQuasiDefiniteSystemsAsADenseLuDoes) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Sparse K = RandomKkt(40, 15, 1e-6, seed);
    KktFactorization kkt;
    ASSERT_TRUE(kkt.Factorize(K));
    EXPECT_FALSE(kkt.uses_lu());
    EXPECT_LT(SolveError(kkt, K, 100 + seed), 1e-10) << "seed " << seed;
  }
}

TEST(KktFactorization, KeepsItsAnalysisWhileThePatternStaysWithinIt) {
  KktFactorization kkt;
  // The full pattern first (the zeros stored), then the same matrix with
  // those zeros left out: one analysis for both.
  ASSERT_TRUE(kkt.Factorize(RandomKkt(30, 10, 1e-6, 7, 4, /*keep_zeros=*/true)));
  const Sparse fewer = RandomKkt(30, 10, 1e-6, 7, 4, /*keep_zeros=*/false);
  ASSERT_LT(fewer.nonZeros(), RandomKkt(30, 10, 1e-6, 7, 4, true).nonZeros());
  ASSERT_TRUE(kkt.Factorize(fewer));
  EXPECT_EQ(kkt.analyses(), 1);
  EXPECT_LT(SolveError(kkt, fewer, 3), 1e-10);
  // New values on the same pattern: still one.
  Sparse scaled = fewer * 2.0;
  ASSERT_TRUE(kkt.Factorize(scaled));
  EXPECT_EQ(kkt.analyses(), 1);
  EXPECT_LT(SolveError(kkt, scaled, 4), 1e-10);
  // An entry outside it: analysed again, for the union.
  Sparse wider = scaled;
  wider.coeffRef(0, 29) += 0.25;
  wider.coeffRef(29, 0) += 0.25;
  ASSERT_TRUE(kkt.Factorize(wider));
  EXPECT_EQ(kkt.analyses(), 2);
  EXPECT_LT(SolveError(kkt, wider, 5), 1e-10);
  ASSERT_TRUE(kkt.Factorize(scaled));  // within the union
  EXPECT_EQ(kkt.analyses(), 2);
  // Another size (another model's): analysed again.
  const Sparse other = RandomKkt(20, 6, 1e-6, 8);
  ASSERT_TRUE(kkt.Factorize(other));
  EXPECT_EQ(kkt.analyses(), 3);
  EXPECT_LT(SolveError(kkt, other, 6), 1e-10);
}

TEST(KktFactorization, TheLuTakesOverWhereTheLdltHasNoPivot) {
  // [0 1; 1 0] (a rigid row on a motion nothing else resists, unregularised):
  // no LDL^T without pivoting in any order.
  Sparse K(2, 2);
  K.insert(0, 1) = 1;
  K.insert(1, 0) = 1;
  KktFactorization kkt;
  ASSERT_TRUE(kkt.Factorize(K));
  EXPECT_TRUE(kkt.uses_lu());
  const Eigen::VectorXd z = kkt.Solve(Eigen::Vector2d(3, -5));
  EXPECT_DOUBLE_EQ(z[0], -5);
  EXPECT_DOUBLE_EQ(z[1], 3);
  // And on request for a matrix the LDL^T could factorise.
  const Sparse Q = RandomKkt(25, 8, 1e-6, 9);
  ASSERT_TRUE(kkt.Factorize(Q));
  EXPECT_FALSE(kkt.uses_lu());
  ASSERT_TRUE(kkt.UseLu());
  EXPECT_TRUE(kkt.uses_lu());
  EXPECT_LT(SolveError(kkt, Q, 10), 1e-10);
  // A singular matrix: neither.
  EXPECT_FALSE(kkt.Factorize(Sparse(3, 3)));
}

}  // namespace kkt_factorization_test
}  // namespace ccma
