// Following waypoints with the loaded end-effector (`ccma trajectory
// --compensate`; docs/statics.md, "Control that compensates"): the path of
// FollowWaypoints (the same steps, problems/path.h), each step a compensated
// move (MoveToCompensated), started from the previous step's correction of
// the aim so that most steps need one or two rounds. Every reported step is
// the loaded configuration: `reached` and `state` are the loaded
// end-effector and state, result.error the loaded miss.
#ifndef CCMA_PROBLEMS_COMPENSATED_TRAJECTORY_H_
#define CCMA_PROBLEMS_COMPENSATED_TRAJECTORY_H_

#include <functional>
#include <vector>

#include "ccma/loads.h"
#include "formats/waypoints.h"
#include "problems/compensated_control.h"
#include "problems/trajectory.h"

namespace ccma {

struct CompensatedPath {
  int rounds = 0;       // rigid control problems solved, all steps
  double max_miss = 0;  // largest loaded miss over the steps [m or rad]
};

// As FollowWaypoints; stops at the first step whose loaded end-effector does
// not reach its target (the result's warning says why). Throws
// std::invalid_argument when the path would take more than kMaxPathSteps.
TrajectoryResult FollowWaypointsCompensated(ControlProblem& problem, const std::vector<Waypoint>& waypoints,
                                            const ExternalWrench& wrench,
                                            const std::function<void(const TrajectoryStep&)>& on_step,
                                            CompensatedPath* path);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_COMPENSATED_TRAJECTORY_H_
