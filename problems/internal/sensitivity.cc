#include "problems/internal/sensitivity.h"

namespace ccma {

// Below this pivot ratio dG/ds counts as singular.
constexpr double kSingularRcond = 1e-12;

HessianSolver::HessianSolver(const ConstraintSet& constraints) {
  const int n = constraints.state_size();
  std::vector<Eigen::Triplet<double>> pattern;
  auto add_block = [&](int a, int b) {
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) pattern.emplace_back(6 * a + i, 6 * b + j, 1.0);
    }
  };
  for (int body = 0; body < n / 6; ++body) add_block(body, body);
  for (const ConstraintBlock& block : constraints.blocks()) {
    if (block.bodies.size() == 2 && block.bodies[0] != kWorld && block.bodies[1] != kWorld) {
      add_block(block.bodies[0], block.bodies[1]);
      add_block(block.bodies[1], block.bodies[0]);
    }
  }
  H_.resize(n, n);
  H_.setFromTriplets(pattern.begin(), pattern.end(), [](double a, double) { return a; });
  H_.makeCompressed();
  ldlt_.analyzePattern(H_);
}

bool HessianSolver::Factorize(const Eigen::MatrixXd& H) {
  for (int col = 0; col < H_.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(H_, col); it; ++it) {
      it.valueRef() = H(it.row(), it.col());
    }
  }
  ldlt_.factorize(H_);
  pivot_ratio_ = 0;
  if (ldlt_.info() != Eigen::Success) return false;
  const Eigen::VectorXd pivots = ldlt_.vectorD();
  const double largest = pivots.cwiseAbs().maxCoeff();
  pivot_ratio_ = largest > 0 ? pivots.minCoeff() / largest : 0.0;  // negative: indefinite
  return true;
}

Eigen::MatrixXd ConstraintJacobianTimes(const ConstraintSet& constraints, const Eigen::MatrixXd& J_s,
                                        const Eigen::MatrixXd& M) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(J_s.rows(), M.cols());
  for (const ConstraintBlock& block : constraints.blocks()) {
    for (int body : block.bodies) {
      if (body == kWorld) continue;
      out.middleRows(block.row, block.rows).noalias() +=
          J_s.block(block.row, 6 * body, block.rows, 6) * M.middleRows(6 * body, 6);
    }
  }
  return out;
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
  dG_du_.resize(d_->H.rows(), static_cast<Eigen::Index>(controls_.size()));
  for (size_t c = 0; c < controls_.size(); ++c) dG_du_.col(c) = d_->dG_du.col(controls_[c]);
  if (solver_->Factorize(d_->H)) rcond_ = solver_->pivot_ratio();
  singular_ = !(rcond_ > kSingularRcond);
}

Eigen::MatrixXd Sensitivity::StateSensitivity() const { return -solver_->Solve(dG_du_); }

Eigen::VectorXd Sensitivity::StateChange(const Eigen::VectorXd& du) const {
  return -solver_->Solve(dG_du_ * du);
}

Eigen::VectorXd Sensitivity::ResidualEnergyGradient() const {
  Eigen::VectorXd g(static_cast<Eigen::Index>(controls_.size()));
  for (size_t c = 0; c < controls_.size(); ++c) g[c] = d_->dE_du[controls_[c]];
  return g;
}

Eigen::VectorXd Sensitivity::TotalDerivative(const Eigen::VectorXd& dF_ds,
                                             const Eigen::VectorXd& dF_du) const {
  const Eigen::VectorXd adjoint = solver_->Solve(dF_ds);  // dG/ds is symmetric
  return dF_du - dG_du_.transpose() * adjoint;
}

}  // namespace ccma
