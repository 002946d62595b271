#include "analyses/internal/workspace_tiles.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <unordered_map>

namespace ccma::internal {
namespace {

// Grid index k of range r [m or rad].
double GridValue(const WorkspaceOptions& options, const WorkspaceRange& r, int k) {
  return options.resolution == 1 ? 0.5 * (r.lo + r.hi)
                                 : r.lo + (r.hi - r.lo) * k / static_cast<double>(options.resolution - 1);
}

// The grid index of range r nearest `home` (ties to the lower index).
int NearestIndex(const WorkspaceOptions& options, const WorkspaceRange& r, double home) {
  int best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int k = 0; k < options.resolution; ++k) {
    const double d = std::abs(GridValue(options, r, k) - home);
    if (d < best_distance) best_distance = d, best = k;
  }
  return best;
}

// Multi-index of i with `per` values per digit, the last digit fastest; and back.
std::vector<int> Digits(long long i, int dims, int per) {
  std::vector<int> digits(static_cast<size_t>(dims));
  for (int d = dims - 1; d >= 0; --d) {
    digits[static_cast<size_t>(d)] = static_cast<int>(i % per);
    i /= per;
  }
  return digits;
}

long long FromDigits(const std::vector<int>& digits, int per) {
  long long i = 0;
  for (int c : digits) i = i * per + c;
  return i;
}

int Chebyshev(const std::vector<int>& a, const std::vector<int>& b) {
  int w = 0;
  for (size_t d = 0; d < a.size(); ++d) w = std::max(w, std::abs(a[d] - b[d]));
  return w;
}

// A tile's order: its L1 distance in tiles from the tile holding home.
int L1(const std::vector<int>& a, const std::vector<int>& b) {
  int w = 0;
  for (size_t d = 0; d < a.size(); ++d) w += std::abs(a[d] - b[d]);
  return w;
}

// Calls f(c') for every c' adjacent to c (3^dims - 1 offsets: faces, edges,
// corners) with lo <= c' <= hi per digit.
void ForEachAdjacent(const std::vector<int>& c, const std::vector<int>& lo, const std::vector<int>& hi,
                     const std::function<void(const std::vector<int>&)>& f) {
  long long offsets = 1;
  for (size_t d = 0; d < c.size(); ++d) offsets *= 3;
  for (long long o = 0; o < offsets; ++o) {
    std::vector<int> a = c;
    long long rest = o;
    bool inside = true, moved = false;
    for (size_t d = 0; d < c.size(); ++d) {
      const int step = static_cast<int>(rest % 3) - 1;
      rest /= 3;
      a[d] += step;
      moved = moved || step != 0;
      inside = inside && a[d] >= lo[d] && a[d] <= hi[d];
    }
    if (inside && moved) f(a);
  }
}

std::vector<PoseTarget> Draws(const WorkspaceOptions& options, const PoseTarget& home) {
  std::vector<PoseTarget> poses(static_cast<size_t>(options.random_samples), home);
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (PoseTarget& pose : poses) {
    for (const WorkspaceRange& r : options.ranges) PoseComponent(pose, r.component) = r.lo + (r.hi - r.lo) * unit(rng);
  }
  return poses;
}

}  // namespace

WorkspaceTiling::WorkspaceTiling(const Model& model, const WorkspaceOptions& options)
    : options_(options),
      home_(WorkspaceHomePose(model)),
      dims_(static_cast<int>(options.ranges.size())),
      side_(options.TileSide()),
      samples_(options.SampleCount()) {
  if (options_.random_samples > 0) {
    BinDraws();
    return;
  }
  per_range_ = (options_.resolution + side_ - 1) / side_;
  long long count = 1;
  for (int d = 0; d < dims_; ++d) count *= per_range_;
  count_ = static_cast<int>(count);  // <= samples <= 1e6
  for (const WorkspaceRange& r : options_.ranges) {
    home_cell_.push_back(NearestIndex(options_, r, PoseComponent(home_, r.component)));
  }
}

