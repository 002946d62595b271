// `ccma workspace --model=FILE --out=FILE.csv [--x=lo:hi ...] [--resolution=N | --samples=N --seed=S]
//                 [--threads=N] [--tile_size=N] [--plot=DIR]`:
// reachability map over the controlled components (analyses/workspace.h);
// one CSV row per sample, optional gnuplot slice maps, JSON summary on stdout.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/interrupt_watch.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "apps/plots.h"
#include "apps/work_bound.h"
#include "apps/workspace_store.h"
#include "formats/model_loader.h"
#include "ccma/internal/format.h"
#include "documents/table.h"
#include "documents/workspace_table.h"

DEFINE_string(x, "", "workspace: sample x over lo:hi [m] (e.g. -0.2:0.2)");
DEFINE_string(y, "", "workspace: sample y over lo:hi [m]");
DEFINE_string(z, "", "workspace: sample z over lo:hi [m]");
DEFINE_string(roll, "", "workspace: sample roll over lo:hi [rad]");
DEFINE_string(pitch, "", "workspace: sample pitch over lo:hi [rad]");
DEFINE_string(yaw, "", "workspace: sample yaw over lo:hi [rad]");
DEFINE_int32(resolution, 11, "workspace grid: points per sampled range, ends included, 1..10000 [points]");
DEFINE_int32(samples, 0, "workspace: seeded uniform samples instead of the grid, 1..100000 (default: the grid) [samples]");
DEFINE_int32(threads, 1, "worker threads, 1..256 (the results do not depend on it) [threads]");
DEFINE_int32(tile_size, 0,
             "workspace: tile side, 0..10000, 0 = 16 for one or two ranges, 6 for three, 4, 3, 2 for four, five, six "
             "(part of the map: it decides where samples start) [cells per range]");
DEFINE_string(plot, "", "workspace: folder for reachability and sigma_min maps over the first two ranges (gnuplot) [path]");
DEFINE_string(store, "",
              "workspace: folder that keeps every finished tile; the same command run again resumes from it "
              "(docs/workspace.md) [path]");

namespace ccma::cli {
namespace {

// "lo:hi" -> range; throws UsageError naming the flag.
WorkspaceRange ParseRange(const std::string& text, int component) {
  const std::string flag = kEndEffectorComponentNames[static_cast<size_t>(component)];
  const size_t colon = text.find(':');
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos) {
    throw UsageError("--" + flag + ": expected lo:hi (two numbers and one colon), got " + Quote(text));
  }
  auto number = [&](const std::string& part) {
    const Eigen::VectorXd v = ParseNumberList(part, flag);
    if (v.size() != 1) throw UsageError("--" + flag + ": expected lo:hi, got " + Quote(text));
    return v[0];
  };
  WorkspaceRange range{component, number(text.substr(0, colon)), number(text.substr(colon + 1))};
  if (!(std::abs(range.lo) <= kMaxMagnitude && std::abs(range.hi) <= kMaxMagnitude)) {
    throw UsageError("--" + flag + ": bounds must be finite numbers in [-" + FormatG(kMaxMagnitude) + ", " +
                     FormatG(kMaxMagnitude) + "]");
  }
  if (!(range.lo <= range.hi)) throw UsageError("--" + flag + ": needs lo <= hi, got " + Quote(text));
  return range;
}

const std::string* RangeFlag(int component) {
  static const std::string* const flags[6] = {&FLAGS_x, &FLAGS_y, &FLAGS_z, &FLAGS_roll, &FLAGS_pitch, &FLAGS_yaw};
  return flags[component];
}

// What a row's computed columns take at home [s] (part of the run's
// estimate), checked once before the long run: a compliant model's
// stiffness column must be within the statics' bound (kMaxStaticsEntries).
double CheckedRowSeconds(const Model& model) {
  try {
    return documents::WorkspaceRowSeconds(model);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("ccma workspace: stiffness_min_N_per_m: ") + e.what());
  }
}

