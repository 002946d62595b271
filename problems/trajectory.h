// Following a list of end-effector waypoints: each leg is walked in small
// steps (ControlProblem::MoveTo), warm-started from the last; every step is
// reported with its (interpolated) time.
#ifndef CCMA_PROBLEMS_TRAJECTORY_H_
#define CCMA_PROBLEMS_TRAJECTORY_H_

#include <functional>
#include <vector>

#include "formats/waypoints.h"
#include "problems/control_problem.h"

namespace ccma {

struct TrajectoryStep {
  double time = 0;       // s, interpolated between the waypoints' times
  PoseTarget target;     // this step's target
  ControlStepResult result;
  Eigen::VectorXd controls;  // after the step
  EndEffectorPose reached;   // after the step
  State state;               // the configuration after the step
  int leg = 0;               // index of the waypoint this step walks to
};

struct TrajectoryResult {
  bool converged = true;   // every waypoint reached
  int reached_waypoints = 0;  // waypoints reached, in order, before a stop
  int steps = 0;
  int iterations = 0;
  double max_residual_energy = 0;
  double max_error = 0;    // largest final error over the waypoints [m, rad]
  double solve_time_ms = 0;
  std::string warning;     // the first waypoint not reached, if any
};

// The number of path steps walking `waypoints` from the problem's current
// pose takes; throws std::invalid_argument when it would be more than
// kMaxPathSteps (ccma/limits.h).
long CheckPathStepCount(const ControlProblem& problem, const std::vector<Waypoint>& waypoints);

// Starts from the problem's current controls; stops at the first waypoint it
// cannot reach (reported in the result). Throws std::invalid_argument when
// the whole path would take more than kMaxPathSteps steps (ccma/limits.h).
TrajectoryResult FollowWaypoints(ControlProblem& problem, const std::vector<Waypoint>& waypoints,
                                 const std::function<void(const TrajectoryStep&)>& on_step);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_TRAJECTORY_H_
