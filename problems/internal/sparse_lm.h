// The forward problem's own Levenberg-Marquardt loop: the same analytic cost
// functions and pose increments as the Ceres path (ConstraintSet,
// PoseManifold), without Ceres' per-call preprocessing.
//
// Per model, once: the block pattern of J^T J (6 x 6 blocks of the bodies a
// constraint couples, at most two per constraint), the position of every
// block entry in the sparse matrix, and the fill-reducing symbolic analysis
// of its Cholesky factorisation. Per iteration: the cost functions write
// their Jacobians into preallocated buffers, J^T J and J^T C are accumulated
// straight into the fixed pattern, one numeric LDLT, one solve. No
// allocation after construction.
#ifndef CCMA_PROBLEMS_INTERNAL_SPARSE_LM_H_
#define CCMA_PROBLEMS_INTERNAL_SPARSE_LM_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include "ccma/internal/constraint_set.h"
#include "ccma/state.h"

namespace ccma {

struct SparseLmSummary {
  int iterations = 0;         // linearisations (successful and rejected trials counted once each)
  double energy = 0;          // E at the end [m^2]
  double gradient_norm = 0;   // max |dE/ds| at the last linearisation
  bool converged = false;     // a convergence test held (not the iteration limit)
};

class SparseLevenbergMarquardt {
 public:
  explicit SparseLevenbergMarquardt(const ConstraintSet& constraints);

  // Minimises E(s, u) over s from `s` (updated in place), at most
  // `max_iterations` trial steps. Tolerances as the Ceres path's
  // (forward_problem.cc): relative decrease 1e-15, gradient 1e-14, step 1e-15.
  SparseLmSummary Solve(State* s, const Eigen::VectorXd& u, int max_iterations);

 private:
  // C, g = J^T C and J^T J (into jtj_'s fixed pattern) at (s, u); returns E.
  double Linearize(const State& s, const Eigen::VectorXd& u);
  // E at (s, u), residuals only.
  double EnergyAt(const State& s, const Eigen::VectorXd& u);

  const ConstraintSet& constraints_;
  int n_ = 0;                               // state tangent size
  Eigen::SparseMatrix<double> jtj_;         // J^T J, fixed pattern (full symmetric)
  Eigen::SparseMatrix<double> damped_;      // J^T J + mu D, same pattern
  std::vector<int> diagonal_;               // value index of each diagonal entry
  // For each constraint block and each ordered pair (p, q) of its pose
  // parameters in the state: the value indices of the 36 entries of block
  // (body_p, body_q), row-major; -1 pairs (the ground) are skipped.
  std::vector<std::vector<int>> pair_entries_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  Eigen::VectorXd C_, g_, ds_;
  std::vector<double> jacobians_;          // per block, per parameter: rows x 7 (row-major)
  std::vector<int> jacobian_offset_;       // start of each block's storage
  State trial_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_SPARSE_LM_H_
