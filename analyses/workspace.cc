#include "analyses/workspace.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <numeric>
#include <random>
#include <stdexcept>
#include <thread>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "ccma/rotation.h"
#include "problems/path.h"

namespace ccma {
namespace {

double& Component(PoseTarget& pose, int c) { return c < 3 ? pose.position[c] : pose.rpy[c - 3]; }
double Component(const PoseTarget& pose, int c) { return c < 3 ? pose.position[c] : pose.rpy[c - 3]; }

// A range's width as the distance scale (1 for a single value).
double Scale(const WorkspaceRange& r) { return r.hi > r.lo ? r.hi - r.lo : 1.0; }

// Squared distance between two poses over the sampled components, each in
// units of its range.
double Distance2(const WorkspaceOptions& options, const PoseTarget& a, const PoseTarget& b) {
  double d2 = 0;
  for (const WorkspaceRange& r : options.ranges) {
    const double d = (Component(a, r.component) - Component(b, r.component)) / Scale(r);
    d2 += d * d;
  }
  return d2;
}

PoseTarget HomePose(const Model& model) {
  const EndEffectorPose home = ComputeEndEffectorPose(model, State::Home(model));
  return {home.position, home.rpy};
}

void CheckOptions(const Model& model, const WorkspaceOptions& options) {
  std::string why;
  if (!options.IsValid(model, &why)) throw std::invalid_argument("WorkspaceOptions: " + why);
}

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

// One sample: restore the start, walk to the pose, record.
WorkspaceSample Reach(ControlProblem& control, const WorkspaceStart& start, const PoseTarget& pose) {
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

// Runs job(problem, i) for i in [0, n) on `threads` threads, one
// ControlProblem each; rethrows the first exception.
void ParallelFor(const Model& model, const WorkspaceOptions& options, long long n,
                 const std::function<void(ControlProblem&, long long)>& job) {
  const int threads = static_cast<int>(std::min<long long>(options.threads, std::max<long long>(n, 1)));
  std::atomic<long long> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&]() {
    try {
      ControlProblem control(model, options.control);
      for (long long i = next++; i < n; i = next++) job(control, i);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = n;  // the others stop after their current sample
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

// Grid cell multi-index of sample i (last range fastest).
std::vector<int> Cell(long long i, int dims, int resolution) {
  std::vector<int> cell(static_cast<size_t>(dims));
  for (int d = dims - 1; d >= 0; --d) {
    cell[static_cast<size_t>(d)] = static_cast<int>(i % resolution);
    i /= resolution;
  }
  return cell;
}

long long Index(const std::vector<int>& cell, int resolution) {
  long long i = 0;
  for (int c : cell) i = i * resolution + c;
  return i;
}

}  // namespace

long long WorkspaceOptions::SampleCount() const {
  if (random_samples > 0) return random_samples;
  long long n = 1;
  for (size_t k = 0; k < ranges.size(); ++k) {
    n *= std::max(resolution, 1);
    if (n > kMaxSamples) return kMaxSamples + 1;  // no overflow: the caller only compares
  }
  return n;
}

bool WorkspaceOptions::IsValid(const Model& model, std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (ranges.empty() || ranges.size() > 6) return fail("ranges: 1 to 6 sampled components, got " + std::to_string(ranges.size()));
  std::array<bool, 6> seen{};
  for (const WorkspaceRange& r : ranges) {
    if (r.component < 0 || r.component > 5) return fail("ranges: component index " + std::to_string(r.component) + " is not in 0..5");
    const std::string name = kEndEffectorComponentNames[static_cast<size_t>(r.component)];
    if (!model.end_effector.controlled[static_cast<size_t>(r.component)]) {
      return fail("ranges: " + name + " is not a controlled component of model '" + model.name + "'");
    }
    if (seen[static_cast<size_t>(r.component)]) return fail("ranges: " + name + " is given twice");
    seen[static_cast<size_t>(r.component)] = true;
    if (!(std::abs(r.lo) <= kMaxMagnitude) || !(std::abs(r.hi) <= kMaxMagnitude)) {
      return fail("ranges: " + name + " bounds must be finite numbers in [-" + FormatG(kMaxMagnitude) + ", " +
                  FormatG(kMaxMagnitude) + "]");
    }
    if (!(r.lo <= r.hi)) return fail("ranges: " + name + " needs lo <= hi, got " + FormatG(r.lo) + ":" + FormatG(r.hi));
  }
  if (resolution < 1 || resolution > 10000) return fail("resolution must lie in [1, 10000], got " + std::to_string(resolution));
  if (random_samples < 0 || random_samples > kMaxRandomSamples) {
    return fail("samples must lie in [1, " + std::to_string(kMaxRandomSamples) + "], got " + std::to_string(random_samples));
  }
  if (SampleCount() > kMaxSamples) {
    return fail("resolution: " + std::to_string(resolution) + " points per range over " + std::to_string(ranges.size()) +
                " ranges exceed " + std::to_string(kMaxSamples) + " samples");
  }
  if (wave_size < 1 || wave_size > 100000) return fail("wave_size must lie in [1, 100000], got " + std::to_string(wave_size));
  if (threads < 1 || threads > 256) return fail("threads must lie in [1, 256], got " + std::to_string(threads));
  std::string control_why;
  if (!control.IsValid(&control_why)) return fail("control." + control_why);
  return true;
}

std::vector<PoseTarget> WorkspacePoses(const Model& model, const WorkspaceOptions& options) {
  CheckOptions(model, options);
  const PoseTarget home = HomePose(model);
  const long long n = options.SampleCount();
  std::vector<PoseTarget> poses(static_cast<size_t>(n), home);
  const int dims = static_cast<int>(options.ranges.size());
  if (options.random_samples > 0) {
    std::mt19937_64 rng(options.seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (PoseTarget& pose : poses) {
      for (const WorkspaceRange& r : options.ranges) Component(pose, r.component) = r.lo + (r.hi - r.lo) * unit(rng);
    }
    return poses;
  }
  for (long long i = 0; i < n; ++i) {
    const std::vector<int> cell = Cell(i, dims, options.resolution);
    for (int d = 0; d < dims; ++d) {
      const WorkspaceRange& r = options.ranges[static_cast<size_t>(d)];
      const int k = cell[static_cast<size_t>(d)];
      Component(poses[static_cast<size_t>(i)], r.component) =
          options.resolution == 1 ? 0.5 * (r.lo + r.hi)
                                  : r.lo + (r.hi - r.lo) * k / static_cast<double>(options.resolution - 1);
    }
  }
  return poses;
}

std::vector<WorkspaceSample> EvaluateWorkspacePoses(const Model& model, const WorkspaceOptions& options,
                                                    const std::vector<PoseTarget>& poses,
                                                    const std::vector<WorkspaceStart>& starts,
                                                    const WorkspaceProgress& progress) {
  CheckOptions(model, options);
  if (!starts.empty() && starts.size() != poses.size()) {
    throw std::invalid_argument("EvaluateWorkspacePoses: " + std::to_string(starts.size()) + " starts for " +
                                std::to_string(poses.size()) + " poses");
  }
  if (static_cast<long long>(poses.size()) > WorkspaceOptions::kMaxSamples) {
    throw std::invalid_argument("EvaluateWorkspacePoses: more than " + std::to_string(WorkspaceOptions::kMaxSamples) +
                                " poses");
  }
  const WorkspaceStart home{State::Home(model), model.home_controls()};
  std::vector<WorkspaceSample> samples(poses.size());
  std::mutex progress_mutex;
  long long done = 0;
  const long long n = static_cast<long long>(poses.size());
  ParallelFor(model, options, n, [&](ControlProblem& control, long long i) {
    const auto k = static_cast<size_t>(i);
    samples[k] = Reach(control, starts.empty() ? home : starts[k], poses[k]);
    if (progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress(++done, n);
    }
  });
  return samples;
}

namespace {

// The index nearest the seed cell (the value nearest home) of range d.
int SeedIndex(const WorkspaceOptions& options, const WorkspaceRange& r, double home) {
  int best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int k = 0; k < options.resolution; ++k) {
    const double value = options.resolution == 1 ? 0.5 * (r.lo + r.hi)
                                                 : r.lo + (r.hi - r.lo) * k / static_cast<double>(options.resolution - 1);
    if (std::abs(value - home) < best_distance) best_distance = std::abs(value - home), best = k;
  }
  return best;
}

// Each sample's wave (file comment). Grid: Chebyshev distance in cells from
// the seed cell. Random: rank by distance from home, wave_size per wave.
std::vector<int> Waves(const WorkspaceOptions& options, const std::vector<PoseTarget>& poses,
                       const PoseTarget& home_pose) {
  const long long n = static_cast<long long>(poses.size());
  const int dims = static_cast<int>(options.ranges.size());
  std::vector<int> wave(static_cast<size_t>(n), 0);
  if (options.random_samples == 0) {
    std::vector<int> seed_cell(static_cast<size_t>(dims), 0);
    for (int d = 0; d < dims; ++d) {
      const WorkspaceRange& r = options.ranges[static_cast<size_t>(d)];
      seed_cell[static_cast<size_t>(d)] = SeedIndex(options, r, Component(home_pose, r.component));
    }
    for (long long i = 0; i < n; ++i) {
      const std::vector<int> cell = Cell(i, dims, options.resolution);
      int w = 0;
      for (int d = 0; d < dims; ++d) w = std::max(w, std::abs(cell[static_cast<size_t>(d)] - seed_cell[static_cast<size_t>(d)]));
      wave[static_cast<size_t>(i)] = w;
    }
    return wave;
  }
  std::vector<long long> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> d2(static_cast<size_t>(n));
  for (long long i = 0; i < n; ++i) d2[static_cast<size_t>(i)] = Distance2(options, poses[static_cast<size_t>(i)], home_pose);
  std::stable_sort(order.begin(), order.end(),
                   [&](long long a, long long b) { return d2[static_cast<size_t>(a)] < d2[static_cast<size_t>(b)]; });
  for (long long k = 0; k < n; ++k) wave[static_cast<size_t>(order[static_cast<size_t>(k)])] = static_cast<int>(k / options.wave_size);
  return wave;
}

// A map computed wave by wave: what the starts and the solves share.
struct WaveRun {
  const Model& model;
  const WorkspaceOptions& options;
  const std::vector<PoseTarget>& poses;
  const WorkspaceProgress& progress;
  PoseTarget home_pose;
  WorkspaceStart home;
  std::vector<int> wave;
  WorkspaceResult result;
  std::vector<long long> reached;  // reached samples of finished waves, ascending per wave
  long long done = 0;              // samples finished (progress)
  std::mutex progress_mutex;
};

// The nearest start found so far: home (-1) or a sample; ties go to the
// lower index.
struct Nearest {
  long long best;
  double best_d2;
  void Consider(long long j, double d) {
    if (d < best_d2 || (d == best_d2 && best >= 0 && j < best)) best_d2 = d, best = j;
  }
};

// Grid: considers the adjacent cells (3^dims - 1 offsets) of earlier waves
// that were reached. False when none qualifies.
bool ConsiderNeighbours(const WaveRun& run, long long i, Nearest* nearest) {
  const int dims = static_cast<int>(run.options.ranges.size()), resolution = run.options.resolution;
  const std::vector<int> cell = Cell(i, dims, resolution);
  bool any = false;
  long long offsets = 1;
  for (int d = 0; d < dims; ++d) offsets *= 3;
  for (long long o = 0; o < offsets; ++o) {
    std::vector<int> neighbour = cell;
    long long rest = o;
    bool inside = true;
    for (int d = 0; d < dims; ++d) {
      neighbour[static_cast<size_t>(d)] += static_cast<int>(rest % 3) - 1;
      rest /= 3;
      if (neighbour[static_cast<size_t>(d)] < 0 || neighbour[static_cast<size_t>(d)] >= resolution) inside = false;
    }
    if (!inside) continue;
    const long long j = Index(neighbour, resolution);
    if (run.wave[static_cast<size_t>(j)] >= run.wave[static_cast<size_t>(i)] ||
        !run.result.samples[static_cast<size_t>(j)].reachable) {
      continue;
    }
    nearest->Consider(j, Distance2(run.options, run.poses[static_cast<size_t>(i)], run.poses[static_cast<size_t>(j)]));
    any = true;
  }
  return any;
}

// The start of sample i: nearest reached sample of an earlier wave (grid:
// adjacent cells first), or home (-1) when nearer or nothing qualifies.
long long StartOf(const WaveRun& run, long long i) {
  const PoseTarget& pose = run.poses[static_cast<size_t>(i)];
  Nearest nearest{-1, Distance2(run.options, pose, run.home_pose)};
  const bool grid = run.options.random_samples == 0;
  if (grid && run.wave[static_cast<size_t>(i)] > 0 && ConsiderNeighbours(run, i, &nearest)) return nearest.best;
  for (long long j : run.reached) nearest.Consider(j, Distance2(run.options, pose, run.poses[static_cast<size_t>(j)]));
  return nearest.best;
}

// The state and controls a walk from sample s (-1: home) begins with.
WorkspaceStart StartFrom(const WaveRun& run, long long s) {
  if (s < 0) return run.home;
  return {run.result.samples[static_cast<size_t>(s)].state, run.result.samples[static_cast<size_t>(s)].controls};
}

// Wave w's samples solved by `evaluate_batch`, checked and stored.
void SolveWaveElsewhere(WaveRun* run, int w, const std::vector<long long>& batch, const std::vector<long long>& starts,
                        const WorkspaceBatchEvaluator& evaluate_batch) {
  std::vector<PoseTarget> batch_poses;
  std::vector<WorkspaceStart> batch_starts;
  for (size_t k = 0; k < batch.size(); ++k) {
    batch_poses.push_back(run->poses[static_cast<size_t>(batch[k])]);
    batch_starts.push_back(StartFrom(*run, starts[k]));
  }
  std::vector<WorkspaceSample> solved = evaluate_batch(batch_poses, batch_starts);
  if (solved.size() != batch.size()) {
    throw std::runtime_error("ComputeWorkspace: the batch evaluator returned " + std::to_string(solved.size()) +
                             " samples for " + std::to_string(batch.size()));
  }
  for (size_t k = 0; k < batch.size(); ++k) {
    if (solved[k].state.num_bodies() != run->model.num_bodies() ||
        solved[k].controls.size() != run->model.num_controls()) {
      throw std::runtime_error("ComputeWorkspace: the batch evaluator returned a sample of another model");
    }
    solved[k].pose = batch_poses[k];
    solved[k].wave = w;
    solved[k].start = starts[k];
    run->result.samples[static_cast<size_t>(batch[k])] = std::move(solved[k]);
  }
  run->done += static_cast<long long>(batch.size());
  if (run->progress) run->progress(run->done, static_cast<long long>(run->poses.size()));
}

// Wave w's samples solved on the local threads.
void SolveWaveHere(WaveRun* run, int w, const std::vector<long long>& batch, const std::vector<long long>& starts) {
  const long long n = static_cast<long long>(run->poses.size());
  ParallelFor(run->model, run->options, static_cast<long long>(batch.size()), [&](ControlProblem& control, long long k) {
    const long long i = batch[static_cast<size_t>(k)];
    const long long s = starts[static_cast<size_t>(k)];
    WorkspaceSample sample = Reach(control, StartFrom(*run, s), run->poses[static_cast<size_t>(i)]);
    sample.wave = w;
    sample.start = s;
    run->result.samples[static_cast<size_t>(i)] = std::move(sample);
    if (run->progress) {
      const std::lock_guard<std::mutex> lock(run->progress_mutex);
      run->progress(++run->done, n);
    }
  });
}

}  // namespace

WorkspaceResult ComputeWorkspace(const Model& model, const WorkspaceOptions& options,
                                 const WorkspaceProgress& progress, const WorkspaceBatchEvaluator& evaluate_batch) {
  const auto clock_start = std::chrono::steady_clock::now();
  const std::vector<PoseTarget> poses = WorkspacePoses(model, options);  // validates
  WaveRun run{model, options, poses, progress, HomePose(model), {State::Home(model), model.home_controls()}};
  run.wave = Waves(options, poses, run.home_pose);
  const int waves = poses.empty() ? 0 : *std::max_element(run.wave.begin(), run.wave.end()) + 1;
  std::vector<std::vector<long long>> members(static_cast<size_t>(waves));
  for (size_t i = 0; i < poses.size(); ++i) members[static_cast<size_t>(run.wave[i])].push_back(static_cast<long long>(i));
  for (const WorkspaceRange& r : options.ranges) run.result.components.push_back(r.component);
  run.result.samples.resize(poses.size());
  for (int w = 0; w < waves; ++w) {
    const std::vector<long long>& batch = members[static_cast<size_t>(w)];
    std::vector<long long> starts(batch.size());
    for (size_t k = 0; k < batch.size(); ++k) starts[k] = StartOf(run, batch[k]);
    if (evaluate_batch) {
      SolveWaveElsewhere(&run, w, batch, starts, evaluate_batch);
    } else {
      SolveWaveHere(&run, w, batch, starts);
    }
    for (long long i : batch) {
      if (run.result.samples[static_cast<size_t>(i)].reachable) run.reached.push_back(i);
    }
  }
  for (const WorkspaceSample& s : run.result.samples) run.result.reachable += s.reachable;
  run.result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return std::move(run.result);
}

}  // namespace ccma
