// The optimisation of ccma plan (problems/plan.h): Levenberg-Marquardt over
// the controls of all steps at once, each iteration one linearisation per
// step (the control step's own, ControlProblem::Linearize), one sparse
// constrained solve of the whole path (plan_system.h) and a trial that
// re-solves every step's forward problem from its last state.
#ifndef CCMA_PROBLEMS_INTERNAL_TRAJECTORY_PLANNER_H_
#define CCMA_PROBLEMS_INTERNAL_TRAJECTORY_PLANNER_H_

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "ccma/end_effector.h"
#include "ccma/state.h"
#include "problems/control_problem.h"
#include "problems/internal/plan_system.h"
#include "problems/plan.h"

namespace ccma {

// One step of a planned path.
struct PlannedStep {
  PoseTarget target;     // on the straight path (a waypoint at a leg's end)
  bool waypoint = false;
  Eigen::VectorXd u;     // all controls
  State s;
  double energy = 0;     // E at (s, u) [m^2]
};

class TrajectoryPlanner {
 public:
  TrajectoryPlanner(ControlProblem* problem, const PlanOptions& options);
  // Improves `steps` (assembled) from the start (u0, s0); returns the
  // iterations taken. `keep_going(iterations done)` is asked before each
  // iteration (false: stop now). *stopped_by: "converged" (the objective
  // stopped decreasing), "plan_iterations" (options.max_iterations) or
  // "plan_time_s" (keep_going said stop).
  int Optimize(const Eigen::VectorXd& u0, const State& s0, std::vector<PlannedStep>* steps,
               const std::function<bool(int)>& keep_going, std::string* stopped_by);

 private:
  // The objective at `steps` (their energies filled in).
  double Objective(const std::vector<PlannedStep>& steps) const;
  // The whole path's linear system at `steps`.
  PlanSystem Linearize(const Eigen::VectorXd& u0, const State& s0, const std::vector<PlannedStep>& steps);
  // Adds the smoothness and travel terms of the bases' x, y to H and g.
  void AddBaseTerms(const std::vector<PlannedStep>& steps, PlanSystem* system) const;
  // The bases' x, y residuals (second and first differences) and their
  // constant Jacobian over the stacked effective controls.
  Eigen::VectorXd BaseResiduals(const std::vector<PlannedStep>& steps, Eigen::SparseMatrix<double>* J) const;
  // `steps` moved by d (every step re-solved) into `next`; false if a step
  // does not assemble or leaves its constraints.
  bool Trial(const Eigen::VectorXd& u0, const State& s0, const Eigen::VectorXd& d,
             const std::vector<PlannedStep>& steps, std::vector<PlannedStep>* next);

  ControlProblem& p_;
  const PlanOptions options_;
  std::vector<int> base_columns_;  // effective columns that are a base's x or y
  Eigen::VectorXd u0_effective_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_TRAJECTORY_PLANNER_H_
