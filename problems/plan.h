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
// step from the planned controls) and the plan is finished: every row back
// at the margin exactly, midpoints between rows within 1e-6 m of it
// (problems/internal/plan_finish.h). The plan is returned only when it is no
// worse than the greedy trajectory: at least as many waypoints reached, and
// with as many, no more base travel and no less clearance; otherwise the
// greedy trajectory is, and `note` says why (naming the pair, the row and
// the shortfall when it is the clearance).
#ifndef CCMA_PROBLEMS_PLAN_H_
#define CCMA_PROBLEMS_PLAN_H_

#include <functional>
#include <string>
#include <vector>

#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "problems/trajectory.h"

namespace ccma {

// Where a plan stands, for a progress line (PlanOptions::on_progress).
struct PlanProgress {
  std::string phase;     // "greedy walk", "detour seeds", "optimisation", "finishing"
  int done = 0;          // walks, iterations or rows done in this phase
  int total = 0;         // of at most this many
  double elapsed_s = 0;  // since the plan began [s]
};

struct PlanOptions {
  double waypoint_weight = 1.0;    // [1], in (0, 1e6]
  double path_weight = 1e-2;       // [1], in [0, 1e6]
  double smoothness_weight = 1.0;  // [1], in [0, 1e6]
  double travel_weight = 1e-2;     // [1], in [0, 1e6]
  int max_iterations = 200;        // Gauss-Newton iterations of the whole path, in [1, 10000]
  // Wall-clock bound [s] on the detour seeds and the optimisation, in
  // [0, 1e6]: when it is reached the plan goes on from where they are
  // (PlanResult::stopped_by). The greedy walk and the finishing always run.
  double max_seconds = 120;
  // Called after every walk, iteration and finished row (optional).
  std::function<void(const PlanProgress&)> on_progress;
  // True if every field is in range; otherwise false and `why` (if not null) names it.
  bool IsValid(std::string* why) const;
};

// The settings `ccma plan` and Python's plan() take, under their names there.
struct PlanCommandSettings {
  double path_weight = 1e-2;
  double smoothness_weight = 1.0;
  double travel_weight = 1e-2;
  int plan_iterations = 200;  // PlanOptions::max_iterations
  double plan_time_s = 120;   // PlanOptions::max_seconds
};

// The options of `settings`; false, with `why` naming the setting as the
// command does ("plan_iterations must be in [1, 10000]"), when one is out of
// range (PlanOptions::IsValid).
bool PlanOptionsFromSettings(const PlanCommandSettings& settings, PlanOptions* options, std::string* why);

// A trajectory's measures (the comparison of plan and greedy).
struct PathMeasures {
  int reached_waypoints = 0;
  double travel_m = 0;            // sum over steps and bases of |(x, y) change| [m]
  double min_clearance_m = 0;     // smallest over the steps (+inf without collision geometry)
};

// The worst place where a finished plan (problems/internal/plan_finish.h)
// is still below the margin: a row more than 1e-9 m below its floor, or a
// midpoint between rows more than 1e-6 m below it or torn.
struct PlanShortfall {
  bool any = false;
  int step = 0;            // the row (1-based, as the CSV's data rows); a midpoint lies before it
  bool midpoint = false;   // half way between rows step - 1 and step (row 0: the start)
  bool torn = false;       // the midpoint does not assemble (residual energy >= 1e-6 m^2)
  std::string a, b;        // the pair: bodies, bases or obstacles
  double clearance_m = 0;  // its clearance there [m]
  double floor_m = 0;  // what it had to keep: the margin, or less where the pair began below it [m]
  double shortfall_m = 0;      // floor_m - clearance_m [m]
  double residual_energy = 0;  // at a midpoint [m^2]
  double time_s = 0;           // of the row, or half way [s]
};

struct PlanResult {
  std::vector<TrajectoryStep> steps;  // the returned trajectory (plan or greedy)
  bool converged = false;             // every waypoint reached
  bool used_plan = false;             // false: the greedy trajectory is returned
  int iterations = 0;                 // of the whole-path optimisation
  PathMeasures greedy, plan;          // plan: as optimised (before the choice)
  std::string greedy_warning;         // the greedy trajectory's, if it stopped
  std::string note;                   // why the greedy trajectory was kept, or ""
  PlanShortfall shortfall;  // where the finished plan is below the margin (any: kept the greedy)
  int repaired_rows = 0;    // rows brought back to the margin by the finishing
  int inserted_rows = 0;    // midpoint rows the finishing inserted
  // "converged" (the objective stopped decreasing), "plan_iterations" (the
  // iteration bound) or "plan_time_s" (the time bound).
  std::string stopped_by;
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
