#include "problems/trajectory.h"

#include <algorithm>
#include <stdexcept>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "problems/path.h"

namespace ccma {

// The whole path's step count, bounded before anything runs.
long CheckPathStepCount(const ControlProblem& problem, const std::vector<Waypoint>& waypoints) {
  const ControlOptions& o = problem.options();
  PoseTarget from = problem.CurrentPose();
  double total = 0;
  for (const Waypoint& w : waypoints) {
    const PoseTarget to{w.position, w.rpy};
    total += PosePath(problem.forward().model(), from, to, o.max_step_m, o.max_step_rad).steps();
    if (total > static_cast<double>(kMaxPathSteps)) {
      throw std::invalid_argument("waypoints: the path takes more than " + std::to_string(kMaxPathSteps) +
                                  " steps of " + FormatG(o.max_step_m) + " m and " + FormatG(o.max_step_rad) +
                                  " rad");
    }
    from = to;
  }
  return static_cast<long>(total);
}

TrajectoryResult FollowWaypoints(ControlProblem& problem, const std::vector<Waypoint>& waypoints,
                                 const std::function<void(const TrajectoryStep&)>& on_step) {
  CheckPathStepCount(problem, waypoints);
  TrajectoryResult out;
  double previous_time = waypoints.empty() ? 0.0 : waypoints.front().time;
  for (size_t w = 0; w < waypoints.size(); ++w) {
    const Waypoint& waypoint = waypoints[w];
    // Count this leg's steps first, to spread the leg's time over them.
    std::vector<TrajectoryStep> steps;
    const ControlResult leg = problem.MoveTo(
        {waypoint.position, waypoint.rpy}, [&](const PoseTarget& target, const ControlStepResult& r) {
          TrajectoryStep step;
          step.target = target;
          step.result = r;
          step.controls = problem.controls();
          step.reached = problem.forward().end_effector();
          step.state = problem.forward().state();
          step.leg = static_cast<int>(w);
          steps.push_back(step);
        });
    for (size_t i = 0; i < steps.size(); ++i) {
      steps[i].time = previous_time + (waypoint.time - previous_time) * double(i + 1) / steps.size();
      if (on_step) on_step(steps[i]);
    }
    previous_time = waypoint.time;
    out.steps += leg.steps;
    out.iterations += leg.iterations;
    out.solve_time_ms += leg.solve_time_ms;
    out.max_residual_energy = std::max(out.max_residual_energy, leg.max_step_residual_energy);
    out.max_error = std::max(out.max_error, leg.error);
    if (leg.converged) ++out.reached_waypoints;
    if (!leg.converged) {
      out.converged = false;
      out.warning = "waypoint " + std::to_string(w) + " (time " + FormatG(waypoint.time) +
                    " s) not reached: " + leg.warning;
      break;
    }
  }
  return out;
}

}  // namespace ccma
