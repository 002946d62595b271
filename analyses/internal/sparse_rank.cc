#include "analyses/internal/sparse_rank.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>

#include <Eigen/SPQRSupport>

namespace ccma {
namespace {

using Qr = Eigen::SPQR<SparseMatrixCol>;

// Power iteration for the largest singular value (a rank threshold): each
// iteration one product with A and A^T, linear in the nonzeros.
constexpr int kMaxIterations = 500;
constexpr double kRelativeChange = 1e-10;
// Inverse iteration for the smallest singular value (each iteration two
// triangular solves with R, linear in its nonzeros): up to 2000 iterations,
// until the eigen-residual is 1e-12 of the eigenvalue (the dense SVD and
// this agree to ~1e-9 relative on the bundled models).
constexpr int kMaxInverseIterations = 2000;
constexpr double kEigenResidual = 1e-12;

// A fixed (seeded) start vector of unit norm: no direction is favoured,
// and the same matrix always gives the same number.
Eigen::VectorXd Start(Eigen::Index n) {
  std::mt19937 random(1);
  std::uniform_real_distribution<double> uniform(0.5, 1.5);
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = uniform(random);
  return x.normalized();
}

// The factorisation of A with columns of remaining norm <= threshold
// counted as dependent. Throws std::runtime_error when SuiteSparseQR fails
// (out of memory).
std::unique_ptr<Qr> Factorize(const SparseMatrixCol& A, double threshold) {
  auto qr = std::make_unique<Qr>();
  qr->setPivotThreshold(threshold);
  qr->compute(A);
  if (qr->info() != Eigen::Success) throw std::runtime_error("sparse QR factorisation failed");
  return qr;
}

}  // namespace

double LargestSingularValue(const SparseMatrixCol& A) {
  if (A.rows() == 0 || A.cols() == 0 || A.nonZeros() == 0) return 0;
  Eigen::VectorXd x = Start(A.cols());
  double sigma = 0;
  for (int it = 0; it < kMaxIterations; ++it) {
    const Eigen::VectorXd y = A * x;
    const double next = y.norm();
    Eigen::VectorXd z = A.transpose() * y;
    if (z.norm() == 0) return next;
    x = z.normalized();
    const bool settled = std::abs(next - sigma) <= kRelativeChange * next;
    sigma = next;
    if (settled) break;
  }
  return sigma;
}

int SparseRank(const SparseMatrixCol& A, double threshold) {
  if (A.rows() == 0 || A.cols() == 0) return 0;
  return static_cast<int>(Factorize(A, threshold)->rank());
}

double SmallestSingularValue(const SparseMatrixCol& A, double threshold) {
  const Eigen::Index n = A.cols();
  if (n == 0 || A.rows() < n) return 0;
  const std::unique_ptr<Qr> qr = Factorize(A, threshold);
  if (qr->rank() < n) return 0;
  // sigma_min(A) = sigma_min(R) = 1 / sqrt(largest eigenvalue of (R^T R)^-1).
  // Copied through the other storage order: sorted inner indices, as the
  // triangular solves expect (the diagonal last in each column of R).
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = qr->matrixR().topLeftCorner(n, n);
  const SparseMatrixCol Rn = rows;
  Eigen::VectorXd x = Start(n);
  double mu = 0;
  for (int it = 0; it < kMaxInverseIterations; ++it) {
    const Eigen::VectorXd y = Rn.transpose().triangularView<Eigen::Lower>().solve(x);
    const Eigen::VectorXd z = Rn.triangularView<Eigen::Upper>().solve(y);
    mu = x.dot(z);  // Rayleigh quotient of (R^T R)^-1, |x| = 1
    // |z - mu x| bounds the distance of mu from an eigenvalue (symmetric
    // matrix): a criterion that a slow creep through a cluster cannot fool.
    const bool settled = (z - mu * x).norm() <= kEigenResidual * mu;
    x = z.normalized();
    if (settled) break;
  }
  return mu > 0 ? 1 / std::sqrt(mu) : 0;
}

Eigen::MatrixXd SparseNullSpace(const SparseMatrixCol& A, double threshold) {
  const Eigen::Index n = A.cols();
  if (A.rows() == 0) return Eigen::MatrixXd::Identity(n, n);
  const SparseMatrixCol At = A.transpose();
  const std::unique_ptr<Qr> qr = Factorize(At, threshold);
  const Eigen::Index rank = qr->rank();
  Eigen::MatrixXd pick = Eigen::MatrixXd::Zero(n, n - rank);
  pick.bottomRows(n - rank).setIdentity();
  return qr->matrixQ() * pick;
}

std::vector<bool> OutsideRange(const SparseMatrixCol& A, const Eigen::MatrixXd& columns, double threshold) {
  std::vector<bool> outside(static_cast<size_t>(columns.cols()), false);
  if (columns.cols() == 0) return outside;
  const std::unique_ptr<Qr> qr = Factorize(A, threshold);
  const Eigen::Index rank = qr->rank();
  // In batches: Q^T applied to a few columns at a time keeps the dense
  // workspace at rows x 64.
  for (Eigen::Index first = 0; first < columns.cols(); first += 64) {
    const Eigen::Index count = std::min<Eigen::Index>(64, columns.cols() - first);
    const Eigen::MatrixXd y = qr->matrixQ().transpose() * columns.middleCols(first, count);
    for (Eigen::Index c = 0; c < count; ++c) {
      outside[static_cast<size_t>(first + c)] = y.col(c).tail(y.rows() - rank).norm() > threshold;
    }
  }
  return outside;
}

}  // namespace ccma
