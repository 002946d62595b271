#include "problems/compensated_trajectory.h"

#include <algorithm>
#include <string>

#include "ccma/internal/format.h"
#include "problems/path.h"

namespace ccma {
namespace {

// The row of one compensated step: the loaded configuration.
TrajectoryStep LoadedStep(const ControlProblem& problem, const PoseTarget& target, const CompensatedResult& c, int leg) {
  TrajectoryStep step;
  step.target = target;
  step.leg = leg;
  step.controls = problem.controls();
  step.state = c.loaded.converged ? c.loaded.state : problem.forward().state();
  step.reached = ComputeEndEffectorPose(problem.forward().model(), step.state);
  step.result.reached = c.converged;
  step.result.assembled = c.control.assembled;
  // The distance of the row's own configuration (the rigid one where no
  // loaded equilibrium was found).
  step.result.error = c.loaded.converged ? c.miss
                                         : ControlledMiss(problem.forward().model(), target, step.reached).cwiseAbs().maxCoeff();
  step.result.iterations = c.control.iterations;
  step.result.residual_energy = c.control.residual_energy;
  step.result.time_ms = c.control.solve_time_ms;
  step.result.min_singular_value_dX_du = c.control.min_singular_value_dX_du;
  step.result.rcond = c.control.rcond;
  return step;
}

}  // namespace

TrajectoryResult FollowWaypointsCompensated(ControlProblem& problem, const std::vector<Waypoint>& waypoints,
                                            const ExternalWrench& wrench,
                                            const std::function<void(const TrajectoryStep&)>& on_step,
                                            CompensatedPath* path) {
  CheckPathStepCount(problem, waypoints);
  const ControlOptions& o = problem.options();
  TrajectoryResult out;
  CompensationOptions compensation;
  compensation.check_held = false;  // no row reports it
  compensation.workspace = NewLoadedWorkspace();
  PoseTarget from = problem.CurrentPose();
  double previous_time = waypoints.empty() ? 0.0 : waypoints.front().time;
  for (size_t w = 0; w < waypoints.size() && out.converged; ++w) {
    const PoseTarget to{waypoints[w].position, waypoints[w].rpy};
    const PosePath leg(problem.forward().model(), from, to, o.max_step_m, o.max_step_rad);
    for (int i = 1; i <= leg.steps(); ++i) {
      const PoseTarget target = leg.At(i);
      const CompensatedResult c = MoveToCompensated(&problem, target, wrench, compensation);
      compensation.aim_offset << c.aim.position - target.position, c.aim.rpy - target.rpy;
      if (c.loaded.converged) compensation.start = c.loaded;
      TrajectoryStep step = LoadedStep(problem, target, c, static_cast<int>(w));
      step.time = previous_time + (waypoints[w].time - previous_time) * double(i) / leg.steps();
      if (on_step) on_step(step);
      ++out.steps;
      out.iterations += c.control.iterations;
      out.solve_time_ms += c.control.solve_time_ms;
      out.max_residual_energy = std::max(out.max_residual_energy, c.control.max_step_residual_energy);
      path->rounds += c.rounds;
      path->max_miss = std::max(path->max_miss, c.miss);
      out.max_error = std::max(out.max_error, step.result.error);
      if (!c.converged) {
        out.converged = false;
        out.warning = "waypoint " + std::to_string(w) + " (time " + FormatG(waypoints[w].time) + " s), step " +
                      std::to_string(i) + " of " + std::to_string(leg.steps()) + " not reached: " + c.warning;
        break;
      }
    }
    if (!out.converged) break;
    ++out.reached_waypoints;
    previous_time = waypoints[w].time;
    from = to;
  }
  return out;
}

}  // namespace ccma
