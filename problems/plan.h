// Whole-trajectory planning (cli.md, `ccma plan`): the controls of every
// step of a waypoint path optimised together, from the greedy trajectory
// (trajectory.h) as a start. Objective, over the steps k = 1..N:
//   sum_k 1/2 w_k |e_k|^2 + lambda E_k              end-effector error, residual energy
//   + 1/2 w_smooth sum_k |x_{k+1} - 2 x_k + x_{k-1}|^2   smoothness of the bases' x, y
//   + 1/2 w_travel sum_k |x_k - x_{k-1}|^2               travel of the bases
// with w_k = waypoint_weight at a waypoint's step and path_weight between
// (how closely the end-effector keeps the straight path between waypoints:
// it may leave it to get round an obstacle). Every step keeps its joint
// limits and every clearance >= collision.margin (the step constraints, all
// steps at once). Each waypoint's step is then solved exactly (a control
// step from the planned controls). The plan is returned only when it is no
// worse than the greedy trajectory: at least as many waypoints reached, and
// with as many, no more base travel and no less clearance; otherwise the
// greedy trajectory is.
#ifndef CCMA_PROBLEMS_PLAN_H_
#define CCMA_PROBLEMS_PLAN_H_

#include <string>
#include <vector>

#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "problems/trajectory.h"

namespace ccma {

struct PlanOptions {
  double waypoint_weight = 1.0;    // [1], in (0, 1e6]
  double path_weight = 1e-2;       // [1], in [0, 1e6]
  double smoothness_weight = 1.0;  // [1], in [0, 1e6]
  double travel_weight = 1e-2;     // [1], in [0, 1e6]
  int max_iterations = 200;        // Gauss-Newton iterations of the whole path, in [1, 10000]
  // True if every field is in range; otherwise false and `why` (if not null) names it.
  bool IsValid(std::string* why) const;
};

// A trajectory's measures (the comparison of plan and greedy).
struct PathMeasures {
  int reached_waypoints = 0;
  double travel_m = 0;            // sum over steps and bases of |(x, y) change| [m]
  double min_clearance_m = 0;     // smallest over the steps (+inf without collision geometry)
};

struct PlanResult {
  std::vector<TrajectoryStep> steps;  // the returned trajectory (plan or greedy)
  bool converged = false;             // every waypoint reached
  bool used_plan = false;             // false: the greedy trajectory is returned
  int iterations = 0;                 // of the whole-path optimisation
  PathMeasures greedy, plan;          // plan: as optimised (before the choice)
  std::string greedy_warning;         // the greedy trajectory's, if it stopped
  std::string note;                   // why the greedy trajectory was kept, or ""
  double solve_time_ms = 0;
};

// Starts from the problem's current controls and state. Throws
// std::invalid_argument for a model with differential bases (their arcs tie
// neighbouring steps: not planned yet), the BFGS method, invalid options, or
// a path longer than kMaxPathSteps steps.
PlanResult PlanTrajectory(ControlProblem& problem, const std::vector<Waypoint>& waypoints,
                          const PlanOptions& options = {});

}  // namespace ccma

#endif  // CCMA_PROBLEMS_PLAN_H_
