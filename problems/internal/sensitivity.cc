#include "problems/internal/sensitivity.h"

#include <algorithm>

namespace ccma {

// Below this pivot ratio dG/ds counts as singular.
constexpr double kSingularRcond = 1e-12;

Sensitivity::Sensitivity(const ConstraintSet& constraints, const State& s,
                         const Eigen::VectorXd& u, const std::vector<int>& controls,
                         HessianSolver* solver, EnergyDerivatives* workspace, double regularization)
    : d_(workspace != nullptr ? workspace : &own_derivatives_), controls_(controls), solver_(solver) {
  if (solver_ == nullptr) {
    own_solver_ = std::make_unique<HessianSolver>(constraints);
    solver_ = own_solver_.get();
  }
  constraints.EvaluateDerivatives(s, u, d_);
  if (regularization > 0) {
    for (Eigen::Index j = 0; j < d_->H.outerSize(); ++j) {
      for (SparseColMajor::InnerIterator it(d_->H, j); it; ++it) {
        if (it.row() == j) it.valueRef() += regularization;
      }
    }
  }
  if (solver_->Factorize(d_->H)) rcond_ = solver_->pivot_ratio();
  singular_ = !(rcond_ > kSingularRcond);
}

Eigen::VectorXd Sensitivity::dG_du_times(const Eigen::VectorXd& du) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(d_->dG_du.rows());
  for (size_t c = 0; c < controls_.size(); ++c) {
    if (du[c] != 0) out += du[c] * d_->dG_du.col(controls_[c]);
  }
  return out;
}

bool Sensitivity::ImplicitProducts(const Eigen::MatrixXd& F, const Eigen::VectorXd& v, Products* out,
                                   ProductsPath path) const {
  if (!solver_->factorized()) return false;
  const Eigen::Index k = static_cast<Eigen::Index>(controls_.size());
  const Eigen::Index n = d_->H.rows();
  if (path == ProductsPath::kDense || (path == ProductsPath::kAuto && n * (k + F.rows()) <= kDenseProductsLimit)) {
    DenseProducts(F, v, out);
  } else {
    SparseProducts(F, v, out);
  }
  return true;
}

void Sensitivity::DenseProducts(const Eigen::MatrixXd& F, const Eigen::VectorXd& v, Products* out) const {
  const int k = static_cast<int>(controls_.size());
  const Eigen::Index n = d_->H.rows();
  // X = L^-1 P B and [Y z] = L^-1 P [F^T v] in one pass each, then
  // B^T S = -X^T D^-1 X, F S = -Y^T D^-1 X, S^T v = -X^T D^-1 z.
  const auto& P = solver_->permutation().indices();
  const Eigen::Index ne = F.rows();
  Eigen::MatrixXd& X = *solver_->dense_scratch(0);
  Eigen::MatrixXd& Yz = *solver_->dense_scratch(1);
  Eigen::MatrixXd& DX = *solver_->dense_scratch(2);
  X.setZero(n, k);
  for (int c = 0; c < k; ++c) {
    for (SparseColMajor::InnerIterator it(d_->dG_du, controls_[c]); it; ++it) X(P[it.row()], c) = it.value();
  }
  Yz.resize(n, ne + 1);
  for (Eigen::Index i = 0; i < n; ++i) {
    Yz.row(P[i]).head(ne) = F.col(i).transpose();
    Yz(P[i], ne) = v[i];
  }
  solver_->ForwardSubstitutePermuted(&X);
  solver_->ForwardSubstitutePermuted(&Yz);
  DX.noalias() = solver_->pivots().cwiseInverse().asDiagonal() * X;
  // Small products: coefficient-based (lazy), no blocked GEMM packing.
  out->BtS.noalias() = -(X.transpose().lazyProduct(DX));
  out->FS.noalias() = -(Yz.leftCols(ne).transpose().lazyProduct(DX));
  out->Stv.noalias() = -(DX.transpose().lazyProduct(Yz.col(ne)));
}

