// The BFGS outer loop of a control step (ControlMethod::kBfgs, as in the
// paper): ceres::GradientProblemSolver on O(u_eff) with the implicit (adjoint)
// gradient dO/du, stopped once O certifies the target.
#ifndef CCMA_PROBLEMS_INTERNAL_BFGS_LOOP_H_
#define CCMA_PROBLEMS_INTERNAL_BFGS_LOOP_H_

#include "problems/control_problem.h"

namespace ccma {

class BfgsLoop {
 public:
  // Keeps a reference to `problem`, which it drives.
  explicit BfgsLoop(ControlProblem* problem) : p_(*problem) {}

  // One control step toward `target` from the current solution.
  ControlStepResult SolveStep(const PoseTarget& target);

 private:
  ControlProblem& p_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_BFGS_LOOP_H_
