// Eigen's dense factorizations of dynamic matrices, compiled once.
//
// Why: instantiating one of Eigen's decompositions for MatrixXd costs 9 to
// 13 s of compiler time in every translation unit or unity batch that uses it
// (JacobiSVD 12.5 s, CompleteOrthogonalDecomposition 11 s,
// SelfAdjointEigenSolver 9 s at -O3 alone; a test with Eigen::BDCSVD compiles
// in 50 s, with these in 12 s; benchmarks/RESULTS.md, "Build and test times"). These thin classes keep Eigen's names and semantics (the same
// algorithms, options and results, bit for bit) but are instantiated only in
// dense_factorizations.cc; their users include <Eigen/Core> alone.
//
// Each object owns its Eigen decomposition (one allocation when made, reused
// by compute()), so a workspace that keeps one reuses its storage.
#ifndef CCMA_INTERNAL_DENSE_FACTORIZATIONS_H_
#define CCMA_INTERNAL_DENSE_FACTORIZATIONS_H_

#include <memory>

#include <Eigen/Core>

namespace ccma {

// Eigen::JacobiSVD<MatrixXd> (two-sided Jacobi, column-pivoting QR
// preconditioner). options: Eigen::ComputeThinU | ComputeFullV etc., or 0
// for the singular values alone. Singular values in decreasing order.
class JacobiSvd {
 public:
  explicit JacobiSvd(const Eigen::MatrixXd& A, unsigned int options = 0);
  JacobiSvd(const JacobiSvd& other);
  JacobiSvd& operator=(const JacobiSvd& other);
  ~JacobiSvd();
  const Eigen::VectorXd& singularValues() const;
  const Eigen::MatrixXd& matrixU() const;  // requires ComputeThinU or ComputeFullU
  const Eigen::MatrixXd& matrixV() const;  // requires ComputeThinV or ComputeFullV

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A numerical rank and orthonormal bases of the null space and of the row
// space of A (rows x cols, any shape), for the rank decisions of the dense
// analyses. A singular value (kJacobiSvd) or a pivot |R_kk| of the column-
// pivoting QR A P = Q R (kPivotedQr) counts towards the rank when above
//   max(threshold.absolute, threshold.relative * scale),
// scale = sigma_max(A) (kJacobiSvd) or the largest pivot |R_11|, A's largest
// column norm, between sigma_max / sqrt(cols) and sigma_max (kPivotedQr, as
// Eigen's own rank-revealing QRs; a caller that wants sigma_max scales
// `absolute` itself, e.g. by analyses/internal/sparse_rank.h's
// LargestSingularValue of a sparse view).
//
// Why not Eigen's BDCSVD: Eigen 3.4.0's BDCSVD::perturbCol0 reads the
// deflation permutation at index -1 on some matrices (battobot_6d's dC/ds
// among them, tests/data/rank_decisions/README.md): an assertion in a
// build with assertions, in a release build a read of a neighbouring
// workspace entry that can give wrong singular values without a word.
//   kJacobiSvd: the SVD (Eigen::JacobiSVD, V in full): the most accurate;
//     bases = V's columns past / up to the rank, exactly as BDCSVD gave
//     them below 16 columns (where it runs this same Jacobi SVD); 7 to 14
//     times BDCSVD's time at hundreds of columns (benchmarks/RESULTS.md,
//     "Rank decisions"): the reference, and for small matrices.
//   kPivotedQr: ColPivHouseholderQR of A, rank from its pivots, then a
//     Householder QR of the leading rank rows of R, transposed (a complete
//     orthogonal decomposition): 2 to 7 times faster than BDCSVD on the
//     tens to hundreds of columns of the sites' matrices, which have a wide
//     gap between the singular values that count and those at rounding
//     level (tests/rank_decisions_test.cc checks the decisions on every
//     model against the SVD's).
class RankRevealingDecomposition {
 public:
  enum class Method { kJacobiSvd, kPivotedQr };
  struct Threshold {
    double absolute = 0.0;
    double relative = 0.0;
  };
  RankRevealingDecomposition(const Eigen::MatrixXd& A, Threshold threshold, Method method);
  int rank() const { return rank_; }
  double threshold() const { return threshold_; }  // the absolute bound applied
  // cols x (cols - rank) and cols x rank, orthonormal, together an
  // orthonormal basis of R^cols.
  const Eigen::MatrixXd& nullSpace() const { return null_space_; }
  const Eigen::MatrixXd& rowSpace() const { return row_space_; }

 private:
  int rank_ = 0;
  double threshold_ = 0.0;
  Eigen::MatrixXd null_space_, row_space_;
};

// For tests (tests/rank_decisions_test.cc): when set, every
// RankRevealingDecomposition passes its matrix and threshold to `observer`
// first. nullptr (the default) to stop. Not for concurrent use with the
// decompositions it observes.
using RankDecisionObserver = void (*)(const Eigen::MatrixXd& A, const RankRevealingDecomposition::Threshold& threshold,
                                      RankRevealingDecomposition::Method method);
void SetRankDecisionObserver(RankDecisionObserver observer);

// Eigen::SelfAdjointEigenSolver<MatrixXd>: eigenvalues in increasing order,
// orthonormal eigenvectors as columns. Reads the lower triangle.
class SymmetricEigenSolver {
 public:
  SymmetricEigenSolver();
  explicit SymmetricEigenSolver(const Eigen::MatrixXd& A);
  SymmetricEigenSolver(const SymmetricEigenSolver& other);
  SymmetricEigenSolver& operator=(const SymmetricEigenSolver& other);
  ~SymmetricEigenSolver();
  SymmetricEigenSolver& compute(const Eigen::MatrixXd& A);
  const Eigen::VectorXd& eigenvalues() const;
  const Eigen::MatrixXd& eigenvectors() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Eigen::CompleteOrthogonalDecomposition<MatrixXd>: the minimum-norm
// least-squares solution of A x = b; rank() counts pivots above the
// threshold (relative to the largest, Eigen's default unless set).
class MinimumNormSolver {
 public:
  MinimumNormSolver();
  explicit MinimumNormSolver(const Eigen::MatrixXd& A);
  MinimumNormSolver(const MinimumNormSolver& other);
  MinimumNormSolver& operator=(const MinimumNormSolver& other);
  ~MinimumNormSolver();
  MinimumNormSolver& setThreshold(double threshold);
  MinimumNormSolver& compute(const Eigen::MatrixXd& A);
  Eigen::Index rows() const;  // of A; 0 before compute()
  Eigen::Index cols() const;
  Eigen::Index rank() const;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  Eigen::MatrixXd solveMatrix(const Eigen::MatrixXd& B) const;  // column by column, as Eigen's solve
  // The minimum-norm least-squares solution of A^T x = b (b: cols(),
  // x: rows()) from the same decomposition (Eigen's transpose().solve()):
  // a caller that needs both A's and A^T's solutions factorises once.
  Eigen::VectorXd solveTransposed(const Eigen::VectorXd& b) const;
  // Orthonormal bases from the decomposition A P = Q [T 0; 0 0] Z: of the
  // null space of A (P Z^T [0; I], cols x (cols - rank)) and of the null
  // space of A^T (Q [0; I], rows x (rows - rank)).
  Eigen::MatrixXd nullSpace() const;
  Eigen::MatrixXd leftNullSpace() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ccma

#endif  // CCMA_INTERNAL_DENSE_FACTORIZATIONS_H_
