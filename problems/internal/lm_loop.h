// The Levenberg-Marquardt outer loop of a control step (the default,
// ControlMethod::kLevenbergMarquardt): damped least squares on
// r(u) = [e; sqrt(lambda) C] with the exact Gauss-Newton model of
// ControlProblem::Linearize, under the step constraints (active set), with
// branch-jump rejection of the trial solves; then, once the task holds, the
// null-space secondary objectives (null_space_step.h).
#ifndef CCMA_PROBLEMS_INTERNAL_LM_LOOP_H_
#define CCMA_PROBLEMS_INTERNAL_LM_LOOP_H_

#include <Eigen/Core>

#include "problems/control_problem.h"
#include "problems/internal/control_linearization.h"
#include "problems/internal/step_constraints.h"

namespace ccma {

class LmLoop {
 public:
  // Keeps a reference to `problem`, which it drives.
  explicit LmLoop(ControlProblem* problem) : p_(*problem) {}

  // One control step toward `target` from the current solution.
  ControlStepResult SolveStep(const PoseTarget& target);
  // The same step, its step constraints begun at (u0, s0) (the previous row
  // of a path) instead of at the current solution: a current solution below
  // a floor (a clearance under the margin) is brought back to it, where
  // SolveStep would keep its shortfall as the floor.
  ControlStepResult SolveStepFrom(const PoseTarget& target, const Eigen::VectorXd& u0,
                                  const State& s0);
  // The LM iterations on the end-effector task alone from the current
  // solution; returns whether it reached the target tolerance. Adds its
  // iterations, branch jumps, rcond and sigma to `result`.
  bool ConvergeTask(const PoseTarget& target, ControlStepResult* result, bool report_iterations);

 private:
  // One iteration: damping trials until one decreases O on the same branch;
  // false when none was accepted (or the step vanished).
  bool Iteration(const PoseTarget& target, const ControlLinearization& lin, double* O, double* mu,
                 Eigen::VectorXd* r, ControlStepResult* result);
  // The step for damping mu, unconstrained or under the step constraints
  // (`active` grows until no other item would cross a bound).
  Eigen::VectorXd Step(const ControlLinearization& lin, double mu, ActiveSet* active) const;
  // Newton steps on the step constraints alone until they hold to 1e-10.
  void ProjectOntoStepConstraints(ControlStepResult* result);
  bool StepConstraintsHold() const;
  // SolveStep after the step constraints have begun; project_first: onto
  // them before the descent.
  ControlStepResult SolveBegunStep(const PoseTarget& target, bool project_first);

  ControlProblem& p_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_LM_LOOP_H_
