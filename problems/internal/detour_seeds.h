// Starts for ccma plan (problems/plan.h) where the greedy walk stalls: a
// local optimisation cannot leave the wrong side of an obstacle it was
// started against (the pull of the next waypoint points straight into it),
// so the stalled leg is bent sideways first. Each seed inserts three
// waypoints across the leg, at 1/4, 1/2 and 3/4 of it, moved horizontally
// perpendicular to it by A sin(pi f) for A = +-0.15, +-0.3, +-0.5, +-0.8 m,
// and walks the path greedily (clearance held); the seed that reaches the
// most waypoints, then travels least, is kept, and the next stall (if any)
// is bent the same way. The plan then straightens and smooths the result.
#ifndef CCMA_PROBLEMS_INTERNAL_DETOUR_SEEDS_H_
#define CCMA_PROBLEMS_INTERNAL_DETOUR_SEEDS_H_

#include <functional>
#include <vector>

#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "problems/trajectory.h"

namespace ccma {

// A waypoint path with detour waypoints inserted; original[i]: waypoint i
// is one of the user's.
struct SeededPath {
  std::vector<Waypoint> waypoints;
  std::vector<bool> original;
  // How many of the user's waypoints the first `reached` of this path include.
  int OriginalAmong(int reached) const;
};

struct SeededWalk {
  SeededPath path;
  TrajectoryResult result;
  std::vector<TrajectoryStep> steps;
  double travel_m = 0;  // the bases' (x, y) path length
};

// The greedy walk of `waypoints` from (u0, s0), its stalled legs bent as
// above (at most `max_bends` of them). `after_walk(walks done, at most)`
// (optional) is called after every walk; when it returns false no further
// seed is walked. Leaves the problem at the best walk's end.
SeededWalk WalkWithDetours(ControlProblem& problem, const std::vector<Waypoint>& waypoints,
                           const Eigen::VectorXd& u0, const State& s0, int max_bends,
                           const std::function<bool(int, int)>& after_walk = nullptr);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_DETOUR_SEEDS_H_
