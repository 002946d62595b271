#include "problems/internal/large_lm_system.h"

#include <algorithm>
#include <utility>

#include <Eigen/Cholesky>

namespace ccma {
namespace {

constexpr int kMaxRefinements = 6;
// A refined step's residual within this of the sizes it sums (|g| and
// |M du|); a step that cannot get within 1e-10 of them is refused.
constexpr double kRefinedResidual = 1e-13;
constexpr double kAcceptedResidual = 1e-10;

using Sparse = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

// The columns `columns` of M (any sparse storage) as a column-major matrix.
template <typename SparseIn>
Sparse Columns(const SparseIn& M, const std::vector<int>& columns) {
  std::vector<int> position(static_cast<size_t>(M.cols()), -1);
  for (size_t c = 0; c < columns.size(); ++c) position[static_cast<size_t>(columns[c])] = static_cast<int>(c);
  Triplets t;
  for (Eigen::Index outer = 0; outer < M.outerSize(); ++outer) {
    for (typename SparseIn::InnerIterator it(M, outer); it; ++it) {
      const int c = position[static_cast<size_t>(it.col())];
      if (c >= 0) t.emplace_back(static_cast<int>(it.row()), c, it.value());
    }
  }
  Sparse out(M.rows(), static_cast<Eigen::Index>(columns.size()));
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace

LargeLmSystem::LargeLmSystem(std::shared_ptr<const Sensitivity> sensitivity, std::vector<int> effective,
                             Eigen::MatrixXd J_e, Eigen::VectorXd g, double lambda, LargeLmWorkspace* workspace)
    : sensitivity_(std::move(sensitivity)),
      effective_(std::move(effective)),
      J_e_(std::move(J_e)),
      g_(std::move(g)),
      lambda_(lambda),
      workspace_(workspace) {
  const EnergyDerivatives& d = sensitivity_->derivatives();
  const int n = static_cast<int>(d.H.rows()), k = static_cast<int>(effective_.size());
  B_ = Columns(d.dG_du, effective_);
  J_u_ = Columns(d.J_u, effective_);
  const Sparse D = Sparse(J_u_.transpose()) * J_u_;
  // W's lower triangle: H's, B^T below it, J_u^T J_u's, and every diagonal
  // entry of the controls' block present (mu / lambda goes there).
  Triplets t;
  t.reserve(static_cast<size_t>(d.H.nonZeros() / 2 + n + B_.nonZeros() + D.nonZeros() + k));
  for (Eigen::Index j = 0; j < d.H.outerSize(); ++j) {
    for (SparseColMajor::InnerIterator it(d.H, j); it; ++it) {
      if (it.row() >= j) t.emplace_back(static_cast<int>(it.row()), static_cast<int>(j), it.value());
    }
  }
  for (int c = 0; c < k; ++c) {
    for (Sparse::InnerIterator it(B_, c); it; ++it) t.emplace_back(n + c, static_cast<int>(it.row()), it.value());
    t.emplace_back(n + c, n + c, 0.0);
  }
  for (int c = 0; c < k; ++c) {
    for (Sparse::InnerIterator it(D, c); it; ++it) {
      if (it.row() >= c) t.emplace_back(n + static_cast<int>(it.row()), n + c, it.value());
    }
  }
  W_.resize(n + k, n + k);
  W_.setFromTriplets(t.begin(), t.end());
  if (workspace_->analysed_size != W_.rows() || workspace_->analysed_nonzeros != W_.nonZeros()) {
    workspace_->ldlt.analyzePattern(W_);
    workspace_->analysed_size = W_.rows();
    workspace_->analysed_nonzeros = W_.nonZeros();
  }
}

bool LargeLmSystem::Factorize(double mu) const {
  if (mu == factorised_mu_) return true;
  Sparse W = W_;
  const Eigen::Index n = W.rows() - static_cast<Eigen::Index>(effective_.size());
  for (Eigen::Index i = n; i < W.rows(); ++i) W.coeffRef(i, i) += mu / lambda_;
  workspace_->ldlt.factorize(W);
  if (workspace_->ldlt.info() != Eigen::Success) return false;
  factorised_mu_ = mu;
  return true;
}

Eigen::MatrixXd LargeLmSystem::SchurSolve(const Eigen::MatrixXd& V) const {
  const Eigen::Index k = V.rows();
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(W_.rows(), V.cols());
  rhs.bottomRows(k) = V;
  const Eigen::MatrixXd x = workspace_->ldlt.solve(rhs);
  return x.bottomRows(k);
}

Eigen::VectorXd LargeLmSystem::Apply(const Eigen::VectorXd& v) const {
  const Eigen::VectorXd S_v = sensitivity_->StateChange(v);  // -H^-1 B v
  Eigen::VectorXd out = J_e_.transpose() * (J_e_ * v);
  out += lambda_ * (J_u_.transpose() * (J_u_ * v) + B_.transpose() * S_v);
  return out;
}

double LargeLmSystem::LargestEigenvalueBound() const { return J_e_.squaredNorm() + lambda_ * J_u_.squaredNorm(); }

bool LargeLmSystem::Step(double mu, Eigen::VectorXd* du) const {
  if (!Factorize(mu)) return false;
  // Woodbury: (lambda Q + J_e^T J_e)^-1 = (Q^-1 - Y (lambda I + J_e Y)^-1 Y^T) / lambda,
  // Q = C + (mu / lambda) I, Y = Q^-1 J_e^T.
  const Eigen::MatrixXd Y = SchurSolve(J_e_.transpose());
  const Eigen::MatrixXd small = lambda_ * Eigen::MatrixXd::Identity(J_e_.rows(), J_e_.rows()) + J_e_ * Y;
  const Eigen::LDLT<Eigen::MatrixXd> small_ldlt(small);
  const auto approximate_inverse = [&](const Eigen::VectorXd& r) {
    const Eigen::VectorXd q = SchurSolve(r);
    return Eigen::VectorXd((q - Y * small_ldlt.solve(J_e_ * q)) / lambda_);
  };
  *du = approximate_inverse(-g_);
  double size = 0, scale = 0;
  for (int refinement = 0; refinement <= kMaxRefinements && du->allFinite(); ++refinement) {
    const Eigen::VectorXd M_du = Apply(*du) + mu * *du;
    const Eigen::VectorXd residual = -g_ - M_du;
    size = residual.lpNorm<Eigen::Infinity>();
    scale = std::max(g_.lpNorm<Eigen::Infinity>(), M_du.lpNorm<Eigen::Infinity>());
    if (size <= kRefinedResidual * scale || refinement == kMaxRefinements) break;
    *du += approximate_inverse(residual);
  }
  return du->allFinite() && size <= kAcceptedResidual * scale;
}

}  // namespace ccma
