// Workspace maps (issue 12 item 1): which end-effector poses the mechanism
// can reach, with the controls found and how well conditioned it is there.
//
// Poses are sampled over some of the model's controlled components (a grid
// over [lo, hi] per component, or seeded uniform samples); components not
// sampled keep their home value. Each sample is reached by continuation: the
// ControlProblem is put at the final configuration of an already reached
// sample (or at home) and walks the end-effector to the sample along a
// PosePath (ControlProblem::MoveTo, steps of max_step_m / max_step_rad).
// A sample whose path would take more than kMaxPathSteps steps is not walked:
// it is unreachable, with the path's reason as its warning, and the rest of
// the map is computed as usual.
//
// Determinism: samples are processed in "waves". A grid sample's wave is its
// Chebyshev distance (in cells) from the cell nearest the home pose; seeded
// samples are sorted by distance from home and cut into waves of
// `wave_size`. A sample starts from the nearest reached sample of an EARLIER
// wave (distances over the sampled components, each divided by its range;
// grids look at the adjacent cells first; ties go to the lower index), or
// from home when home is nearer or nothing is reached. Every solve starts
// from a restored state and controls (no warm-start memory is carried over),
// so results depend only on the options and never on the thread count or on
// which thread solved what. Threads share the Model read-only and own one
// ControlProblem each (std::thread); a wave's samples are handed out through
// an atomic counter.
#ifndef CCMA_PROBLEMS_WORKSPACE_H_
#define CCMA_PROBLEMS_WORKSPACE_H_

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/end_effector.h"
#include "ccma/model.h"
#include "ccma/state.h"
#include "problems/control_problem.h"

namespace ccma {

// One sampled component: index 0..5 into x y z roll pitch yaw (it must be
// one of the model's controlled components) and its range [lo, hi] in m or
// rad, lo <= hi.
struct WorkspaceRange {
  int component = 0;
  double lo = 0;
  double hi = 0;
};

struct WorkspaceOptions {
  std::vector<WorkspaceRange> ranges;  // 1..6 distinct components
  // Grid: `resolution` points per range, ends included (1 = the range's
  // midpoint), in [1, 10000]; the grid's total is at most kMaxSamples.
  int resolution = 11;
  // > 0: that many seeded uniform samples instead of the grid, in
  // [1, kMaxRandomSamples] (the nearest-start search is quadratic).
  int random_samples = 0;
  std::uint64_t seed = 1;  // random samples' generator seed
  int wave_size = 64;      // random samples per wave, in [1, 100000]
  int threads = 1;         // worker threads, in [1, 256]
  ControlOptions control;  // the continuation's controller (path steps, tolerance)

  static constexpr long long kMaxSamples = 1000000;
  static constexpr int kMaxRandomSamples = 100000;

  // Number of samples these options give (grid product or random_samples).
  long long SampleCount() const;
  // True if every field is in range and the ranges name distinct controlled
  // components of `model`; otherwise false and a message naming the field.
  bool IsValid(const Model& model, std::string* why) const;
};

struct WorkspaceSample {
  PoseTarget pose;           // the target: sampled components, others at home
  bool reachable = false;    // converged, assembled and within the target tolerance
  bool converged = false;    // the control loop reached the target (ControlResult)
  bool assembled = false;    // E below forward.assembly_tolerance at the end
  Eigen::VectorXd controls;  // all controls found (at the end, reachable or not)
  double residual_energy = 0;  // E at the end [m^2]
  double error = 0;            // max end-effector error [m or rad]
  double sigma_min = 0;        // smallest singular value of dX_c/du at the end; 0 when unreachable
  double rcond = 0;            // pivot ratio of dG/ds at the end
  double max_limit_violation = 0;  // worst joint-limit violation on the way [rad or m]
  std::string limited_by;          // joints held at a limit when it stopped ("" if none)
  int wave = 0;                    // continuation wave
  long long start = -1;            // sample it started from (-1: home)
  int steps = 0;                   // path steps walked
  std::string warning;             // why it was not reached ("" if reached)
  State state;                     // final configuration (a later sample's start)
};

struct WorkspaceResult {
  std::vector<int> components;           // sampled components, in option order
  std::vector<WorkspaceSample> samples;  // grid order (last range fastest) or draw order
  long long reachable = 0;
  double seconds = 0;                    // wall time
};

// Called as samples finish (from worker threads, one at a time): samples
// done so far and the total.
using WorkspaceProgress = std::function<void(long long done, long long total)>;

// The sample poses of `options` in output order (sampled components set,
// the others at the home pose). Throws std::invalid_argument if the options
// are not valid for the model.
std::vector<PoseTarget> WorkspacePoses(const Model& model, const WorkspaceOptions& options);

// Where a sample's walk begins: a configuration and all controls.
struct WorkspaceStart {
  State state;
  Eigen::VectorXd controls;
};

// Solves one wave's samples elsewhere (e.g. on a Dask cluster): given the
// poses and their starts, returns one WorkspaceSample per pose, as
// EvaluateWorkspacePoses() would (pose, reachable, ..., state filled).
using WorkspaceBatchEvaluator = std::function<std::vector<WorkspaceSample>(const std::vector<PoseTarget>& poses,
                                                                           const std::vector<WorkspaceStart>& starts)>;

// The whole map (see the file comment). Throws std::invalid_argument if the
// options are not valid for the model. With `evaluate_batch`, every wave is
// handed to it instead of the local threads (progress then advances per
// wave); the waves and starts are the same, so are the results.
WorkspaceResult ComputeWorkspace(const Model& model, const WorkspaceOptions& options,
                                 const WorkspaceProgress& progress = nullptr,
                                 const WorkspaceBatchEvaluator& evaluate_batch = nullptr);

// An explicit list of poses, each reached independently from its start
// (`starts[i]`, a state and all controls, e.g. a reached sample's; or home
// when `starts` is empty), on options.threads threads. What a distributed
// run sends to a worker in chunks; the result depends only on the inputs.
std::vector<WorkspaceSample> EvaluateWorkspacePoses(const Model& model, const WorkspaceOptions& options,
                                                    const std::vector<PoseTarget>& poses,
                                                    const std::vector<WorkspaceStart>& starts = {},
                                                    const WorkspaceProgress& progress = nullptr);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_WORKSPACE_H_
