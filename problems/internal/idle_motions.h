// Idle motions: motions of the state that no constraint resists and that do
// not move the end-effector, such as a rod spinning about its own axis
// between two ball joints, or between two stacks of revolute joints as
// robots exported from CAD often have (docs/import.md). They make dG/ds
// singular although the control problem is well posed: ds/du is not unique,
// de/du is. The control problem then factorises dG/ds + mu I, whose
// sensitivities pick the solution without idle motion (the idle directions v
// have v^T dG/du = 0, so mu never divides anything but rounding), once
// OnlyIdleMotions has shown that every unresisted motion is idle. A motion
// that moves the end-effector (a true singularity) keeps the step singular.
#ifndef CCMA_PROBLEMS_INTERNAL_IDLE_MOTIONS_H_
#define CCMA_PROBLEMS_INTERNAL_IDLE_MOTIONS_H_

#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "problems/internal/hessian_solver.h"

namespace ccma {

// mu for dG/ds = H: 1e-9 of its largest diagonal entry (m^2 per tangent unit
// squared), so that the regularised pivot ratio (about 1e-9) is far above
// the singular threshold (1e-12) and the end-effector's sensitivities change
// by a relative 1e-9 / (smallest resisted curvature) at most.
double IdleRegularization(const SparseColMajor& H);

// `solver` holds the factorisation of H_regularized = H + mu I. True when
// every motion that H resists less than 10 mu moves the end-effector by less
// than 1e-8 relative to |de/ds| (de_ds: d(end-effector error)/ds). Those
// motions are found by seeded inverse iteration from as many starts as there
// are pivots within 1000 mu, then the eigenvectors of H within their span.
bool OnlyIdleMotions(const HessianSolver& solver, const SparseColMajor& H_regularized, double mu,
                     const Eigen::MatrixXd& de_ds);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_IDLE_MOTIONS_H_
