// Internal to analyses/workspace*.cc: reaching one sample by continuation,
// the thread pool, and wave continuation over one tile's rows (with the
// samples of other tiles it may start from). The rules are those of
// analyses/workspace.h's file comment.
#ifndef CCMA_ANALYSES_INTERNAL_WORKSPACE_WAVES_H_
#define CCMA_ANALYSES_INTERNAL_WORKSPACE_WAVES_H_

#include <functional>
#include <vector>

#include "analyses/workspace.h"

namespace ccma::internal {

// Component c (0..5: x y z roll pitch yaw) of a pose [m or rad].
double& PoseComponent(PoseTarget& pose, int c);
double PoseComponent(const PoseTarget& pose, int c);

// Squared distance between two poses over the sampled components, each in
// units of its range width (1 for a single value).
double WorkspaceDistance2(const WorkspaceOptions& options, const PoseTarget& a, const PoseTarget& b);

// The end-effector pose at the home configuration.
PoseTarget WorkspaceHomePose(const Model& model);

// Throws std::invalid_argument("WorkspaceOptions: ...") unless valid.
void CheckWorkspaceOptions(const Model& model, const WorkspaceOptions& options);

// One sample: restore `start`, walk to `pose`, record (wave, start, tile
// left for the caller).
WorkspaceSample ReachPose(ControlProblem& control, const WorkspaceStart& start, const PoseTarget& pose);

// Runs job(problem, i) for i in [0, n) on `threads` threads, one
// ControlProblem each, i handed out by an atomic counter; rethrows the first
// exception.
void ParallelFor(const Model& model, const ControlOptions& control, int threads, long long n,
                 const std::function<void(ControlProblem&, long long)>& job);

// A sample of another, finished tile that an item may start from.
struct WaveOutside {
  long long row = 0;
  PoseTarget pose;
  int wave = 0;
  const WorkspaceSample* sample = nullptr;  // used when reachable
};

// Items continued wave by wave. Candidates for a start are indexed items
// first, then `outside` (index items + k for outside[k]); a candidate
// qualifies when reached and of an earlier wave than the item.
struct WaveItems {
  std::vector<PoseTarget> poses;           // per item
  std::vector<long long> rows;             // per item: its map row (a sample's `start`, ties)
  std::vector<int> wave;                   // per item, >= 0 (waves may be skipped)
  std::vector<std::vector<int>> adjacent;  // per item: candidates tried first (grid neighbours); may be empty
  std::vector<WaveOutside> outside;
};

// Solves one wave's poses from their starts; one sample per pose.
using WaveSolver = std::function<std::vector<WorkspaceSample>(const std::vector<PoseTarget>& poses,
                                                              const std::vector<WorkspaceStart>& starts)>;

// Fills (*results)[i] for every item, wave by wave: starts as in the file
// comment of analyses/workspace.h, then `solve`; sets each sample's pose,
// wave and start (a row, -1 for home). `done(k)` after each wave with the k
// samples it solved.
void SolveInWaves(const Model& model, const WorkspaceOptions& options, const WaveItems& items,
                  const WaveSolver& solve, const std::function<void(long long)>& done,
                  std::vector<WorkspaceSample>* results);

}  // namespace ccma::internal

#endif  // CCMA_ANALYSES_INTERNAL_WORKSPACE_WAVES_H_
