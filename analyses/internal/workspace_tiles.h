// Internal to analyses/workspace*.cc: the map's tiles (analyses/workspace.h,
// file comment) and the wave items of one tile.
//
// Grid: tiles of TileSide() cells per range, numbered over the tile grid
// (ceil(resolution / side) tiles per range, last range fastest). A tile is
// computed in O(its cells), so a worker evaluating one tile of a
// million-sample grid never builds the whole map. Draws: binned over a grid
// of ceil(round(n^(1/ranges)) / side) bins per range; bins holding no draw
// are left out; built in O(n) (n <= 100,000).
#ifndef CCMA_ANALYSES_INTERNAL_WORKSPACE_TILES_H_
#define CCMA_ANALYSES_INTERNAL_WORKSPACE_TILES_H_

#include <utility>
#include <vector>

#include "analyses/internal/workspace_waves.h"
#include "analyses/workspace.h"

namespace ccma::internal {

class WorkspaceTiling {
 public:
  // `options` must be valid for `model` (CheckWorkspaceOptions); copied.
  WorkspaceTiling(const Model& model, const WorkspaceOptions& options);

  int count() const { return count_; }
  long long samples() const { return samples_; }
  const PoseTarget& home_pose() const { return home_; }
  // Tile t in [0, count()): rows, order, depends_on.
  WorkspaceTile Tile(int t) const;
  // Tile t without its rows (grid: O(3^ranges)).
  WorkspaceTile Header(int t) const;
  // The pose of a map row in [0, samples()).
  PoseTarget Pose(long long row) const;
  // The global wave of a row: grid, its Chebyshev distance in cells from
  // the cell nearest home; draws, its rank by distance from home over
  // wave_size.
  int Wave(long long row) const;
  // A tile's rows as wave items, with the samples it may also start from
  // (`outside`: row and sample; grid: adjacent cells, inside the tile or
  // outside, first).
  WaveItems TileItems(const WorkspaceTile& tile,
                      const std::vector<std::pair<long long, const WorkspaceSample*>>& outside) const;

 private:
  std::vector<int> GridCell(long long row) const;
  long long GridRow(const std::vector<int>& cell) const;
  void BinDraws();

  WorkspaceOptions options_;
  PoseTarget home_;
  int dims_ = 0;
  int side_ = 1;
  int per_range_ = 1;  // tiles (grid) or bins (draws) per range
  int count_ = 0;
  long long samples_ = 0;
  std::vector<int> home_cell_;    // grid: the cell nearest home; draws: home's bin
  std::vector<PoseTarget> draws_;              // draws only
  std::vector<int> draw_waves_;                // draws only: global wave per draw
  std::vector<WorkspaceTile> draw_tiles_;      // draws only
};

// The sample poses of valid options, in output order.
std::vector<PoseTarget> AllWorkspacePoses(const Model& model, const WorkspaceOptions& options);

}  // namespace ccma::internal

#endif  // CCMA_ANALYSES_INTERNAL_WORKSPACE_TILES_H_
