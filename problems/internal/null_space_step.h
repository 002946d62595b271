// Redundancy resolution (ControlOptions::Secondary, LM only): once a step
// has reached its target, Gauss-Newton steps on the secondary objective Phi
// (secondary_objective.h) restricted to the null space of the task's
// Gauss-Newton model, each followed by re-converging the task (LmLoop). A
// step is kept only if the target is reached again, on the same assembly
// branch, and Phi decreased; so the end-effector error is that of the plain
// controller.
#ifndef CCMA_PROBLEMS_INTERNAL_NULL_SPACE_STEP_H_
#define CCMA_PROBLEMS_INTERNAL_NULL_SPACE_STEP_H_

#include <Eigen/Core>

#include "problems/control_problem.h"
#include "problems/internal/control_linearization.h"

namespace ccma {

class NullSpaceStep {
 public:
  // Keeps a reference to `problem`, which it drives.
  explicit NullSpaceStep(ControlProblem* problem) : p_(*problem) {}

  // One accepted null-space step (result: iterations, branch jumps, rcond,
  // sigma updated), or false with the solution restored when no trial
  // decreased Phi (or there is no null space, or Phi is 0 or infinite).
  bool Iterate(const PoseTarget& target, ControlStepResult* result);

 private:
  // Re-converges the task after the trial du and reports whether it is
  // acceptable: target reached, no branch jump, Phi below `phi`.
  bool TryStep(const PoseTarget& target, const ControlLinearization& lin, const Eigen::VectorXd& du, double phi,
               ControlStepResult* result);

  ControlProblem& p_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_NULL_SPACE_STEP_H_
