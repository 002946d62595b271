#include "analyses/internal/workspace_waves.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "ccma/limits.h"
#include "ccma/rotation.h"
#include "problems/path.h"

namespace ccma::internal {

double& PoseComponent(PoseTarget& pose, int c) { return c < 3 ? pose.position[c] : pose.rpy[c - 3]; }
double PoseComponent(const PoseTarget& pose, int c) { return c < 3 ? pose.position[c] : pose.rpy[c - 3]; }

double WorkspaceDistance2(const WorkspaceOptions& options, const PoseTarget& a, const PoseTarget& b) {
  double d2 = 0;
  for (const WorkspaceRange& r : options.ranges) {
    const double scale = r.hi > r.lo ? r.hi - r.lo : 1.0;
    const double d = (PoseComponent(a, r.component) - PoseComponent(b, r.component)) / scale;
    d2 += d * d;
  }
  return d2;
}

PoseTarget WorkspaceHomePose(const Model& model) {
  const EndEffectorPose home = ComputeEndEffectorPose(model, State::Home(model));
  return {home.position, home.rpy};
}

void CheckWorkspaceOptions(const Model& model, const WorkspaceOptions& options) {
  std::string why;
  if (!options.IsValid(model, &why)) throw std::invalid_argument("WorkspaceOptions: " + why);
}

namespace {

// A sample whose walk would take more than kMaxPathSteps path steps: not
// reached, with the path's reason, so that one far sample does not abort the
// whole map. Nothing was walked: the start's controls and state are kept.
WorkspaceSample TooFar(ControlProblem& control, const PoseTarget& pose, const std::string& why) {
  WorkspaceSample sample;
  sample.pose = pose;
  sample.controls = control.controls();
  sample.residual_energy = control.forward().Energy();
  const PoseTarget here = control.CurrentPose();
  for (int c = 0; c < 6; ++c) {  // the start's error: largest controlled component [m or rad]
    if (!control.forward().model().end_effector.controlled[c]) continue;
    const double d = c < 3 ? here.position[c] - pose.position[c] : WrapAngle(here.rpy[c - 3] - pose.rpy[c - 3]);
    sample.error = std::max(sample.error, std::abs(d));
  }
  sample.warning = why;
  sample.state = control.forward().state();
  return sample;
}

}  // namespace

WorkspaceSample ReachPose(ControlProblem& control, const WorkspaceStart& start, const PoseTarget& pose) {
  control.forward().Restore(start.state, start.controls);
  // The path MoveTo would walk; too many steps throw (problems/path.h). A pose
  // out of range is left to MoveTo, which refuses it as before.
  const bool in_range =
      (pose.position.array().abs() <= kMaxMagnitude).all() && (pose.rpy.array().abs() <= kMaxMagnitude).all();
  try {
    const ControlOptions& o = control.options();
    if (in_range) PosePath(control.forward().model(), control.CurrentPose(), pose, o.max_step_m, o.max_step_rad);
  } catch (const std::invalid_argument& e) {
    return TooFar(control, pose, e.what());
  }
  WorkspaceSample sample;
  sample.pose = pose;
  const ControlResult r = control.MoveTo(pose);
  const double tolerance = control.options().target_tolerance;
  const double assembly = control.options().forward.assembly_tolerance;
  sample.converged = r.converged;
  sample.assembled = r.assembled && r.residual_energy < assembly;
  sample.reachable = r.converged && sample.assembled && r.error <= tolerance;
  sample.controls = control.controls();
  sample.residual_energy = r.residual_energy;
  sample.error = r.error;
  sample.sigma_min = sample.reachable && std::isfinite(r.min_singular_value_dX_du) ? r.min_singular_value_dX_du : 0;
  sample.rcond = std::isfinite(r.rcond) ? r.rcond : 0;
  sample.max_limit_violation = r.max_limit_violation;
  sample.limited_by = r.limited_by;
  sample.steps = r.steps;
  sample.warning = sample.reachable ? "" : (r.warning.empty() ? "target not reached" : r.warning);
  sample.state = control.forward().state();
  return sample;
}

void ParallelFor(const Model& model, const ControlOptions& control_options, int threads_wanted, long long n,
                 const std::function<void(ControlProblem&, long long)>& job) {
  const int threads = static_cast<int>(std::min<long long>(threads_wanted, std::max<long long>(n, 1)));
  std::atomic<long long> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&]() {
    try {
      ControlProblem control(model, control_options);
      for (long long i = next++; i < n; i = next++) job(control, i);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = n;  // the others stop after their current item
    }
  };
  if (threads <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    pool.reserve(static_cast<size_t>(threads));
    for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (std::thread& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

namespace {

// The nearest start found so far: home (row -1) or a candidate. Ties go
// to home, then to the lower row; so the choice does not depend on the order
// in which candidates are considered.
struct Nearest {
  long long row = -1;
  double d2 = 0;
  int candidate = -1;
  void Consider(long long r, double d, int c) {
    if (d < d2 || (d == d2 && row >= 0 && r < row)) row = r, d2 = d, candidate = c;
  }
};

// Candidate c (an item or an outside sample): its row, pose, wave and result.
struct Candidate {
  long long row;
  const PoseTarget* pose;
  int wave;
  const WorkspaceSample* sample;
};

Candidate CandidateAt(const WaveItems& items, const std::vector<WorkspaceSample>& results, int c) {
  const auto k = static_cast<size_t>(c);
  if (k < items.poses.size()) return {items.rows[k], &items.poses[k], items.wave[k], &results[k]};
  const WaveOutside& o = items.outside[k - items.poses.size()];
  return {o.row, &o.pose, o.wave, o.sample};
}

// Where item i starts: the reached adjacent candidates of earlier waves,
// when there are any; else every reached candidate of an earlier wave; home
// when nearer.
Nearest StartOf(const WorkspaceOptions& options, const WaveItems& items, const std::vector<WorkspaceSample>& results,
                const std::vector<int>& reached, const PoseTarget& home_pose, int i) {
  const PoseTarget& pose = items.poses[static_cast<size_t>(i)];
  const int wave = items.wave[static_cast<size_t>(i)];
  const int n = static_cast<int>(items.poses.size());
  Nearest nearest;
  nearest.d2 = WorkspaceDistance2(options, pose, home_pose);
  auto consider = [&](int c) {
    const Candidate k = CandidateAt(items, results, c);
    nearest.Consider(k.row, WorkspaceDistance2(options, pose, *k.pose), c);
  };
  if (!items.adjacent.empty()) {
    bool any = false;
    for (int j : items.adjacent[static_cast<size_t>(i)]) {
      const Candidate k = CandidateAt(items, results, j);
      if (k.wave >= wave || !k.sample->reachable) continue;
      consider(j);
      any = true;
    }
    if (any) return nearest;
  }
  for (int j : reached) consider(j);  // items of finished waves
  for (size_t k = 0; k < items.outside.size(); ++k) {
    if (items.outside[k].wave < wave && items.outside[k].sample->reachable) consider(n + static_cast<int>(k));
  }
  return nearest;
}

}  // namespace

void SolveInWaves(const Model& model, const WorkspaceOptions& options, const WaveItems& items,
                  const WaveSolver& solve, const std::function<void(long long)>& done,
                  std::vector<WorkspaceSample>* results) {
  const PoseTarget home_pose = WorkspaceHomePose(model);
  const WorkspaceStart home{State::Home(model), model.home_controls()};
  const int waves = items.wave.empty() ? 0 : *std::max_element(items.wave.begin(), items.wave.end()) + 1;
  std::vector<std::vector<int>> members(static_cast<size_t>(waves));
  for (size_t i = 0; i < items.wave.size(); ++i) members[static_cast<size_t>(items.wave[i])].push_back(static_cast<int>(i));
  std::vector<int> reached;  // reached items of finished waves
  for (int w = 0; w < waves; ++w) {
    const std::vector<int>& batch = members[static_cast<size_t>(w)];
    std::vector<long long> start_rows;
    std::vector<PoseTarget> poses;
    std::vector<WorkspaceStart> starts;
    for (int i : batch) {
      const Nearest s = StartOf(options, items, *results, reached, home_pose, i);
      start_rows.push_back(s.row);
      poses.push_back(items.poses[static_cast<size_t>(i)]);
      if (s.candidate < 0) {
        starts.push_back(home);
      } else {
        const WorkspaceSample& from = *CandidateAt(items, *results, s.candidate).sample;
        starts.push_back({from.state, from.controls});
      }
    }
    if (batch.empty()) continue;
    std::vector<WorkspaceSample> solved = solve(poses, starts);
    for (size_t k = 0; k < batch.size(); ++k) {
      solved[k].pose = poses[k];
      solved[k].wave = w;
      solved[k].start = start_rows[k];
      (*results)[static_cast<size_t>(batch[k])] = std::move(solved[k]);
    }
    if (done) done(static_cast<long long>(batch.size()));
    for (int i : batch) {
      if ((*results)[static_cast<size_t>(i)].reachable) reached.push_back(i);
    }
  }
}

}  // namespace ccma::internal
