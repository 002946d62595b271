// How an assembled mechanism moves when its controls move, to second order:
// the velocities and accelerations of every body for the controls' rates
// u' and accelerations u'' (inverse dynamics, analyses/dynamics.h).
//
// Differentiating C(s (+) delta(t), u(t)) = 0 at t = 0 once and twice
// (delta(0) = 0, a chart centred at the configuration, state.h):
//   J_s delta'  = -J_u u'
//   J_s delta'' = -J_u u'' - h(delta', u'),
//   h_i = delta'^T Hess_s(C_i) delta' + u'^T Hess_u(C_i) u'
// (no constraint couples s and u at second order: body_frame.h), h from
// ConstraintSet::CurvatureAlong. So q' = S u' and q'' = S u'' + S'(u', u')
// with S = ds/du, the implicit-function sensitivity, and S'(u', u') = -J_s^+ h.
// Both are minimum-norm least-squares solutions through one complete
// orthogonal decomposition: exact where the controls fix the mechanism, and
// free of idle motions (a leg spinning about its own axis) where they do
// not. The factorisation (constraint_factorization.h) also gives the
// efforts of the same configuration (analyses/statics.h's EffortEvaluator),
// so inverse dynamics factorises once per row. At the chart's centre delta' and delta'' are exactly
// the bodies' [omega; v] and [alpha; a] (inertial_loads.h).
#ifndef CCMA_PROBLEMS_INTERNAL_CONTROL_MOTION_H_
#define CCMA_PROBLEMS_INTERNAL_CONTROL_MOTION_H_

#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "problems/internal/constraint_factorization.h"
#include "problems/internal/hessian_solver.h"
#include "ccma/state.h"

namespace ccma {

class ControlMotion {
 public:
  // Evaluates J_s, J_u at (s, u) and factorises (ConstraintFactorization;
  // `symbolic`: a HessianSolver of `set`). Throws std::invalid_argument when
  // the dense path's rows x state size exceeds kMaxStaticsEntries.
  ControlMotion(const ConstraintSet& set, const HessianSolver& symbolic, const State& s, const Eigen::VectorXd& u);

  // delta' (state tangent) for control rates du (num_controls).
  Eigen::VectorXd Velocity(const Eigen::VectorXd& du) const;
  // delta'' for control accelerations ddu, given du and ds = Velocity(du).
  Eigen::VectorXd Acceleration(const Eigen::VectorXd& du, const Eigen::VectorXd& ddu, const Eigen::VectorXd& ds) const;
  // max |J_s ds + J_u du|: how far the rates du are from rates the
  // constraints admit (0 to rounding unless the model is over-actuated and
  // du inconsistent) [m/s or rad/s per row].
  double Inconsistency(const Eigen::VectorXd& ds, const Eigen::VectorXd& du) const;

  int rank() const { return factorization_.rank(); }
  const SparseRowMajor& J_s() const { return factorization_.J_s(); }
  const SparseRowMajor& J_u() const { return factorization_.J_u(); }
  // The same configuration's factorisation, for its efforts.
  const ConstraintFactorization& factorization() const { return factorization_; }

 private:
  const ConstraintSet& set_;
  const State s_;  // copies: the motion belongs to this configuration
  const Eigen::VectorXd u_;
  const ConstraintFactorization factorization_;
  mutable BodyFrames frames_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_CONTROL_MOTION_H_
