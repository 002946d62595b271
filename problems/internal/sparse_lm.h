// The forward problem's own Levenberg-Marquardt loop: the same analytic cost
// functions and pose increments as the Ceres path (ConstraintSet,
// PoseManifold), without Ceres' per-call preprocessing.
//
// Per model, once: the block pattern of J^T J (6 x 6 blocks of the bodies a
// constraint couples, at most two per constraint), the position of every
// block entry in the sparse matrix, and the fill-reducing symbolic analysis
// of its Cholesky factorisation (the fill-reducing permutation is applied to
// the pattern itself, so the factorisation reads the matrix in place). Per
// iteration: one evaluation of every cost function with its Jacobians at
// the trial point (which is the next linearisation when accepted), J^T J and
// J^T C accumulated straight into the fixed pattern, one numeric LDLT, one
// solve.
#ifndef CCMA_PROBLEMS_INTERNAL_SPARSE_LM_H_
#define CCMA_PROBLEMS_INTERNAL_SPARSE_LM_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
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
  // damped_ = P (J^T J + mu D) P^T, upper triangle (P: the fill-reducing order).
  void Damp(double mu);

  const ConstraintSet& constraints_;
  int n_ = 0;                               // state tangent size
  Eigen::SparseMatrix<double> jtj_;         // J^T J, fixed pattern (full symmetric)
  // P (J^T J + mu D) P^T, upper triangle only: what the LDLT reads in place.
  Eigen::SparseMatrix<double> damped_;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation_;  // P
  std::vector<int> permuted_entry_;         // jtj_ value k -> damped_ value index, or -1 (mirror)
  std::vector<int> diagonal_;               // value index of each diagonal entry of jtj_
  std::vector<int> permuted_diagonal_;      // ... and of damped_, same order
  // For each constraint block and each ordered pair (p, q) of its pose
  // parameters in the state: the value indices of the 36 entries of block
  // (body_p, body_q), row-major; -1 pairs (the ground) are skipped.
  std::vector<std::vector<int>> pair_entries_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>> ldlt_;
  Eigen::VectorXd C_, g_, ds_, permuted_g_, permuted_ds_;
  // The last accepted linearisation, restored when a trial is rejected.
  std::vector<double> saved_jtj_;
  Eigen::VectorXd saved_C_, saved_g_;
  std::vector<double> jacobians_;          // per block, per parameter: rows x 7 (row-major)
  std::vector<int> jacobian_offset_;       // start of each block's storage
  State trial_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_SPARSE_LM_H_
