// One factorisation of the constraint Jacobian J_s = dC/ds at an assembled
// configuration, for the two least-squares problems inverse dynamics solves
// at every row (analyses/dynamics.h, analyses/retime.h) and the efforts of
// the controls (analyses/statics.h's EffortEvaluator):
//   the motion:      J_s x = b        (minimum-norm least squares)
//   the multipliers: J_s^T lambda = -Q (minimum-norm least squares)
//
// Why two paths. Where the controls fix the mechanism and no row is
// redundant enough to make J_s rank deficient (every bundled model away from
// its singularities), J_s has full column rank and both solutions come from
// the block-sparse LDL^T of H = dG/ds (hessian_solver.h, the factorisation
// the forward problem and the sensitivities use):
//   x = H^-1 J_s^T b,   lambda = -J_s H^-1 Q,
// each followed by one step of iterative refinement against the exact J_s
// (corrected semi-normal equations, Bjorck 1987), which brings the error
// from cond(J_s)^2 eps down to about cond(J_s) eps. That is a few sparse
// solves instead of a dense QR of J_s (benchmarks/dynamics_benchmark.cc).
// H holds sum_i C_i Hess(C_i) too; at an assembled row C is at rounding
// level, and the refinement step removes what it adds.
// Elsewhere (idle motions, a singular configuration: H's pivot ratio below
// kNormalPivotRatio, or H not factorisable) the dense complete orthogonal
// decomposition of Equilibrium (equilibrium.h) decides the rank, as statics
// does, and gives the minimum-norm solutions.
#ifndef CCMA_PROBLEMS_INTERNAL_CONSTRAINT_FACTORIZATION_H_
#define CCMA_PROBLEMS_INTERNAL_CONSTRAINT_FACTORIZATION_H_

#include <optional>

#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "ccma/state.h"
#include "problems/internal/equilibrium.h"
#include "problems/internal/hessian_solver.h"

namespace ccma {

class ConstraintFactorization {
 public:
  // H's smallest over largest LDL^T pivot below which the dense path is
  // taken: about cond(J_s) > 1e4, where the refined normal equations would
  // lose more than the dense decomposition's digits.
  static constexpr double kNormalPivotRatio = 1e-8;

  // Evaluates C, J_s, J_u, H at (s, u) and factorises. `symbolic` is a
  // HessianSolver of `set` (its symbolic analysis is copied, not redone).
  // The dense path throws std::invalid_argument when rows x state size
  // exceeds kMaxStaticsEntries (equilibrium.h).
  ConstraintFactorization(const ConstraintSet& set, const HessianSolver& symbolic, const State& s,
                          const Eigen::VectorXd& u);

  bool sparse() const { return !dense_; }
  int rank() const;  // of J_s
  const SparseRowMajor& J_s() const { return d_.J_s; }
  const SparseRowMajor& J_u() const { return d_.J_u; }
  // About how many doubles this object holds (a cache's budget).
  long stored_doubles() const;

  // Minimum-norm least-squares x of J_s x = b (b: rows, x: state tangent).
  Eigen::VectorXd StateSolution(const Eigen::VectorXd& b) const;
  // The state's motion for control rates du: StateSolution(-J_u du).
  Eigen::VectorXd StateMotion(const Eigen::VectorXd& du) const { return StateSolution(-(d_.J_u * du)); }
  // Minimum-norm least-squares lambda of J_s^T lambda = -Q (Q: state tangent).
  Eigen::VectorXd Multipliers(const Eigen::VectorXd& Q) const;
  // e = -J_u^T lambda (num_controls) [N, N*m].
  Eigen::VectorXd Efforts(const Eigen::VectorXd& lambda) const { return -(d_.J_u.transpose() * lambda); }

 private:
  EnergyDerivatives d_;
  HessianSolver solver_;
  std::optional<Equilibrium> dense_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_CONSTRAINT_FACTORIZATION_H_
