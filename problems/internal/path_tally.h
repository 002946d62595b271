// The bookkeeping of ControlProblem::MoveTo: the path's steps summed into a
// ControlResult, the last assembled configuration kept for a stop, and the
// warning that says why a step was not reached.
#ifndef CCMA_PROBLEMS_INTERNAL_PATH_TALLY_H_
#define CCMA_PROBLEMS_INTERNAL_PATH_TALLY_H_

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include <Eigen/Core>

#include "ccma/internal/format.h"
#include "ccma/state.h"
#include "problems/control_problem.h"

namespace ccma {

// Sums the steps of a path into a ControlResult (MoveTo).
struct PathTally {
  ControlResult result;
  ControlStepResult last;
  const std::function<void(const PoseTarget&, const ControlStepResult&)>& on_step;
  // The last assembled configuration (the start, or a step that ended
  // assembled) and its path step (0: the start): where a stop returns to.
  bool have_assembled = false;
  State assembled_state;
  Eigen::VectorXd assembled_controls;
  int assembled_step = 0;

  void KeepIfAssembled(bool assembled, const State& s, const Eigen::VectorXd& u, int step) {
    if (!assembled) return;
    have_assembled = true;
    assembled_state = s;
    assembled_controls = u;
    assembled_step = step;
  }

  explicit PathTally(const std::function<void(const PoseTarget&, const ControlStepResult&)>& callback)
      : on_step(callback) {
    result.min_rcond = std::numeric_limits<double>::infinity();
    result.min_singular_value_dX_du_on_path = std::numeric_limits<double>::infinity();
  }
  void Add(const PoseTarget& step_target, const ControlStepResult& step, bool turn_on_the_spot = false) {
    ++result.steps;
    result.iterations += step.iterations;
    result.forward_solves += step.forward_solves;
    result.branch_jumps_rejected += step.branch_jumps_rejected;
    result.max_step_residual_energy = std::max(result.max_step_residual_energy, step.residual_energy);
    result.max_limit_violation = std::max(result.max_limit_violation, step.max_limit_violation);
    result.max_lateral_displacement = std::max(result.max_lateral_displacement, step.max_lateral_displacement);
    result.max_clearance_violation = std::max(result.max_clearance_violation, step.max_clearance_violation);
    result.max_effort_violation = std::max(result.max_effort_violation, step.max_effort_violation);
    result.limited_by = step.limited_by;
    result.min_rcond = std::min(result.min_rcond, step.rcond);
    if (!turn_on_the_spot) {  // (a turn does not linearise)
      result.min_singular_value_dX_du_on_path =
          std::min(result.min_singular_value_dX_du_on_path, step.min_singular_value_dX_du);
    }
    result.null_space_steps += step.null_space_steps;
    if (on_step) on_step(step_target, step);
    last = step;
  }
  // The path's result: the last step's measures.
  ControlResult Close(double solve_time_ms) {
    result.converged = last.reached && result.warning.empty();
    result.assembled = last.assembled;
    result.objective = last.objective;
    result.error = last.error;
    result.residual_energy = last.residual_energy;
    result.rcond = last.rcond;
    result.min_singular_value_dX_du = last.min_singular_value_dX_du;
    if (!std::isfinite(result.min_singular_value_dX_du_on_path)) result.min_singular_value_dX_du_on_path = 0;
    result.secondary_objective = last.secondary_objective;
    result.solve_time_ms = solve_time_ms;
    return result;
  }
};

// What the step constraints that held a step back mean for its target.
inline std::string WhyLimited(const std::string& limited_by) {
  if (limited_by.empty()) return "the target may be outside the workspace or past a singularity";
  if (limited_by.find("clearance") != std::string::npos) return "the target would need less clearance than the margin";
  if (limited_by.find("effort of") != std::string::npos || limited_by.find("push of") != std::string::npos) {
    return "the target would need an effort beyond its limits";
  }
  return "the target would need a joint beyond its limits";
}

// Why path step i of n was not reached, for ControlResult::warning.
inline std::string StepNotReached(int i, int n, const ControlStepResult& step) {
  return "path step " + std::to_string(i) + " of " + std::to_string(n) + " not reached (error " +
         FormatG(step.error) + ", residual energy " + FormatG(step.residual_energy) +
         (step.singular ? ", dG/ds singular" : "") +
         (step.branch_jumps_rejected > 0 ? ", trial steps landed on another assembly branch" : "") +
         (step.limited_by.empty() ? "" : ", stopped by " + step.limited_by) +
         "): " + WhyLimited(step.limited_by);
}


}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_PATH_TALLY_H_
