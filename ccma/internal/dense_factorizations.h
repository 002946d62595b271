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

// Eigen::BDCSVD<MatrixXd> (divide and conquer: faster on large matrices;
// Jacobi below 16 columns), same interface and ordering as JacobiSvd.
class BdcSvd {
 public:
  explicit BdcSvd(const Eigen::MatrixXd& A, unsigned int options = 0);
  BdcSvd(const BdcSvd& other);
  BdcSvd& operator=(const BdcSvd& other);
  ~BdcSvd();
  const Eigen::VectorXd& singularValues() const;
  const Eigen::MatrixXd& matrixU() const;
  const Eigen::MatrixXd& matrixV() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

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
