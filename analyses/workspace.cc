#include "analyses/workspace.h"

#include <array>
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "analyses/internal/workspace_tiles.h"
#include "analyses/internal/workspace_waves.h"
#include "ccma/internal/format.h"
#include "ccma/limits.h"

namespace ccma {

using internal::WaveItems;
using internal::WaveSolver;
using internal::WorkspaceTiling;

long long WorkspaceOptions::SampleCount() const {
  if (random_samples > 0) return random_samples;
  long long n = 1;
  for (size_t k = 0; k < ranges.size(); ++k) {
    n *= std::max(resolution, 1);
    if (n > kMaxSamples) return kMaxSamples + 1;  // no overflow: the caller only compares
  }
  return n;
}

int WorkspaceOptions::TileSide() const {
  if (tile_size > 0) return tile_size;
  const int dims = std::max<int>(1, static_cast<int>(ranges.size()));
  auto cells = [dims](int side) {
    long long c = 1;
    for (int d = 0; d < dims; ++d) c *= side;
    return c;
  };
  int side = 1;
  while (side < 16 && cells(side + 1) <= 256) ++side;
  return side;
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
  if (tile_size < 0 || tile_size > 10000) return fail("tile_size must lie in [0, 10000], got " + std::to_string(tile_size));
  if (threads < 1 || threads > 256) return fail("threads must lie in [1, 256], got " + std::to_string(threads));
  std::string control_why;
  if (!control.IsValid(&control_why)) return fail("control." + control_why);
  return true;
}

std::vector<PoseTarget> WorkspacePoses(const Model& model, const WorkspaceOptions& options) {
  internal::CheckWorkspaceOptions(model, options);
  return internal::AllWorkspacePoses(model, options);
}

std::vector<WorkspaceSample> EvaluateWorkspacePoses(const Model& model, const WorkspaceOptions& options,
                                                    const std::vector<PoseTarget>& poses,
                                                    const std::vector<WorkspaceStart>& starts,
                                                    const WorkspaceProgress& progress) {
  internal::CheckWorkspaceOptions(model, options);
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
  internal::ParallelFor(model, options.control, options.threads, n, [&](ControlProblem& control, long long i) {
    const auto k = static_cast<size_t>(i);
    samples[k] = internal::ReachPose(control, starts.empty() ? home : starts[k], poses[k]);
    if (progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress(++done, n);
    }
  });
  return samples;
}

namespace {

// Tile `tile` on `control` from the samples of the tiles it depends on
// (`outside`: row and sample); done(k) after each wave.
std::vector<WorkspaceSample> TileWith(ControlProblem& control, const Model& model, const WorkspaceOptions& options,
                                      const WorkspaceTiling& tiling, int t, const WorkspaceTile& tile,
                                      const std::vector<std::pair<long long, const WorkspaceSample*>>& outside,
                                      const std::function<void(long long)>& done) {
  const WaveItems items = tiling.TileItems(tile, outside);
  std::vector<WorkspaceSample> out(items.rows.size());
  const WaveSolver one = [&control](const std::vector<PoseTarget>& poses, const std::vector<WorkspaceStart>& starts) {
    std::vector<WorkspaceSample> solved;
    for (size_t k = 0; k < poses.size(); ++k) solved.push_back(internal::ReachPose(control, starts[k], poses[k]));
    return solved;
  };
  internal::SolveInWaves(model, options, items, one, done, &out);
  for (WorkspaceSample& s : out) s.tile = t;
  return out;
}

// Hands out tiles whose dependencies are finished, nearest home first (the
// order does not change results, only how soon later tiles become ready).
class TileQueue {
 public:
  explicit TileQueue(const std::vector<WorkspaceTile>& tiles) : tiles_(tiles), waiting_(tiles.size()), users_(tiles.size()) {
    for (size_t t = 0; t < tiles.size(); ++t) {
      waiting_[t] = static_cast<int>(tiles[t].depends_on.size());
      for (int d : tiles[t].depends_on) users_[static_cast<size_t>(d)].push_back(static_cast<int>(t));
      if (waiting_[t] == 0) Push(static_cast<int>(t));
    }
  }
  // The next ready tile, waiting while none is; -1 when all are handed out or after Stop().
  int Next() {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_changed_.wait(lock, [&] { return !ready_.empty() || handed_ == tiles_.size() || stopped_; });
    if (ready_.empty() || stopped_) return -1;
    std::pop_heap(ready_.begin(), ready_.end(), std::greater<>());
    const int t = ready_.back().second;
    ready_.pop_back();
    ++handed_;
    return t;
  }
  void Finished(int t) {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (int u : users_[static_cast<size_t>(t)]) {
      if (--waiting_[static_cast<size_t>(u)] == 0) Push(u);
    }
    ready_changed_.notify_all();
  }
  void Stop() {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
    ready_changed_.notify_all();
  }