// The map as its CSV; `estimate` told of every row's computed columns.
void WriteCsv(const Model& model, const WorkspaceResult& result, std::ostream& csv, WorkEstimate* estimate) {
  const documents::WorkspaceComputedColumns computed =
      documents::ComputeWorkspaceColumns(model, result.samples, [estimate](long long row) { estimate->Update(row); });
  documents::WriteCsv(documents::WorkspaceTable(model, result.samples, computed), csv);
}

// The sampling options from the flags, checked against the model.
WorkspaceOptions OptionsFromFlags(const Model& model) {
  WorkspaceOptions options;
  for (int c = 0; c < 6; ++c) {
    const std::string& text = *RangeFlag(c);
    if (text.empty()) continue;
    if (!model.end_effector.controlled[static_cast<size_t>(c)]) {
      throw UsageError(std::string("--") + kEndEffectorComponentNames[static_cast<size_t>(c)] + ": model '" +
                       model.name + "' does not control " + kEndEffectorComponentNames[static_cast<size_t>(c)]);
    }
    options.ranges.push_back(ParseRange(text, c));
  }
  if (options.ranges.empty()) {
    throw UsageError("ccma workspace: give at least one range, e.g. --z=0.3:0.9 (flags --x --y --z --roll --pitch --yaw)");
  }
  if (FLAGS_resolution < 1 || FLAGS_resolution > 10000) {
    throw UsageError("--resolution: must lie in [1, 10000], got " + std::to_string(FLAGS_resolution));
  }
  if (FLAGS_samples < 0 || FLAGS_samples > WorkspaceOptions::kMaxRandomSamples) {
    throw UsageError("--samples: must lie in [1, " + std::to_string(WorkspaceOptions::kMaxRandomSamples) + "], got " +
                     std::to_string(FLAGS_samples));
  }
  if (FLAGS_seed < 0) throw UsageError("--seed: must be >= 0, got " + std::to_string(FLAGS_seed));
  if (FLAGS_threads < 1 || FLAGS_threads > 256) {
    throw UsageError("--threads: must lie in [1, 256], got " + std::to_string(FLAGS_threads));
  }
  if (FLAGS_tile_size < 0 || FLAGS_tile_size > 10000) {
    throw UsageError("--tile_size: must lie in [0, 10000], got " + std::to_string(FLAGS_tile_size));
  }
  options.resolution = FLAGS_resolution;
  options.random_samples = FLAGS_samples;
  options.seed = static_cast<std::uint64_t>(FLAGS_seed);
  options.threads = FLAGS_threads;
  options.tile_size = FLAGS_tile_size;
  options.control = ControlOptionsFromFlags();
  std::string why;
  if (!options.IsValid(model, &why)) throw UsageError("ccma workspace: " + why);
  return options;
}

// A percentage bar on stderr, only for a person watching (a terminal), and
// the samples done told to `estimate` (which may end the run: WorkBoundError).
WorkspaceProgress TerminalProgress(WorkEstimate* estimate) {
  const bool show = isatty(STDERR_FILENO) != 0;
  return [show, estimate, last_percent = -1](long long done, long long total) mutable {
    estimate->Update(done);
    if (!show) return;
    const int percent = static_cast<int>(100 * done / std::max<long long>(total, 1));
    if (percent == last_percent) return;
    last_percent = percent;
    const int bar = percent / 4;
    std::cerr << "\r[" << std::string(static_cast<size_t>(bar), '#') << std::string(static_cast<size_t>(25 - bar), ' ')
              << "] " << percent << "% (" << done << "/" << total << ")" << (done == total ? "\n" : "") << std::flush;
  };
}

// What names a map in a store: the model file's text and every option
// that changes a sample (threads, --out and --plot do not).
std::string StoreKey(const std::string& model_path, const WorkspaceOptions& options) {
  std::string text, error;
  if (!internal::ReadRegularFile(model_path, kMaxModelFileBytes, "model file", &text, &error)) throw ModelError(error);
  nlohmann::json key = {{"resolution", options.resolution}, {"samples", options.random_samples},
                        {"seed", options.seed}, {"tile_size", options.TileSide()}, {"wave_size", options.wave_size}};
  for (const WorkspaceRange& r : options.ranges) key["ranges"].push_back({r.component, r.lo, r.hi});
  for (const char* flag : {"method", "max_step_m", "max_step_rad", "lambda", "obstacles"}) {
    std::string value;
    gflags::GetCommandLineOption(flag, &value);
    key[flag] = value;
  }
  std::string obstacles;
  if (!FLAGS_obstacles.empty() &&
      !internal::ReadRegularFile(FLAGS_obstacles, kMaxModelFileBytes, "obstacles file", &obstacles, &error)) {
    throw UsageError(error);
  }
  return text + "\n" + obstacles + "\n" + key.dump();
}

