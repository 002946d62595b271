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
// Waves: a grid sample's wave is its Chebyshev distance (in cells) from the
// cell nearest the home pose; draws are sorted by distance from home and cut
// into waves of `wave_size`. A sample starts from the nearest reached sample
// of an earlier wave that its tile sees (grid: the adjacent cells first;
// distances over the sampled components, each divided by its range width),
// or from home when home is nearer or nothing qualifies; ties go to home,
// then to the lower row.
//
// Tiles (what fits a cluster): the grid is cut into tiles of TileSide()
// cells per range; draws are binned into a grid of tiles as if they were a
// grid of round(n^(1/ranges)) points per range (empty bins are no tile). A
// tile's order is its L1 distance, in tiles, from the tile holding home; a
// tile depends on its adjacent tiles (sharing a face, an edge or a corner)
// of a smaller order and starts when they are finished. A tile sees its own
// samples, those of the tiles it depends on, and the samples outside them
// that those started from (their carried samples: a tile behind an
// unreachable region still starts from the last reached samples before it,
// not from home). The adjacent cell toward home along every axis that
// changes is always seen, so starts differ from the global continuation only
// where that cell was not reached. A map of one tile (TileSide() >=
// resolution, or few draws) is the global wave continuation.
//
// Determinism: every solve starts from a restored state and controls (no
// warm-start memory is carried over), and a tile depends only on the options
// and on the samples of the tiles it depends on, so results never depend on
// the thread count, on which thread or worker solved what, or on how tiles
// are grouped into tasks. Threads share the Model read-only and own one
// ControlProblem each (std::thread); each takes whole tiles, the ready ones
// nearest home first.
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
  int wave_size = 64;      // random samples per wave inside a tile, in [1, 100000]
  // Tile side in cells per range, in [0, 10000]; 0: the default for the
  // number of ranges (TileSide()). Part of the map's definition (it
  // changes starts, hence results); never derived from threads or workers.
  int tile_size = 0;
  int threads = 1;         // worker threads, in [1, 256]
  ControlOptions control;  // the continuation's controller (path steps, tolerance)

  static constexpr long long kMaxSamples = 1000000;
  static constexpr int kMaxRandomSamples = 100000;

  // Number of samples these options give (grid product or random_samples).
  long long SampleCount() const;
  // The tile side actually used: tile_size, or min(16, floor(256^(1/ranges)))
  // (16 for 1 or 2 ranges, 6 for 3, 4 for 4, 3 for 5, 2 for 6): about 256
  // cells per tile.
  int TileSide() const;
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
  int wave = 0;                    // wave inside its tile (0: the tile's seed)
  long long start = -1;            // row it started from (-1: home)
  int tile = 0;                    // its tile (WorkspaceTiles order)
  int steps = 0;                   // path steps walked
  std::string warning;             // why it was not reached ("" if reached)
  State state;                     // final configuration (a later sample's start)
};

struct WorkspaceResult {
  std::vector<int> components;           // sampled components, in option order
  std::vector<WorkspaceSample> samples;  // grid order (last range fastest) or draw order
  long long reachable = 0;
  int tiles = 0;                         // number of tiles
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

// One tile of the map: its rows (ascending), its order (L1 distance in
// tiles from the tile holding home) and the tiles it depends on (adjacent,
// of a smaller order; ascending). Tiles are numbered
// in tile-grid order (last range fastest); draws leave out empty bins.
struct WorkspaceTile {
  std::vector<long long> rows;
  int order = 0;
  std::vector<int> depends_on;
};

// The map's tiles; every row is in exactly one. Depends only on the model's
// home pose and the options. Throws std::invalid_argument on bad options.
std::vector<WorkspaceTile> WorkspaceTiles(const Model& model, const WorkspaceOptions& options);

// A finished tile: its samples (its rows' order) and the reached samples
// outside it that its samples started from (ascending rows), which the
// tiles depending on it may start from too.
struct WorkspaceTileResult {
  std::vector<WorkspaceSample> samples;
  std::vector<long long> carried_rows;
  std::vector<WorkspaceSample> carried;
};

// One tile, on the calling thread. `inputs[k]` is the result of this
// function for the tile's depends_on[k] (the state and controls of reached
// samples are read). A pure function of (model, options, tile, inputs), which
// are themselves such functions: what a worker runs for one task. Progress
// counts this tile's samples. Throws std::invalid_argument on bad options, a
// tile out of range, or inputs of the wrong count or size.
WorkspaceTileResult EvaluateWorkspaceTile(const Model& model, const WorkspaceOptions& options, int tile,
                                          const std::vector<WorkspaceTileResult>& inputs,
                                          const WorkspaceProgress& progress = nullptr);

// Where finished tiles are kept between runs (`ccma workspace --store`,
// apps/workspace_store.h): ComputeWorkspace reads a tile back instead of
// computing it when Load() finds it (its samples and carried_rows are
// used), and hands every tile it computes to Save() as it finishes. Both are
// called from the worker threads, each for its own tile.
class WorkspaceTileCache {
 public:
  virtual ~WorkspaceTileCache() = default;
  // True and `out` filled when tile `tile` was kept; false: compute it.
  virtual bool Load(int tile, WorkspaceTileResult* out) = 0;
  virtual void Save(int tile, const WorkspaceTileResult& result) = 0;
};

// The whole map (see the file comment) on options.threads threads, each
// taking whole tiles; with `cache`, kept tiles are read back (a tile read
// back must have its tile's sample count, else it is computed). Throws
// std::invalid_argument if the options are not valid for the model.
WorkspaceResult ComputeWorkspace(const Model& model, const WorkspaceOptions& options,
                                 const WorkspaceProgress& progress = nullptr, WorkspaceTileCache* cache = nullptr);

// An explicit list of poses, each reached independently from its start
// (`starts[i]`, a state and all controls, e.g. a reached sample's; or home
// when `starts` is empty), on options.threads threads; the result depends
// only on the inputs.
std::vector<WorkspaceSample> EvaluateWorkspacePoses(const Model& model, const WorkspaceOptions& options,
                                                    const std::vector<PoseTarget>& poses,
                                                    const std::vector<WorkspaceStart>& starts = {},
                                                    const WorkspaceProgress& progress = nullptr);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_WORKSPACE_H_