 private:
  void Push(int t) {
    ready_.emplace_back(tiles_[static_cast<size_t>(t)].order, t);
    std::push_heap(ready_.begin(), ready_.end(), std::greater<>());
  }
  const std::vector<WorkspaceTile>& tiles_;
  std::vector<int> waiting_;             // unfinished dependencies per tile
  std::vector<std::vector<int>> users_;  // tiles that depend on each tile
  std::vector<std::pair<int, int>> ready_;  // (order, tile), a min-heap
  size_t handed_ = 0;
  bool stopped_ = false;
  std::mutex mutex_;
  std::condition_variable ready_changed_;
};

}  // namespace

std::vector<WorkspaceTile> WorkspaceTiles(const Model& model, const WorkspaceOptions& options) {
  internal::CheckWorkspaceOptions(model, options);
  const WorkspaceTiling tiling(model, options);
  std::vector<WorkspaceTile> tiles;
  for (int t = 0; t < tiling.count(); ++t) tiles.push_back(tiling.Tile(t));
  return tiles;
}

namespace {

// The carried rows of a finished tile: the rows outside it its samples
// started from, ascending.
std::vector<long long> CarriedRows(const WorkspaceTile& tile, const std::vector<WorkspaceSample>& samples) {
  std::vector<long long> rows;
  for (const WorkspaceSample& s : samples) {
    if (s.start >= 0 && !std::binary_search(tile.rows.begin(), tile.rows.end(), s.start)) rows.push_back(s.start);
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  return rows;
}

// Adds (row, sample) unless the row is already there.
void AddOutside(std::map<long long, const WorkspaceSample*>* outside, long long row, const WorkspaceSample* s) {
  outside->emplace(row, s);
}

// Checks one input of EvaluateWorkspaceTile against the tile it stands for.
void CheckInput(const Model& model, const WorkspaceTileResult& input, const WorkspaceTile& other, size_t k) {
  const std::string which = "EvaluateWorkspaceTile: input " + std::to_string(k);
  if (input.samples.size() != other.rows.size() || input.carried.size() != input.carried_rows.size()) {
    throw std::invalid_argument(which + " has " + std::to_string(input.samples.size()) + " samples for " +
                                std::to_string(other.rows.size()) + " rows, or carried samples without rows");
  }
  auto of_model = [&](const WorkspaceSample& s) {
    return !s.reachable || (s.state.num_bodies() == model.num_bodies() && s.controls.size() == model.num_controls());
  };
  const bool ok = std::all_of(input.samples.begin(), input.samples.end(), of_model) &&
                  std::all_of(input.carried.begin(), input.carried.end(), of_model);
  if (!ok) throw std::invalid_argument(which + " is not of model '" + model.name + "'");
}

}  // namespace

WorkspaceTileResult EvaluateWorkspaceTile(const Model& model, const WorkspaceOptions& options, int tile,
                                          const std::vector<WorkspaceTileResult>& inputs,
                                          const WorkspaceProgress& progress) {
  internal::CheckWorkspaceOptions(model, options);
  const WorkspaceTiling tiling(model, options);
  if (tile < 0 || tile >= tiling.count()) {
    throw std::invalid_argument("EvaluateWorkspaceTile: tile " + std::to_string(tile) + " is not in [0, " +
                                std::to_string(tiling.count()) + ")");
  }
  const WorkspaceTile t = tiling.Tile(tile);
  if (inputs.size() != t.depends_on.size()) {
    throw std::invalid_argument("EvaluateWorkspaceTile: tile " + std::to_string(tile) + " depends on " +
                                std::to_string(t.depends_on.size()) + " tiles, got " + std::to_string(inputs.size()) +
                                " inputs");
  }
  std::map<long long, const WorkspaceSample*> outside;
  for (size_t k = 0; k < inputs.size(); ++k) {
    const WorkspaceTile other = tiling.Tile(t.depends_on[k]);
    CheckInput(model, inputs[k], other, k);
    for (size_t i = 0; i < other.rows.size(); ++i) AddOutside(&outside, other.rows[i], &inputs[k].samples[i]);
    for (size_t i = 0; i < inputs[k].carried.size(); ++i) {
      AddOutside(&outside, inputs[k].carried_rows[i], &inputs[k].carried[i]);
    }
  }
  ControlProblem control(model, options.control);
  long long done = 0;
  WorkspaceTileResult result;
  result.samples = TileWith(control, model, options, tiling, tile, t, {outside.begin(), outside.end()}, [&](long long k) {
    done += k;
    if (progress) progress(done, static_cast<long long>(t.rows.size()));
  });
  result.carried_rows = CarriedRows(t, result.samples);
  for (long long row : result.carried_rows) result.carried.push_back(*outside.at(row));
  return result;
}

namespace {

// A tile read back from `cache` into the map: false when it is not kept or
// does not fit the tile (then it is computed).
bool LoadTile(WorkspaceTileCache* cache, int t, const WorkspaceTile& tile, std::vector<WorkspaceSample>* samples,
              std::vector<long long>* carried) {
  WorkspaceTileResult kept;
  if (cache == nullptr || !cache->Load(t, &kept) || kept.samples.size() != tile.rows.size()) return false;
  for (long long row : kept.carried_rows) {
    if (row < 0 || row >= static_cast<long long>(samples->size())) return false;
  }
  for (size_t k = 0; k < tile.rows.size(); ++k) (*samples)[static_cast<size_t>(tile.rows[k])] = std::move(kept.samples[k]);
  *carried = std::move(kept.carried_rows);
  return true;
}

// A computed tile handed to `cache`: its samples and the carried ones.
void SaveTile(WorkspaceTileCache* cache, int t, const std::vector<WorkspaceSample>& samples,
              const std::vector<long long>& carried_rows, const std::vector<WorkspaceSample>& map) {
  if (cache == nullptr) return;
  WorkspaceTileResult result{samples, carried_rows, {}};
  for (long long row : carried_rows) result.carried.push_back(map[static_cast<size_t>(row)]);
  cache->Save(t, result);
}

}  // namespace

WorkspaceResult ComputeWorkspace(const Model& model, const WorkspaceOptions& options,
                                 const WorkspaceProgress& progress, WorkspaceTileCache* cache) {
  const auto clock_start = std::chrono::steady_clock::now();
  internal::CheckWorkspaceOptions(model, options);
  const WorkspaceTiling tiling(model, options);
  std::vector<WorkspaceTile> tiles;
  for (int t = 0; t < tiling.count(); ++t) tiles.push_back(tiling.Tile(t));
  WorkspaceResult result;
  for (const WorkspaceRange& r : options.ranges) result.components.push_back(r.component);
  result.samples.resize(static_cast<size_t>(tiling.samples()));
  result.tiles = tiling.count();
  std::mutex progress_mutex;
  long long done = 0;
  const auto report = [&](long long k) {
    const std::lock_guard<std::mutex> lock(progress_mutex);
    done += k;
    if (progress) progress(done, tiling.samples());
  };
  std::vector<std::vector<long long>> carried(tiles.size());  // per finished tile
  TileQueue queue(tiles);
  const int threads = std::min(options.threads, std::max(1, tiling.count()));
  internal::ParallelFor(model, options.control, threads, threads, [&](ControlProblem& control, long long) {
    try {
      for (int t = queue.Next(); t >= 0; t = queue.Next()) {
        const WorkspaceTile& tile = tiles[static_cast<size_t>(t)];
        if (LoadTile(cache, t, tile, &result.samples, &carried[static_cast<size_t>(t)])) {
          report(static_cast<long long>(tile.rows.size()));
          queue.Finished(t);
          continue;
        }
        std::map<long long, const WorkspaceSample*> outside;  // finished: no longer written
        for (int d : tile.depends_on) {
          for (long long row : tiles[static_cast<size_t>(d)].rows) AddOutside(&outside, row, &result.samples[static_cast<size_t>(row)]);
          for (long long row : carried[static_cast<size_t>(d)]) AddOutside(&outside, row, &result.samples[static_cast<size_t>(row)]);
        }
        std::vector<WorkspaceSample> samples =
            TileWith(control, model, options, tiling, t, tile, {outside.begin(), outside.end()}, report);
        carried[static_cast<size_t>(t)] = CarriedRows(tile, samples);
        SaveTile(cache, t, samples, carried[static_cast<size_t>(t)], result.samples);
        for (size_t k = 0; k < tile.rows.size(); ++k) result.samples[static_cast<size_t>(tile.rows[k])] = std::move(samples[k]);
        queue.Finished(t);
      }
    } catch (...) {
      queue.Stop();  // the other threads stop waiting for tiles that will never be ready
      throw;
    }
  });
  for (const WorkspaceSample& s : result.samples) result.reachable += s.reachable;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace ccma
