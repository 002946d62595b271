// The cost of inverse dynamics per row against the trajectory that made the
// rows (issue target: `ccma dynamics` at most 3x `ccma trajectory`'s own
// time per row on the 6-agent model). The path: 201 waypoints on the 5 cm
// loop of benchmarks/RESULTS.md (x = 5 cm sin t, y = 5 cm (1 - cos t),
// z = 0.6 m + 4 cm sin t, yaw = 0.05 sin t over 100 s).
//   Trajectory/...: FollowWaypoints from home, as `ccma trajectory`;
//   Dynamics/...:   ComputeDynamics over the rows it wrote, as `ccma dynamics`.
// Both report per_row (seconds per written row); compare them within one run.
// The massless model is the bundled one; "payload" adds a 2 kg payload and
// 1 kg on every body (dynamics does the same work, the trajectory then also
// computes its effort columns: ccma trajectory does so only in the CLI).
//   build/benchmarks/dynamics_benchmark --benchmark_repetitions=5 \
//       --benchmark_report_aggregates_only=true
#include <cmath>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "analyses/dynamics.h"
#include "ccma/ccma.h"

namespace {

using namespace ccma;

Model SixAgents(bool masses) {
  Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/6dof_six_agents.yaml");
  if (!masses) return model;
  model.end_effector.payload.mass = 2.0;
  for (Body& body : model.bodies) {
    body.inertia.mass = 1.0;
    body.inertia.inertia_B = 0.01 * Eigen::Matrix3d::Identity();
  }
  return model;
}

std::vector<Waypoint> Loop() {
  std::vector<Waypoint> out;
  for (int i = 0; i <= 200; ++i) {
    const double t = 0.5 * i, angle = M_PI * t / 50.0;
    Waypoint w;
    w.time = t;
    w.position = Eigen::Vector3d(0.05 * std::sin(angle), 0.05 * (1 - std::cos(angle)), 0.6 + 0.04 * std::sin(angle));
    w.rpy = Eigen::Vector3d(0, 0, 0.05 * std::sin(angle));
    out.push_back(w);
  }
  return out;
}

// The rows FollowWaypoints writes, as ComputeDynamics reads them back.
ControlPath Rows(const std::vector<TrajectoryStep>& steps) {
  ControlPath path;
  path.source = "benchmark";
  double last = -1;
  for (const TrajectoryStep& s : steps) {
    if (s.time <= last) continue;  // a row per time, as the CSV reader insists
    last = s.time;
    path.times.push_back(s.time);
    path.controls.push_back(s.controls);
    path.lines.push_back(0);
    path.reached.push_back(s.reached.position);
  }
  return path;
}

void BM_Trajectory(benchmark::State& state, bool masses) {
  const Model model = SixAgents(masses);
  const std::vector<Waypoint> waypoints = Loop();
  long rows = 0;
  for (auto _ : state) {
    ControlProblem control(model, ControlOptions());
    long n = 0;
    const TrajectoryResult r = FollowWaypoints(control, waypoints, [&](const TrajectoryStep&) { ++n; });
    if (!r.converged) state.SkipWithError("trajectory not converged");
    rows += n;
  }
  state.counters["rows"] = static_cast<double>(rows) / static_cast<double>(state.iterations());
  state.counters["per_row"] = benchmark::Counter(static_cast<double>(rows), benchmark::Counter::kIsRate |
                                                                           benchmark::Counter::kInvert);
}

void BM_Dynamics(benchmark::State& state, bool masses) {
  const Model model = SixAgents(masses);
  ControlProblem control(model, ControlOptions());
  std::vector<TrajectoryStep> steps;
  FollowWaypoints(control, Loop(), [&](const TrajectoryStep& s) { steps.push_back(s); });
  const ControlPath path = Rows(steps);
  long rows = 0;
  for (auto _ : state) {
    const DynamicsReport r = ComputeDynamics(model, path);
    if (r.not_assembled_rows > 0) state.SkipWithError("a row did not assemble");
    benchmark::DoNotOptimize(r.rows.data());
    rows += static_cast<long>(r.rows.size());
  }
  state.counters["rows"] = static_cast<double>(path.times.size());
  state.counters["per_row"] = benchmark::Counter(static_cast<double>(rows), benchmark::Counter::kIsRate |
                                                                           benchmark::Counter::kInvert);
}

BENCHMARK_CAPTURE(BM_Trajectory, massless, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Dynamics, massless, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Trajectory, payload, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Dynamics, payload, true)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
