#include "problems/internal/kkt_factorization.h"

namespace ccma {

bool KktFactorization::Factorize(const Sparse& K) {
  const bool same_size = pattern_.rows() == K.rows() && pattern_.cols() == K.cols();
  padded_ = same_size ? Sparse(K + pattern_) : K;  // K's values on the union of both patterns
  if (!same_size || padded_.nonZeros() != pattern_.nonZeros()) {
    pattern_ = padded_ * 0.0;
    ldlt_.analyzePattern(padded_);
    ++analyses_;
  }
  ldlt_.factorize(padded_);
  use_lu_ = !(ldlt_.info() == Eigen::Success && ldlt_.vectorD().allFinite());
  return !use_lu_ || UseLu();
}

bool KktFactorization::UseLu() {
  use_lu_ = true;
  lu_.compute(padded_);
  return lu_.info() == Eigen::Success;
}

Eigen::VectorXd KktFactorization::Solve(const Eigen::VectorXd& rhs) const {
  return use_lu_ ? Eigen::VectorXd(lu_.solve(rhs)) : Eigen::VectorXd(ldlt_.solve(rhs));
}

}  // namespace ccma
