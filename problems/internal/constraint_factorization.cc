#include "problems/internal/constraint_factorization.h"

namespace ccma {

ConstraintFactorization::ConstraintFactorization(const ConstraintSet& set, const HessianSolver& symbolic,
                                                 const State& s, const Eigen::VectorXd& u)
    : solver_(symbolic) {
  set.EvaluateDerivatives(s, u, &d_);
  const bool factorised = solver_.Factorize(d_.H);
  if (!factorised || !(solver_.pivot_ratio() > kNormalPivotRatio)) dense_.emplace(set, s, u);
}

int ConstraintFactorization::rank() const {
  return dense_ ? dense_->rank() : static_cast<int>(d_.J_s.cols());
}

long ConstraintFactorization::stored_doubles() const {
  // Jacobians, H and dG/du, and a factor about twice H's size.
  const long sparse = static_cast<long>(d_.J_s.nonZeros() + d_.J_u.nonZeros() + 3 * d_.H.nonZeros() +
                                        d_.dG_du.nonZeros());
  const long dense = dense_ ? 3 * static_cast<long>(d_.J_s.rows()) * d_.J_s.cols() : 0;
  return sparse + dense;
}

Eigen::VectorXd ConstraintFactorization::StateSolution(const Eigen::VectorXd& b) const {
  if (dense_) return dense_->StateSolution(b);
  Eigen::VectorXd x = solver_.Solve(Eigen::VectorXd(d_.J_s.transpose() * b));
  const Eigen::VectorXd r = b - d_.J_s * x;  // one refinement step
  x += solver_.Solve(Eigen::VectorXd(d_.J_s.transpose() * r));
  return x;
}

Eigen::VectorXd ConstraintFactorization::Multipliers(const Eigen::VectorXd& Q) const {
  if (dense_) return dense_->Multipliers(Q);
  Eigen::VectorXd lambda = -(d_.J_s * solver_.Solve(Q));
  const Eigen::VectorXd r = -Q - d_.J_s.transpose() * lambda;  // one refinement step
  lambda += d_.J_s * solver_.Solve(r);
  return lambda;
}

}  // namespace ccma