nlohmann::json SummaryJson(const Model& model, const WorkspaceOptions& options, const WorkspaceResult& result,
                           const std::string& out_path) {
  nlohmann::json out;
  out["model"] = model.name;
  out["out"] = out_path;
  out["samples"] = result.samples.size();
  out["reachable"] = result.reachable;
  out["seconds"] = result.seconds;
  out["threads"] = options.threads;
  out["tiles"] = result.tiles;
  out["tile_size"] = options.TileSide();
  out["mode"] = options.random_samples > 0 ? "random" : "grid";
  nlohmann::json components = nlohmann::json::array();
  for (int c : result.components) components.push_back(kEndEffectorComponentNames[static_cast<size_t>(c)]);
  out["components"] = components;
  return out;
}

// The map; with a store, Ctrl-C (or SIGTERM) first says on stderr what the
// store keeps and how to resume, then ends the run as the signal would.
WorkspaceResult ComputeWithStore(const Model& model, const WorkspaceOptions& options, WorkspaceStore* store,
                                 WorkEstimate* estimate) {
  if (store == nullptr) return ComputeWorkspace(model, options, TerminalProgress(estimate), nullptr);
  const InterruptWatch watch([store](int signal_number) {
    const int kept = store->Freeze();
    std::cerr << (isatty(STDERR_FILENO) != 0 ? "\n" : "") << "ccma workspace: "
              << (signal_number == SIGINT ? "interrupted" : "terminated") << ": " << kept << " of " << store->tiles()
              << " tiles of the map are finished and kept in the store " << Quote(FLAGS_store)
              << "; the same command again resumes from them:\n  " << CommandLineForShell() << std::endl;
  });
  return ComputeWorkspace(model, options, TerminalProgress(estimate), store);
}

}  // namespace

int RunWorkspace(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "workspace");
  const std::string model_path = RequireFlag(FLAGS_model, "model", "workspace");
  const std::string out_path = RequireFlag(FLAGS_out, "out", "workspace");
  const Model model = LoadModelOrThrow(model_path);
  const WorkspaceOptions options = OptionsFromFlags(model);
  // Work bounded by its cost (--max_minutes): the samples timed as they are
  // solved, the CSV's computed columns once at home.
  const long long n = options.SampleCount();
  WorkEstimate estimate(CommandWorkEstimate("workspace", "samples", true), n);
  estimate.AddLaterSeconds(CheckedRowSeconds(model) * static_cast<double>(n), "the CSV's computed columns");
  if (!FLAGS_plot.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(FLAGS_plot, ec);
    if (!std::filesystem::is_directory(FLAGS_plot)) throw UsageError("--plot: cannot create folder '" + FLAGS_plot + "'");
  }
  OutputFile file(out_path, "out");  // checked before the long run
  std::unique_ptr<WorkspaceStore> store;
  if (!FLAGS_store.empty()) {
    store = std::make_unique<WorkspaceStore>(FLAGS_store, model, StoreKey(model_path, options),
                                             WorkspaceTiles(model, options));
  }
  const WorkspaceResult result = ComputeWithStore(model, options, store.get(), &estimate);
  estimate.BeginStage("rows of the CSV", n, 0, false);
  WriteCsv(model, result, file.stream(), &estimate);
  file.Commit();

  nlohmann::json out = SummaryJson(model, options, result, out_path);
  if (store) out["tiles_from_store"] = store->loaded();
  if (!FLAGS_plot.empty()) {
    std::string warning;
    out["plots"] = PlotWorkspaceMaps(model, options, result, FLAGS_plot, &warning);
    if (!warning.empty()) {
      out["plot_warning"] = warning;
      std::cerr << "ccma workspace: warning: " << warning << "\n";
    }
  }
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
