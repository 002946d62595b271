#include "problems/internal/sensitivity.h"

#include <algorithm>

#include <Eigen/OrderingMethods>

namespace ccma {

// Below this pivot ratio dG/ds counts as singular.
constexpr double kSingularRcond = 1e-12;

HessianSolver::HessianSolver(const ConstraintSet& constraints) {
  // The fill-reducing order P (AMD, as Eigen's LDLT would choose it) is
  // applied once, to the pattern: permuted_ holds the upper triangle of
  // P H P^T and the factorisation (natural order) reads it in place. Left
  // to Eigen, every factorisation permutes H first (a third of its time).
  const SparseColMajor& pattern = constraints.hessian_pattern();
  const int n = constraints.state_size();
  Eigen::AMDOrdering<int> amd;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  amd(pattern, inverse);
  P_ = inverse.inverse();
  // Which value of H lands where: permute a matrix of entry numbers.
  SparseColMajor numbers = pattern;
  for (int k = 0; k < numbers.nonZeros(); ++k) numbers.valuePtr()[k] = k + 1;
  permuted_.resize(n, n);
  permuted_.selfadjointView<Eigen::Upper>() = numbers.selfadjointView<Eigen::Lower>().twistedBy(P_);
  permuted_.makeCompressed();
  permuted_entry_.assign(static_cast<size_t>(pattern.nonZeros()), -1);  // -1: upper entries of H (mirrors)
  for (int k = 0; k < permuted_.nonZeros(); ++k) {
    permuted_entry_[static_cast<size_t>(permuted_.valuePtr()[k]) - 1] = k;
  }
  ldlt_.analyzePattern(permuted_);
  parent_.assign(static_cast<size_t>(n), -1);
  mark_.assign(static_cast<size_t>(n), 0);
  group_work_ = GroupWork::Zero(n, kGroup);
}

bool HessianSolver::Factorize(const SparseColMajor& H) {
  const double* values = H.valuePtr();
  double* permuted = permuted_.valuePtr();
  for (size_t k = 0; k < permuted_entry_.size(); ++k) {
    if (permuted_entry_[k] >= 0) permuted[permuted_entry_[k]] = values[k];
  }
  ldlt_.factorize(permuted_);
  pivot_ratio_ = 0;
  factorized_ = ldlt_.info() == Eigen::Success;
  if (!factorized_) return false;
  const auto& pivots = ldlt_.vectorD();
  const double largest = pivots.cwiseAbs().maxCoeff();
  pivot_ratio_ = largest > 0 ? pivots.minCoeff() / largest : 0.0;  // negative: indefinite
  // The elimination tree: a column's first below-diagonal row (Eigen's
  // simplicial LDLT stores each column's rows in increasing order, without
  // the unit diagonal). Fixed by the pattern, but only readable once L exists.
  const SparseColMajor& L = ldlt_.matrixL().nestedExpression();
  for (int j = 0; j < L.outerSize(); ++j) {
    const int begin = L.outerIndexPtr()[j], end = L.outerIndexPtr()[j + 1];
    parent_[j] = begin < end ? L.innerIndexPtr()[begin] : -1;
  }
  return true;
}

void HessianSolver::ForwardSubstitute(const SparseColMajor& M, const std::vector<int>& columns,
                                      SparseFactorColumns* out) const {
  const SparseColMajor& L = ldlt_.matrixL().nestedExpression();
  const auto& P = P_.indices();
  const int* L_start = L.outerIndexPtr();
  const int* L_row = L.innerIndexPtr();
  const double* L_value = L.valuePtr();
  out->rows.resize(static_cast<size_t>(L.rows()));
  for (auto& row : out->rows) row.clear();
  // kGroup columns at a time over the union of their reaches: each entry of
  // L is then read once per group and applied to the group's columns as one
  // short vector. The columns of one control block (a base's x, y, theta)
  // or of F (the end-effector body's rows) share their pattern, so the
  // union costs nothing over one reach on large models, while on small
  // ones, where every column reaches most of L, it saves most of the passes.
  for (size_t first = 0; first < columns.size(); first += kGroup) {
    const int group = static_cast<int>(std::min(columns.size() - first, size_t(kGroup)));
    // The reach: every ancestor in the elimination tree of the columns'
    // nonzeros; ascending index order is a topological order (parent > child).
    reach_.clear();
    for (int g = 0; g < group; ++g) {
      for (SparseColMajor::InnerIterator it(M, columns[first + g]); it; ++it) {
        const int i = P[it.row()];
        group_work_(i, g) = it.value();
        for (int j = i; j >= 0 && !mark_[j]; j = parent_[j]) {
          mark_[j] = 1;
          reach_.push_back(j);
        }
      }
    }
    std::sort(reach_.begin(), reach_.end());
    for (int j : reach_) {
      const GroupRow x_j = group_work_.row(j);
      if ((x_j.array() == 0).all()) continue;
      for (int p = L_start[j]; p < L_start[j + 1]; ++p) group_work_.row(L_row[p]) -= L_value[p] * x_j;
    }
    for (int j : reach_) {
      for (int g = 0; g < group; ++g) {
        const double x = group_work_(j, g);
        if (x != 0) out->rows[j].emplace_back(static_cast<int>(first) + g, x);
      }
      group_work_.row(j).setZero();
      mark_[j] = 0;
    }
  }
}

Eigen::VectorXd HessianSolver::ForwardSubstitute(const Eigen::VectorXd& v) const {
  Eigen::VectorXd x = P_ * v;
  ldlt_.matrixL().solveInPlace(x);
  return x;
}

Sensitivity::Sensitivity(const ConstraintSet& constraints, const State& s,
                         const Eigen::VectorXd& u, const std::vector<int>& controls,
                         HessianSolver* solver, EnergyDerivatives* workspace)
    : d_(workspace != nullptr ? workspace : &own_derivatives_), controls_(controls), solver_(solver) {
  if (solver_ == nullptr) {
    own_solver_ = std::make_unique<HessianSolver>(constraints);
    solver_ = own_solver_.get();
  }
  constraints.EvaluateDerivatives(s, u, d_);
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

bool Sensitivity::ImplicitProducts(const Eigen::MatrixXd& F, const Eigen::VectorXd& v, Products* out) const {
  if (!solver_->factorized()) return false;
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
  const Eigen::VectorXd D = solver_->pivots();
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
  if (!dense_rows.empty()) {
    const int r = static_cast<int>(dense_rows.size());
    Eigen::MatrixXd Xd = Eigen::MatrixXd::Zero(r, k), Yd = Eigen::MatrixXd::Zero(r, F.rows());
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
  return true;
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