// Draws binned as if they were a grid of round(n^(1/ranges)) points per range.
void WorkspaceTiling::BinDraws() {
  draws_ = Draws(options_, home_);
  const long long n = static_cast<long long>(draws_.size());
  // The global waves: draws sorted by distance from home, wave_size per wave.
  std::vector<long long> by_distance(static_cast<size_t>(n));
  std::iota(by_distance.begin(), by_distance.end(), 0LL);
  std::vector<double> d2(static_cast<size_t>(n));
  for (long long i = 0; i < n; ++i) d2[static_cast<size_t>(i)] = WorkspaceDistance2(options_, draws_[static_cast<size_t>(i)], home_);
  std::stable_sort(by_distance.begin(), by_distance.end(),
                   [&](long long a, long long b) { return d2[static_cast<size_t>(a)] < d2[static_cast<size_t>(b)]; });
  draw_waves_.resize(static_cast<size_t>(n));
  for (long long k = 0; k < n; ++k) draw_waves_[static_cast<size_t>(by_distance[static_cast<size_t>(k)])] = static_cast<int>(k / options_.wave_size);
  const long long points = std::max(1LL, std::llround(std::pow(static_cast<double>(n), 1.0 / dims_)));
  per_range_ = static_cast<int>((points + side_ - 1) / side_);
  auto bin_of = [&](const PoseTarget& pose) {
    std::vector<int> bin(static_cast<size_t>(dims_), 0);
    for (int d = 0; d < dims_; ++d) {
      const WorkspaceRange& r = options_.ranges[static_cast<size_t>(d)];
      if (!(r.hi > r.lo)) continue;
      const double k = std::floor((PoseComponent(pose, r.component) - r.lo) / (r.hi - r.lo) * per_range_);
      bin[static_cast<size_t>(d)] = static_cast<int>(std::clamp(k, 0.0, per_range_ - 1.0));
    }
    return bin;
  };
  home_cell_ = bin_of(home_);
  long long bins = 1;
  for (int d = 0; d < dims_; ++d) bins *= per_range_;
  std::vector<long long> bin_of_row(static_cast<size_t>(n));
  std::vector<int> tile_of_bin(static_cast<size_t>(bins), -1);
  for (long long i = 0; i < n; ++i) {
    bin_of_row[static_cast<size_t>(i)] = FromDigits(bin_of(draws_[static_cast<size_t>(i)]), per_range_);
    tile_of_bin[static_cast<size_t>(bin_of_row[static_cast<size_t>(i)])] = 0;
  }
  std::vector<long long> bin_of_tile;
  for (long long b = 0; b < bins; ++b) {
    if (tile_of_bin[static_cast<size_t>(b)] < 0) continue;
    tile_of_bin[static_cast<size_t>(b)] = static_cast<int>(bin_of_tile.size());
    bin_of_tile.push_back(b);
  }
  count_ = static_cast<int>(bin_of_tile.size());
  draw_tiles_.assign(static_cast<size_t>(count_), WorkspaceTile{});
  for (long long i = 0; i < n; ++i) {
    draw_tiles_[static_cast<size_t>(tile_of_bin[static_cast<size_t>(bin_of_row[static_cast<size_t>(i)])])].rows.push_back(i);
  }
  const std::vector<int> lo(static_cast<size_t>(dims_), 0), hi(static_cast<size_t>(dims_), per_range_ - 1);
  for (int t = 0; t < count_; ++t) {
    WorkspaceTile& tile = draw_tiles_[static_cast<size_t>(t)];
    const std::vector<int> bin = Digits(bin_of_tile[static_cast<size_t>(t)], dims_, per_range_);
    tile.order = L1(bin, home_cell_);
    ForEachAdjacent(bin, lo, hi, [&](const std::vector<int>& a) {
      const int other = tile_of_bin[static_cast<size_t>(FromDigits(a, per_range_))];
      if (other >= 0 && L1(a, home_cell_) < tile.order) tile.depends_on.push_back(other);
    });
    std::sort(tile.depends_on.begin(), tile.depends_on.end());
  }
}

std::vector<int> WorkspaceTiling::GridCell(long long row) const { return Digits(row, dims_, options_.resolution); }

long long WorkspaceTiling::GridRow(const std::vector<int>& cell) const { return FromDigits(cell, options_.resolution); }

WorkspaceTile WorkspaceTiling::Header(int t) const {
  if (!draws_.empty()) {
    WorkspaceTile tile = draw_tiles_[static_cast<size_t>(t)];
    tile.rows.clear();
    return tile;
  }
  WorkspaceTile tile;
  const std::vector<int> at = Digits(t, dims_, per_range_);
  std::vector<int> home_tile(static_cast<size_t>(dims_));
  for (size_t d = 0; d < at.size(); ++d) home_tile[d] = home_cell_[d] / side_;
  tile.order = L1(at, home_tile);
  const std::vector<int> lo(static_cast<size_t>(dims_), 0), hi(static_cast<size_t>(dims_), per_range_ - 1);
  ForEachAdjacent(at, lo, hi, [&](const std::vector<int>& a) {
    if (L1(a, home_tile) < tile.order) tile.depends_on.push_back(static_cast<int>(FromDigits(a, per_range_)));
  });
  std::sort(tile.depends_on.begin(), tile.depends_on.end());
  return tile;
}

