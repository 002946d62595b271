#include "problems/internal/detour_seeds.h"

#include <cmath>

namespace ccma {
namespace {

double Travel(const Model& model, const Eigen::VectorXd& u0, const std::vector<TrajectoryStep>& steps) {
  double travel = 0;
  Eigen::VectorXd previous = u0;
  for (const TrajectoryStep& s : steps) {
    for (int k = 0; k < model.num_bases(); ++k) {
      travel += (s.controls.segment<2>(3 * k) - previous.segment<2>(3 * k)).norm();
    }
    previous = s.controls;
  }
  return travel;
}

SeededWalk Walk(ControlProblem& problem, const SeededPath& path, const Eigen::VectorXd& u0, const State& s0) {
  SeededWalk walk;
  walk.path = path;
  problem.forward().Restore(s0, u0);
  walk.result = FollowWaypoints(problem, path.waypoints, [&](const TrajectoryStep& s) { walk.steps.push_back(s); });
  walk.travel_m = Travel(problem.forward().model(), u0, walk.steps);
  return walk;
}

// `path` with leg `leg` (from `from` to its waypoint) bent sideways by `amplitude` [m].
SeededPath Bend(const SeededPath& path, int leg, const Waypoint& from, double amplitude) {
  const Waypoint& to = path.waypoints[static_cast<size_t>(leg)];
  Eigen::Vector2d along = (to.position - from.position).head<2>();
  if (!(along.norm() > 1e-9)) along = Eigen::Vector2d::UnitX();
  const Eigen::Vector2d across = Eigen::Vector2d(-along.y(), along.x()).normalized();
  SeededPath out;
  for (int i = 0; i < static_cast<int>(path.waypoints.size()); ++i) {
    if (i == leg) {
      for (double f : {0.25, 0.5, 0.75}) {
        Waypoint w;
        w.time = from.time + f * (to.time - from.time);
        w.position = from.position + f * (to.position - from.position);
        w.position.head<2>() += amplitude * std::sin(M_PI * f) * across;
        w.rpy = from.rpy + f * (to.rpy - from.rpy);
        out.waypoints.push_back(w);
        out.original.push_back(false);
      }
    }
    out.waypoints.push_back(path.waypoints[static_cast<size_t>(i)]);
    out.original.push_back(path.original[static_cast<size_t>(i)]);
  }
  return out;
}

bool Better(const SeededWalk& a, const SeededWalk& b) {
  const int ra = a.path.OriginalAmong(a.result.reached_waypoints);
  const int rb = b.path.OriginalAmong(b.result.reached_waypoints);
  return ra > rb || (ra == rb && a.travel_m < b.travel_m);
}

}  // namespace

int SeededPath::OriginalAmong(int reached) const {
  int count = 0;
  for (int i = 0; i < reached && i < static_cast<int>(original.size()); ++i) count += original[static_cast<size_t>(i)];
  return count;
}

SeededWalk WalkWithDetours(ControlProblem& problem, const std::vector<Waypoint>& waypoints,
                           const Eigen::VectorXd& u0, const State& s0, int max_bends,
                           const std::function<bool(int, int)>& after_walk) {
  const std::vector<double> amplitudes = {0.15, -0.15, 0.3, -0.3, 0.5, -0.5, 0.8, -0.8};
  const int most = 1 + max_bends * static_cast<int>(amplitudes.size());
  int walks = 0;
  bool go_on = true;
  auto walked = [&] {
    ++walks;
    go_on = go_on && (!after_walk || after_walk(walks, most));
  };
  problem.forward().Restore(s0, u0);
  const PoseTarget start = problem.CurrentPose();
  SeededPath plain{waypoints, std::vector<bool>(waypoints.size(), true)};
  SeededWalk best = Walk(problem, plain, u0, s0);
  walked();
  for (int bend = 0; bend < max_bends && !best.result.converged && go_on; ++bend) {
    const int leg = best.result.reached_waypoints;
    const Waypoint from = leg == 0 ? Waypoint{waypoints.front().time, start.position, start.rpy}
                                   : best.path.waypoints[static_cast<size_t>(leg - 1)];
    SeededWalk chosen = best;
    for (size_t a = 0; a < amplitudes.size() && go_on; ++a) {
      const SeededWalk seeded = Walk(problem, Bend(best.path, leg, from, amplitudes[a]), u0, s0);
      walked();
      if (Better(seeded, chosen)) chosen = seeded;
    }
    if (!Better(chosen, best)) break;
    best = chosen;
  }
  problem.forward().Restore(best.steps.empty() ? s0 : best.steps.back().state,
                            best.steps.empty() ? u0 : best.steps.back().controls);
  return best;
}

}  // namespace ccma
