#include "ccma/internal/dense_factorizations.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

namespace ccma {

// ------------------------------------------------------------ JacobiSvd ---
struct JacobiSvd::Impl {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd;
};
JacobiSvd::JacobiSvd(const Eigen::MatrixXd& A, unsigned int options)
    : impl_(new Impl{Eigen::JacobiSVD<Eigen::MatrixXd>(A, options)}) {}
JacobiSvd::JacobiSvd(const JacobiSvd& other) : impl_(new Impl(*other.impl_)) {}
JacobiSvd& JacobiSvd::operator=(const JacobiSvd& other) {
  *impl_ = *other.impl_;
  return *this;
}
JacobiSvd::~JacobiSvd() = default;
const Eigen::VectorXd& JacobiSvd::singularValues() const { return impl_->svd.singularValues(); }
const Eigen::MatrixXd& JacobiSvd::matrixU() const { return impl_->svd.matrixU(); }
const Eigen::MatrixXd& JacobiSvd::matrixV() const { return impl_->svd.matrixV(); }

// --------------------------------------------------------------- BdcSvd ---
struct BdcSvd::Impl {
  Eigen::BDCSVD<Eigen::MatrixXd> svd;
};
BdcSvd::BdcSvd(const Eigen::MatrixXd& A, unsigned int options)
    : impl_(new Impl{Eigen::BDCSVD<Eigen::MatrixXd>(A, options)}) {}
BdcSvd::BdcSvd(const BdcSvd& other) : impl_(new Impl(*other.impl_)) {}
BdcSvd& BdcSvd::operator=(const BdcSvd& other) {
  *impl_ = *other.impl_;
  return *this;
}
BdcSvd::~BdcSvd() = default;
const Eigen::VectorXd& BdcSvd::singularValues() const { return impl_->svd.singularValues(); }
const Eigen::MatrixXd& BdcSvd::matrixU() const { return impl_->svd.matrixU(); }
const Eigen::MatrixXd& BdcSvd::matrixV() const { return impl_->svd.matrixV(); }

// -------------------------------------------------- SymmetricEigenSolver ---
struct SymmetricEigenSolver::Impl {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen;
};
SymmetricEigenSolver::SymmetricEigenSolver() : impl_(new Impl) {}
SymmetricEigenSolver::SymmetricEigenSolver(const Eigen::MatrixXd& A)
    : impl_(new Impl{Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A)}) {}
SymmetricEigenSolver::SymmetricEigenSolver(const SymmetricEigenSolver& other) : impl_(new Impl(*other.impl_)) {}
SymmetricEigenSolver& SymmetricEigenSolver::operator=(const SymmetricEigenSolver& other) {
  *impl_ = *other.impl_;
  return *this;
}
SymmetricEigenSolver::~SymmetricEigenSolver() = default;
SymmetricEigenSolver& SymmetricEigenSolver::compute(const Eigen::MatrixXd& A) {
  impl_->eigen.compute(A);
  return *this;
}
const Eigen::VectorXd& SymmetricEigenSolver::eigenvalues() const { return impl_->eigen.eigenvalues(); }
const Eigen::MatrixXd& SymmetricEigenSolver::eigenvectors() const { return impl_->eigen.eigenvectors(); }

// ----------------------------------------------------- MinimumNormSolver ---
struct MinimumNormSolver::Impl {
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
};
MinimumNormSolver::MinimumNormSolver() : impl_(new Impl) {}
MinimumNormSolver::MinimumNormSolver(const Eigen::MatrixXd& A)
    : impl_(new Impl{Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(A)}) {}
MinimumNormSolver::MinimumNormSolver(const MinimumNormSolver& other) : impl_(new Impl(*other.impl_)) {}
MinimumNormSolver& MinimumNormSolver::operator=(const MinimumNormSolver& other) {
  *impl_ = *other.impl_;
  return *this;
}
MinimumNormSolver::~MinimumNormSolver() = default;
MinimumNormSolver& MinimumNormSolver::setThreshold(double threshold) {
  impl_->cod.setThreshold(threshold);
  return *this;
}
MinimumNormSolver& MinimumNormSolver::compute(const Eigen::MatrixXd& A) {
  impl_->cod.compute(A);
  return *this;
}
Eigen::Index MinimumNormSolver::rows() const { return impl_->cod.rows(); }
Eigen::Index MinimumNormSolver::cols() const { return impl_->cod.cols(); }
Eigen::Index MinimumNormSolver::rank() const { return impl_->cod.rank(); }
Eigen::VectorXd MinimumNormSolver::solve(const Eigen::VectorXd& b) const { return impl_->cod.solve(b); }
Eigen::MatrixXd MinimumNormSolver::solveMatrix(const Eigen::MatrixXd& B) const { return impl_->cod.solve(B); }
Eigen::MatrixXd MinimumNormSolver::nullSpace() const {
  const Eigen::Index n = cols(), r = rank();
  return impl_->cod.colsPermutation() * impl_->cod.matrixZ().transpose().rightCols(n - r);
}
Eigen::MatrixXd MinimumNormSolver::leftNullSpace() const {
  const Eigen::Index m = rows(), r = rank();
  Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(m, m - r);
  basis.bottomRows(m - r).setIdentity();
  basis.applyOnTheLeft(impl_->cod.householderQ());
  return basis;
}

}  // namespace ccma
