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
// least norm, so it converges quadratically from a start near the solution
// (a rigid round's controls, the loaded configuration expected there): 3 to
// 4 factorisations where rounds of rigid control and loaded equilibria took
// 9 to 12. The caller checks the controls against what a control step
// enforces (ControlProblem::CorrectTo).
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

namespace ccma {

struct CompensatedNewtonOptions {
  double force_tolerance = 1e-10;  // [N or N*m], as LoadedOptions' (already scaled)
  double error_tolerance = 1e-11;  // max |e| [m or rad]
  double max_control_step = 0.01;  // per step, any control [m or rad]
  int max_iterations = 8;
};

struct CompensatedNewtonResult {
  bool converged = false;
  int iterations = 0;     // steps taken (factorisations: one more)
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
