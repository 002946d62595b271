// Static equilibrium at one configuration, the algebra `ccma statics`, the
// effort limits of control (effort_limit_constraint.h) and the design
// objectives (analyses/design_objective.h) share.
//
// The loads Q (ccma/loads.h) are held by the constraint rows when
// Q + J_s^T lambda = 0 (J_s = dC/ds, lambda the rows' multipliers); a
// control's effort is e = -J_u^T lambda (J_u = dC/du), which obeys virtual
// work: e . du = -Q . ds along every motion with J_s ds + J_u du = 0.
// lambda is the least-squares, minimum-norm solution (complete orthogonal
// decomposition of J_s^T), unique when the rows are independent.
//
// Derivatives of a weighted effort w . e along a motion (ds, du, and a
// change of the model), for the minimum-norm lambda = -(J_s^T)^+ Q (rank
// constant along the motion, loads balanced): with the adjoints
//   mu = J_s^+ J_u w,  zeta = J_u w - J_s mu,  eta = J_s^+ lambda,
// the derivative of the pseudo-inverse collapses to
//   d(w . e) = d/d(s, u, model) [ L ] at fixed (lambda, mu, zeta, eta),
//   L = -w^T J_u^T lambda + mu^T (J_s^T lambda + Q) - zeta^T J_s eta,
// so no derivative of the least-squares solve itself is needed
// (EffortLagrangian; callers differentiate it along their motion). zeta is
// zero exactly when w . e is fixed by the loads (then mu solves
// J_s mu = J_u w, the classic adjoint).
#ifndef CCMA_PROBLEMS_INTERNAL_EQUILIBRIUM_H_
#define CCMA_PROBLEMS_INTERNAL_EQUILIBRIUM_H_

#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "ccma/internal/dense_factorizations.h"
#include "ccma/limits.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

class Equilibrium {
 public:
  // Evaluates J_s and J_u at (s, u) and factorises J_s^T. Throws
  // std::invalid_argument when rows x state size exceeds kMaxStaticsEntries.
  Equilibrium(const ConstraintSet& set, const State& s, const Eigen::VectorXd& u);

  const Eigen::MatrixXd& J_s() const { return J_s_; }
  const Eigen::MatrixXd& J_u() const { return J_u_; }
  int rank() const { return static_cast<int>(cod_.rank()); }

  // Minimum-norm lambda (rows) with J_s^T lambda = -Q in least squares.
  Eigen::VectorXd Multipliers(const Eigen::VectorXd& Q) const { return cod_.solve(-Q); }
  // e = -J_u^T lambda (num_controls) [N, N*m].
  Eigen::VectorXd Efforts(const Eigen::VectorXd& lambda) const { return -J_u_.transpose() * lambda; }
  // The adjoints of w . e under the loads Q (above).
  struct Adjoint {
    Eigen::VectorXd lambda, mu, zeta, eta;
    bool unique = true;  // zeta = 0: w . e does not depend on which lambda
  };
  Adjoint AdjointOf(const Eigen::VectorXd& w, const Eigen::VectorXd& Q) const;
  // The state's motion for a control change du [state tangent]: the
  // minimum-norm solution of J_s ds = -J_u du. It is ds/du du wherever the
  // controls fix the mechanism, and leaves out idle motions (a leg spinning
  // about its own axis) where they do not: those change no effort, but a
  // sensitivity through a singular dG/ds may carry them at any size.
  Eigen::VectorXd StateMotion(const Eigen::VectorXd& du) const { return StateSolution(-(J_u_ * du)); }
  // The minimum-norm least-squares solution x of J_s x = b (b: rows), from
  // the same factorisation as the multipliers (one per configuration: the
  // motion and the efforts of inverse dynamics share it).
  Eigen::VectorXd StateSolution(const Eigen::VectorXd& b) const { return cod_.solveTransposed(b); }

 private:
  Eigen::MatrixXd J_s_, J_u_;
  MinimumNormSolver cod_;   // of J_s^T
};

// L (above) at (s, u) on `set`, with Q the loads of `loads_model` at s
// (ccma/loads.h) and the adjoints held fixed [N or N*m per unit of w].
double EffortLagrangian(const ConstraintSet& set, const Model& loads_model, const State& s,
                        const Eigen::VectorXd& u, const Eigen::VectorXd& w, const Equilibrium::Adjoint& adjoint);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_EQUILIBRIUM_H_
