// Differential bases turn on the spot before a step that would move them far
// off their heading (more than kMaxArcTurn): a path step of its own, with the
// end-effector held, so that the step itself is a gentle arc (the arcs are
// step constraints, differential_arc_constraint.h).
#ifndef CCMA_PROBLEMS_INTERNAL_DIFFERENTIAL_TURNING_H_
#define CCMA_PROBLEMS_INTERNAL_DIFFERENTIAL_TURNING_H_

#include <Eigen/Core>

#include "problems/control_problem.h"

namespace ccma {

class DifferentialTurning {
 public:
  // Heading change [rad] above which a base turns on the spot first.
  static constexpr double kMaxArcTurn = 0.05;

  // Keeps a reference to `problem`, which it drives.
  explicit DifferentialTurning(ControlProblem* problem) : p_(*problem) {}

  // Turns the differential bases that the step toward `target` would move
  // more than kMaxArcTurn off their heading; true (and `turn` filled) when
  // they turned with the end-effector held, false with nothing changed when
  // no base needs to or the headings are not free in this chain.
  bool Turn(const PoseTarget& target, ControlStepResult* turn);

 private:
  // The controls with each such base facing its unconstrained Gauss-Newton
  // motion (forwards or backwards, the smaller turn); false if none turns.
  bool FaceTheMotion(const PoseTarget& target, Eigen::VectorXd* u);

  ControlProblem& p_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_DIFFERENTIAL_TURNING_H_
