// What a ControlProblem owns besides its forward problem: built once per
// problem, reused by every step (no allocation of solver structures in the
// loop). Shared by the parts of a control step in problems/internal/.
#ifndef CCMA_PROBLEMS_INTERNAL_CONTROL_WORKSPACE_H_
#define CCMA_PROBLEMS_INTERNAL_CONTROL_WORKSPACE_H_

#include <vector>

#include "ccma/internal/constraint_set.h"
#include "problems/control_problem.h"
#include "problems/internal/end_effector_error.h"
#include "problems/internal/large_lm_system.h"
#include "problems/internal/sensitivity.h"
#include "problems/internal/step_constraints.h"

namespace ccma {

// A step's loops stop once it is this far inside its tolerances: the
// forward problem then sits at its own precision floor.
constexpr double kEnergyFloor = 1e-24;

struct ControlProblem::Workspace {
  Workspace(const Model& model, const ConstraintSet& constraints, const std::vector<int>& effective)
      : error(model),
        step_constraints(model, effective),
        hessian_solver(constraints),
        sigma_solver(constraints),
        effective_column(static_cast<size_t>(model.num_controls()), -1),
        active(step_constraints.NoneActive()) {
    for (size_t c = 0; c < effective.size(); ++c) {
      effective_column[static_cast<size_t>(effective[c])] = static_cast<int>(c);
    }
  }
  EndEffectorError error;
  StepConstraints step_constraints;  // differential arcs, joint limits
  HessianSolver hessian_solver;      // symbolic analysis of dG/ds, done once
  EnergyDerivatives derivatives;     // reused by every linearisation
  HessianSolver sigma_solver;        // the singularity gradient's own (keeps hessian_solver's factors)
  EnergyDerivatives sigma_derivatives;
  std::vector<int> effective_column;  // control index -> column among the effective ones, or -1
  ActiveSet active;                   // step-constraint items held at a bound in the current step
  LargeLmWorkspace large_lm;          // many controls: the LM step's sparse analysis, done once
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_CONTROL_WORKSPACE_H_
