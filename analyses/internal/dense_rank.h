// The numerical rank of a matrix from its singular values, shared by the
// dense mobility analyses (analyses/mobility.cc, analyses/moved_components.cc).
#ifndef CCMA_ANALYSES_INTERNAL_DENSE_RANK_H_
#define CCMA_ANALYSES_INTERNAL_DENSE_RANK_H_

#include <Eigen/Core>

namespace ccma {

// How many singular values exceed `threshold` (an absolute bound: callers
// scale their relative tolerance by the largest singular value).
inline int RankAbove(const Eigen::VectorXd& singular_values, double threshold) {
  return static_cast<int>((singular_values.array() > threshold).count());
}

}  // namespace ccma

#endif  // CCMA_ANALYSES_INTERNAL_DENSE_RANK_H_
