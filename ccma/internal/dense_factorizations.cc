#include "ccma/internal/dense_factorizations.h"

#include <algorithm>
#include <atomic>
#include <cmath>

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

// ------------------------------------------- RankRevealingDecomposition ---
namespace {

std::atomic<RankDecisionObserver> rank_decision_observer{nullptr};

}  // namespace

void SetRankDecisionObserver(RankDecisionObserver observer) { rank_decision_observer = observer; }

RankRevealingDecomposition::RankRevealingDecomposition(const Eigen::MatrixXd& A, Threshold threshold,
                                                       Method method) {
  if (const RankDecisionObserver observer = rank_decision_observer.load()) observer(A, threshold, method);
  const Eigen::Index n = A.cols();
  threshold_ = threshold.absolute;
  if (A.size() == 0) {  // no rows: everything is null
    row_space_.resize(n, 0);
    null_space_ = Eigen::MatrixXd::Identity(n, n);
    return;
  }
  if (method == Method::kJacobiSvd) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
    const Eigen::VectorXd& sigma = svd.singularValues();
    threshold_ = std::max(threshold.absolute, threshold.relative * (sigma.size() > 0 ? sigma[0] : 0.0));
    while (rank_ < sigma.size() && sigma[rank_] > threshold_) ++rank_;
    row_space_ = svd.matrixV().leftCols(rank_);
    null_space_ = svd.matrixV().rightCols(n - rank_);
    return;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::Index p = std::min(A.rows(), n);
  threshold_ = std::max(threshold.absolute, threshold.relative * std::abs(qr.matrixQR()(0, 0)));
  // The pivots do not increase (each is the largest remaining column norm).
  while (rank_ < p && std::abs(qr.matrixQR()(rank_, rank_)) > threshold_) ++rank_;
  // null(A) = P null(R_top), R_top the leading rank rows of R (the rows
  // beyond are below the threshold): R_top^T = H [T; 0] gives
  // null(R_top) = H [0; I] and its complement H [I; 0].
  const Eigen::MatrixXd R_top = qr.matrixQR().topRows(rank_).triangularView<Eigen::Upper>();
  const Eigen::HouseholderQR<Eigen::MatrixXd> h(R_top.transpose());
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(n, n);
  if (rank_ > 0) H.applyOnTheLeft(h.householderQ());
  row_space_ = qr.colsPermutation() * H.leftCols(rank_);
  null_space_ = qr.colsPermutation() * H.rightCols(n - rank_);
}

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
Eigen::VectorXd MinimumNormSolver::solveTransposed(const Eigen::VectorXd& b) const {
  return impl_->cod.transpose().solve(b);
}
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
