#include "problems/internal/kkt_factorization.h"

#include <algorithm>

namespace ccma {
namespace {

// Whether compressed K has exactly the pattern P.
bool SamePattern(const KktFactorization::Sparse& K, const KktFactorization::Sparse& P) {
  if (K.rows() != P.rows() || K.cols() != P.cols() || K.nonZeros() != P.nonZeros() || !K.isCompressed()) return false;
  return std::equal(K.outerIndexPtr(), K.outerIndexPtr() + K.outerSize() + 1, P.outerIndexPtr()) &&
         std::equal(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros(), P.innerIndexPtr());
}

}  // namespace

bool KktFactorization::Factorize(const Sparse& K) {
  // A matrix on the analysed pattern itself (the loaded KKT's fixed one,
  // problems/internal/loaded_kkt.h) is factorised as it is; another is
  // padded onto the union of both patterns.
  if (SamePattern(K, pattern_)) {
    factorized_ = &K;
  } else {
    const bool same_size = pattern_.rows() == K.rows() && pattern_.cols() == K.cols();
    padded_ = same_size ? Sparse(K + pattern_) : K;  // K's values on the union of both patterns
    padded_.makeCompressed();
    if (!same_size || padded_.nonZeros() != pattern_.nonZeros()) {
      pattern_ = padded_ * 0.0;
      pattern_.makeCompressed();
      ldlt_.analyzePattern(padded_);
      ++analyses_;
    }
    factorized_ = &padded_;
  }
  ldlt_.factorize(*factorized_);
  use_lu_ = !(ldlt_.info() == Eigen::Success && ldlt_.vectorD().allFinite());
  return !use_lu_ || UseLu();
}

bool KktFactorization::UseLu() {
  use_lu_ = true;
  lu_.compute(Sparse(factorized_->selfadjointView<Eigen::Lower>()));
  return lu_.info() == Eigen::Success;
}

// The LDL^T's solve P^T L^-T D^-1 L^-1 P rhs written out on the factor's
// arrays (L unit lower, its strict lower part stored by columns): the
// same operations as Eigen's, without its generic triangular views.
Eigen::VectorXd KktFactorization::Solve(const Eigen::VectorXd& rhs) const {
  if (use_lu_) return lu_.solve(rhs);
  const Sparse& L = ldlt_.matrixL().nestedExpression();
  const int* Lp = L.outerIndexPtr();
  const int* Li = L.innerIndexPtr();
  const double* Lx = L.valuePtr();
  Eigen::VectorXd x = ldlt_.permutationP() * rhs;
  const Eigen::Index n = x.size();
  for (Eigen::Index j = 0; j < n; ++j) {
    const double xj = x[j];
    for (int p = Lp[j]; p < Lp[j + 1]; ++p) x[Li[p]] -= Lx[p] * xj;
  }
  x.array() /= ldlt_.vectorD().array();
  for (Eigen::Index j = n - 1; j >= 0; --j) {
    double xj = x[j];
    for (int p = Lp[j]; p < Lp[j + 1]; ++p) xj -= Lx[p] * x[Li[p]];
    x[j] = xj;
  }
  return ldlt_.permutationPinv() * x;
}

}  // namespace ccma
