// `ccma replay --model=FILE --waypoints=FILE.csv --out=DIR [--noise=default|none]
//  [--seed=1] [--mocap_noise_m] [--mocap_noise_rad] [--latency_s] [--slip]`:
// the paper's closed loop, simulated (execution/replay.h). Writes
// DIR/end_effector.csv, DIR/bases.csv, DIR/rmse.md and, with gnuplot,
// DIR/end_effector.{png,svg} and DIR/bases_xy.{png,svg} (apps/plots.h).
// A replay that failed (plan not converged, chain torn) says so on stderr,
// in rmse.md, in the plots and in the JSON.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/work_bound.h"
#include "ccma/internal/format.h"
#include "apps/flags.h"
#include "apps/commands.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "apps/plots.h"
#include "documents/replay_document.h"
#include "documents/replay_report.h"

DEFINE_string(noise, "default",
              "simulated imperfections: 'default' (the documented ones, docs/cli.md) or 'none' [default|none]");
DEFINE_double(mocap_noise_m, -1,
              "motion-capture noise sigma on x and y, overrides --noise (default noise: 0.001) [m]");
DEFINE_double(mocap_noise_rad, -1,
              "motion-capture noise sigma on the heading, overrides --noise (default noise: 0.003) [rad]");
DEFINE_double(latency_s, -1,
              "motion-capture and radio latency, 0..10, overrides --noise (default noise: 0.01 and 0.02) [s]");
DEFINE_double(slip, -1,
              "mean wheel slip, fraction of wheel speed lost, 0 <= slip < 1, overrides --noise (default noise: 0.03) [1]");
DEFINE_double(kp, 4.0, "PI proportional gain, position and heading [1/s]");
DEFINE_double(ki, 4.0, "PI integral gain, position and heading [1/s^2]");
DEFINE_double(controller_hz, 100.0, "PI controller rate, 1..10000 [Hz]");
DEFINE_double(max_wheel_speed, 30.0, "wheel-speed saturation [rad/s]");
DEFINE_double(gait_hz, 2.0,
              "legged bases: trotting gait frequency, (0, 100] and at most a quarter of --controller_hz (the gait is "
              "evaluated at every controller tick) [Hz]");
DEFINE_double(gait_bob_m, 0.01, "legged bases: amplitude of the body's bob while walking, [0, 1] [m]");
DEFINE_double(gait_sway_rad, 0.02, "legged bases: amplitude of the body's sway (roll) while walking, [0, 0.5] [rad]");

namespace ccma::cli {
namespace {

// Whether a flag was given on the command line (the replay flags' -1 means "not given").
bool Given(const char* flag) { return !gflags::GetCommandLineFlagInfoOrDie(flag).is_default; }

// The options the flags ask for, checked by ReplayOptions::IsValid (UsageError).
ReplayOptions ReplayOptionsFromFlags() {
  ReplayOptions options;
  options.control = ControlOptionsFromFlags();
  if (FLAGS_noise == "none") {
    options.noise = SimulationNoise::None();
  } else if (FLAGS_noise != "default") {
    throw UsageError("ccma replay: --noise must be 'default' or 'none'");
  }
  SimulationNoise& n = options.noise;
  if (Given("mocap_noise_m")) n.position_sigma = FLAGS_mocap_noise_m;
  if (Given("mocap_noise_rad")) n.heading_sigma = FLAGS_mocap_noise_rad;
  if (Given("latency_s")) n.mocap_latency = n.command_latency = FLAGS_latency_s;
  if (Given("slip")) n.slip = FLAGS_slip;
  if (FLAGS_seed < 0) throw UsageError("ccma replay: --seed must not be negative");
  n.seed = static_cast<unsigned>(FLAGS_seed);
  TrackingGains& g = options.gains;
  g.kp_position = g.kp_heading = FLAGS_kp;
  g.ki_position = g.ki_heading = FLAGS_ki;
  g.rate_hz = FLAGS_controller_hz;
  g.max_wheel_speed = FLAGS_max_wheel_speed;
  options.gait.hz = FLAGS_gait_hz;
  options.gait.bob_m = FLAGS_gait_bob_m;
  options.gait.sway_rad = FLAGS_gait_sway_rad;
  std::string why;
  if (!options.IsValid(&why)) throw UsageError("ccma replay: invalid options: " + why);
  return options;
}

// One sentence: what was simulated, for rmse.md.
std::string Setting(const Model& model, const std::string& path_name, const ReplayOptions& o) {
  const SimulationNoise& n = o.noise;
  return model.name + " on " + path_name + " (noise: " + FLAGS_noise + ", mocap " + FormatG(1000 * n.position_sigma) +
         " mm / " + FormatG(n.heading_sigma) + " rad, latency " + FormatG(1000 * n.mocap_latency) + "+" +
         FormatG(1000 * n.command_latency) + " ms, slip " + FormatG(100 * n.slip) + " +- " + FormatG(100 * n.slip_sigma) +
         " %, seed " + std::to_string(n.seed) + "; PI kp " + FormatG(o.gains.kp_position) + "/s, ki " +
         FormatG(o.gains.ki_position) + "/s^2 at " + FormatG(o.gains.rate_hz) + " Hz)";
}

}  // namespace

int RunReplay(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "replay");  // the registry's flags (commands.cc)
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "replay"));
  const std::vector<Waypoint> waypoints = WaypointsFlag("replay");
  const std::string dir = RequireFlag(FLAGS_out, "out", "replay");
  ReplayOptions options = ReplayOptionsFromFlags();
  std::string why;
  if (!IsValidReplay(model, waypoints, options, &why)) throw UsageError("ccma replay: " + why);
  const WorkEstimateOptions bound = CommandWorkEstimate("replay", "chain solves", false);  // checks --max_minutes
  OutputDirectory output(dir, "ccma replay");
  // Written in a private scratch folder, moved into --out at the end
  // (apps/output_file.h): a link planted in --out is replaced, never
  // written through. Made before the run: an unwritable --out stops here.
  FolderOutput folder(dir, "out");

  // Work bounded by its cost (--max_minutes): the chain's solves timed as they are made.
  std::unique_ptr<WorkEstimate> estimate;
  options.on_solve = [&estimate, &bound](long done, long total) {
    if (!estimate) estimate = std::make_unique<WorkEstimate>(bound, total);
    estimate->Update(done);
  };
  const ReplayResult r = Replay(model, waypoints, options);
  const std::string path_name = std::filesystem::path(FLAGS_waypoints).filename().string();
  documents::WriteReplayCsv(folder.scratch(), model, r);
  const std::string table = documents::ReplayRmseTable(model, r, Setting(model, path_name, options));
  std::ofstream(folder.scratch() + "/rmse.md") << table;
  std::cerr << table;
  documents::Document document = documents::ReplayDocument(model, options, r);
  PrintWarnings(document, "replay");
  std::string plot_warning;
  std::vector<std::string> plots = PlotReplay(folder.scratch(), model, r, path_name, &plot_warning);
  for (std::string& plot : plots) plot = folder.Final(plot);
  if (!plot_warning.empty()) std::cerr << "ccma replay: " << plot_warning << "\n";
  folder.Commit();
  output.Keep();
  nlohmann::json& out = document.json;
  out["files"] = {dir + "/end_effector.csv", dir + "/bases.csv", dir + "/rmse.md"};
  out["plots"] = plots;
  if (!plot_warning.empty()) out["plot_warning"] = plot_warning;
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