namespace {

// The rows of L^-1 P B that nearly every control reaches (`dense_rows`),
// gathered into dense blocks and subtracted from the products as one rank
// update each.
void SubtractRootBlock(const std::vector<int>& dense_rows, const HessianSolver::SparseFactorColumns& X,
                       const HessianSolver::SparseFactorColumns& Y, const Eigen::VectorXd& D,
                       const Eigen::VectorXd& z, int k, Eigen::Index num_f, Sensitivity::Products* out) {
  const int r = static_cast<int>(dense_rows.size());
  Eigen::MatrixXd Xd = Eigen::MatrixXd::Zero(r, k), Yd = Eigen::MatrixXd::Zero(r, num_f);
  Eigen::VectorXd inverse_pivots(r), zd(r);
  for (int q = 0; q < r; ++q) {
    const int i = dense_rows[static_cast<size_t>(q)];
    for (const auto& [a, x_a] : X.rows[static_cast<size_t>(i)]) Xd(q, a) = x_a;
    for (const auto& [f, y_f] : Y.rows[static_cast<size_t>(i)]) Yd(q, f) = y_f;
    inverse_pivots[q] = 1.0 / D[i];
    zd[q] = z[i];
  }
  const Eigen::MatrixXd DXd = inverse_pivots.asDiagonal() * Xd;
  out->BtS.noalias() -= Xd.transpose() * DXd;
  out->FS.noalias() -= Yd.transpose() * DXd;
  out->Stv.noalias() -= DXd.transpose() * zd;
}

}  // namespace

void Sensitivity::SparseProducts(const Eigen::MatrixXd& F, const Eigen::VectorXd& v, Products* out) const {
  const int k = static_cast<int>(controls_.size());
  HessianSolver::SparseFactorColumns& X = *solver_->scratch(0);
  HessianSolver::SparseFactorColumns& Y = *solver_->scratch(1);
  solver_->ForwardSubstitute(d_->dG_du, controls_, &X);
  // F^T as a sparse matrix: de/ds has only the end-effector body's columns.
  const SparseColMajor Ft = F.transpose().sparseView();
  std::vector<int> f_columns(static_cast<size_t>(F.rows()));
  for (int r = 0; r < F.rows(); ++r) f_columns[static_cast<size_t>(r)] = r;
  solver_->ForwardSubstitute(Ft, f_columns, &Y);
  const Eigen::VectorXd z = solver_->ForwardSubstitute(v);
  const Eigen::VectorXd& D = solver_->pivots();
  out->BtS.setZero(k, k);
  out->FS.setZero(F.rows(), k);
  out->Stv.setZero(k);
  // Row by row of L^-1 P B: each row pairs its own nonzeros only. Rows that
  // nearly every control reaches (the bodies near the elimination tree's
  // root, e.g. the end-effector every leg closes on) are gathered into a
  // dense block and multiplied as one rank update.
  const int dense_threshold = std::max(16, k / 4);
  std::vector<int> dense_rows;
  for (size_t i = 0; i < X.rows.size(); ++i) {
    const auto& x = X.rows[i];
    if (x.empty()) continue;
    if (static_cast<int>(x.size()) > dense_threshold) {
      dense_rows.push_back(static_cast<int>(i));
      continue;
    }
    const double inverse_pivot = 1.0 / D[static_cast<Eigen::Index>(i)];
    for (const auto& [a, x_a] : x) {
      const double scaled = inverse_pivot * x_a;
      for (const auto& [b, x_b] : x) out->BtS(b, a) -= scaled * x_b;
      for (const auto& [f, y_f] : Y.rows[i]) out->FS(f, a) -= y_f * scaled;
      out->Stv[a] -= scaled * z[static_cast<Eigen::Index>(i)];
    }
  }
  if (!dense_rows.empty()) SubtractRootBlock(dense_rows, X, Y, D, z, k, F.rows(), out);
}

Eigen::MatrixXd Sensitivity::StateSensitivity() const {
  Eigen::MatrixXd dG_du(d_->dG_du.rows(), static_cast<Eigen::Index>(controls_.size()));
  for (size_t c = 0; c < controls_.size(); ++c) dG_du.col(c) = d_->dG_du.col(controls_[c]);
  return -solver_->Solve(dG_du);
}

Eigen::VectorXd Sensitivity::StateChange(const Eigen::VectorXd& du) const {
  return -solver_->Solve(dG_du_times(du));
}

Eigen::VectorXd Sensitivity::ResidualEnergyGradient() const {
  Eigen::VectorXd g(static_cast<Eigen::Index>(controls_.size()));
  for (size_t c = 0; c < controls_.size(); ++c) g[c] = d_->dE_du[controls_[c]];
  return g;
}

Eigen::VectorXd Sensitivity::TotalDerivative(const Eigen::VectorXd& dF_ds,
                                             const Eigen::VectorXd& dF_du) const {
  const Eigen::VectorXd adjoint = solver_->Solve(dF_ds);  // dG/ds is symmetric
  Eigen::VectorXd total = dF_du;
  for (size_t c = 0; c < controls_.size(); ++c) total[c] -= d_->dG_du.col(controls_[c]).dot(adjoint);
  return total;
}

}  // namespace ccma
