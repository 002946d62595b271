// Newton's method on the whole compensated control problem
// (problems/compensated_control.h): the loaded equilibrium at the controls
// and the loaded end-effector on the target, together.
//
// Unknowns: the configuration x = (s, delta), the rigid rows' multipliers
// mu and the effective controls u. Equations: the loaded equilibrium's
// (problems/internal/loaded_newton.h) and e(s) = 0, the end-effector error
// on the controlled components (problems/internal/end_effector_error.h).
// One step at (x, u), with the equilibrium's Newton system
// K [y; mu] = [force; -g] factorised once:
//   [y0; mu0] = K^-1 [force; -g]           the equilibrium's own step,
//   J = de/du = -W_mu^T A_u, W = K^-1 [de/ds^T; 0]
//                                          (problems/internal/loaded_sensitivity.h),
//   du = J^+ (-(e + de/ds y0))              minimum norm over the effective controls,
//   y = y0 + (K^-1 [0; -A_u du])_top        the configuration the new controls move.
// That is Newton's step on the bordered system with the controls' step of
// least norm. Its rate is about 1e-3 a step (a stretched rotation spring's
// virtual-work direction differs from its deviation's derivative by the
// stretch, so the symmetric K is not the exact Jacobian), so the steps
// after the first are chord steps while they shrink tenfold: the last
// factorisation against the new residuals [force - A^T mu_last; -g]
// (LoadedKkt::AssembleResiduals, the rows' Jacobians at the new point), as
// fast a rate at a fifth of the cost; a full step (assembly, factorisation,
// sensitivity) where they stall. Every step tests convergence at its point
// with the loaded equilibrium's own tolerances: the unbalanced force with
// the current rows and the multipliers of the step's solve (a chord step's:
// the last ones), the rigid rows, the end-effector error. From a rigid
// round's controls and the loaded configuration expected there: one
// factorisation and 3 chord steps, where rounds of rigid control and loaded
// equilibria took 9 to 12 factorisations. The caller checks the controls
// against what a control step enforces (ControlProblem::CorrectTo).
// Units: m, rad, N, N*m.
#ifndef CCMA_PROBLEMS_INTERNAL_COMPENSATED_NEWTON_H_
#define CCMA_PROBLEMS_INTERNAL_COMPENSATED_NEWTON_H_

#include <vector>

#include <Eigen/Core>

#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/loads.h"
#include "ccma/model.h"
#include "problems/internal/loaded_newton.h"
#include "problems/internal/loaded_tolerances.h"

namespace ccma {

struct CompensatedNewtonOptions {
  LoadedTolerances tolerances;     // the loaded equilibrium's (LoadedTolerancesFor)
  double error_tolerance = 1e-11;  // max |e| [m or rad]
  double max_control_step = 0.01;  // per step, any control [m or rad]
  int max_chords = 6;       // chord steps in a row before a full one
  int max_iterations = 12;  // steps, chord and full
};

struct CompensatedNewtonResult {
  bool converged = false;
  int iterations = 0;     // steps taken, full and chord
  double unbalanced = 0;  // max |force - A^T mu| at the last point [N or N*m]
};

// From (*x, *u): on convergence both hold the solution (the workspace
// factorised there), else they are unchanged. `effective`: the controls
// that may move (ControlProblem::effective_controls).
CompensatedNewtonResult SolveCompensatedNewton(const Model& model, const ConstraintSet& set, const PoseTarget& target,
                                               const std::vector<int>& effective, const ExternalWrench& wrench,
                                               const CompensatedNewtonOptions& options, LoadedWorkspace* workspace,
                                               LoadedPoint* x, Eigen::VectorXd* u);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_COMPENSATED_NEWTON_H_