WorkspaceTile WorkspaceTiling::Tile(int t) const {
  if (!draws_.empty()) return draw_tiles_[static_cast<size_t>(t)];
  WorkspaceTile tile = Header(t);
  const std::vector<int> at = Digits(t, dims_, per_range_);
  std::vector<int> lo(static_cast<size_t>(dims_)), hi(static_cast<size_t>(dims_));
  for (size_t d = 0; d < at.size(); ++d) {
    lo[d] = at[d] * side_;
    hi[d] = std::min(lo[d] + side_, options_.resolution) - 1;
  }
  std::vector<int> cell = lo;
  for (;;) {  // the box's cells in row order (last range fastest): ascending rows
    tile.rows.push_back(GridRow(cell));
    int d = dims_ - 1;
    while (d >= 0 && cell[static_cast<size_t>(d)] == hi[static_cast<size_t>(d)]) {
      cell[static_cast<size_t>(d)] = lo[static_cast<size_t>(d)];
      --d;
    }
    if (d < 0) break;
    ++cell[static_cast<size_t>(d)];
  }
  return tile;
}

PoseTarget WorkspaceTiling::Pose(long long row) const {
  if (!draws_.empty()) return draws_[static_cast<size_t>(row)];
  PoseTarget pose = home_;
  const std::vector<int> cell = GridCell(row);
  for (int d = 0; d < dims_; ++d) {
    const WorkspaceRange& r = options_.ranges[static_cast<size_t>(d)];
    PoseComponent(pose, r.component) = GridValue(options_, r, cell[static_cast<size_t>(d)]);
  }
  return pose;
}

int WorkspaceTiling::Wave(long long row) const {
  if (!draws_.empty()) return draw_waves_[static_cast<size_t>(row)];
  return Chebyshev(GridCell(row), home_cell_);
}

WaveItems WorkspaceTiling::TileItems(const WorkspaceTile& tile,
                                     const std::vector<std::pair<long long, const WorkspaceSample*>>& outside) const {
  WaveItems items;
  const size_t n = tile.rows.size();
  items.rows = tile.rows;
  for (long long row : tile.rows) {
    items.poses.push_back(Pose(row));
    items.wave.push_back(Wave(row));
  }
  for (const auto& [row, sample] : outside) items.outside.push_back({row, Pose(row), Wave(row), sample});
  if (!draws_.empty()) return items;
  // Grid: adjacent cells inside the tile's box, or outside it in a tile it
  // depends on (or carried by one).
  std::unordered_map<long long, int> outside_index;
  for (size_t k = 0; k < outside.size(); ++k) outside_index[outside[k].first] = static_cast<int>(n + k);
  const std::vector<int> lo = GridCell(tile.rows.front()), hi = GridCell(tile.rows.back());
  const std::vector<int> grid_lo(static_cast<size_t>(dims_), 0), grid_hi(static_cast<size_t>(dims_), options_.resolution - 1);
  items.adjacent.resize(n);
  for (size_t i = 0; i < n; ++i) {
    ForEachAdjacent(GridCell(tile.rows[i]), grid_lo, grid_hi, [&](const std::vector<int>& a) {
      bool inside = true;
      long long local = 0;  // index in the box, row order
      for (size_t d = 0; d < a.size(); ++d) {
        inside = inside && a[d] >= lo[d] && a[d] <= hi[d];
        local = local * (hi[d] - lo[d] + 1) + (a[d] - lo[d]);
      }
      if (inside) {
        items.adjacent[i].push_back(static_cast<int>(local));
      } else if (const auto it = outside_index.find(GridRow(a)); it != outside_index.end()) {
        items.adjacent[i].push_back(it->second);
      }
    });
  }
  return items;
}

std::vector<PoseTarget> AllWorkspacePoses(const Model& model, const WorkspaceOptions& options) {
  if (options.random_samples > 0) return Draws(options, WorkspaceHomePose(model));
  const WorkspaceTiling tiling(model, options);
  std::vector<PoseTarget> poses(static_cast<size_t>(tiling.samples()));
  for (long long i = 0; i < tiling.samples(); ++i) poses[static_cast<size_t>(i)] = tiling.Pose(i);
  return poses;
}

}  // namespace ccma::internal
