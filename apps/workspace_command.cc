// `ccma workspace --model=FILE --out=FILE.csv [--x=lo:hi ...] [--resolution=N | --samples=N --seed=S]
//                 [--threads=N] [--plot=DIR]`:
// reachability map over the controlled components (analyses/workspace.h);
// one CSV row per sample, optional gnuplot slice maps, JSON summary on stdout.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "apps/plots.h"
#include "ccma/internal/format.h"

DEFINE_string(x, "", "workspace: sample x over lo:hi [m] (e.g. -0.2:0.2)");
DEFINE_string(y, "", "workspace: sample y over lo:hi [m]");
DEFINE_string(z, "", "workspace: sample z over lo:hi [m]");
DEFINE_string(roll, "", "workspace: sample roll over lo:hi [rad]");
DEFINE_string(pitch, "", "workspace: sample pitch over lo:hi [rad]");
DEFINE_string(yaw, "", "workspace: sample yaw over lo:hi [rad]");
DEFINE_int32(resolution, 11, "workspace grid: points per sampled range, ends included, 1..10000 [points]");
DEFINE_int32(samples, 0, "workspace: seeded uniform samples instead of the grid, 1..100000 (default: the grid) [samples]");
DEFINE_int32(threads, 1, "worker threads, 1..256 (the results do not depend on it) [threads]");
DEFINE_string(plot, "", "workspace: folder for reachability and sigma_min maps over the first two ranges (gnuplot) [path]");

namespace ccma::cli {
namespace {

// "lo:hi" -> range; throws UsageError naming the flag.
WorkspaceRange ParseRange(const std::string& text, int component) {
  const std::string flag = kEndEffectorComponentNames[static_cast<size_t>(component)];
  const size_t colon = text.find(':');
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos) {
    throw UsageError("--" + flag + ": expected lo:hi (two numbers and one colon), got '" + text + "'");
  }
  auto number = [&](const std::string& part) {
    const Eigen::VectorXd v = ParseNumberList(part, flag);
    if (v.size() != 1) throw UsageError("--" + flag + ": expected lo:hi, got '" + text + "'");
    return v[0];
  };
  WorkspaceRange range{component, number(text.substr(0, colon)), number(text.substr(colon + 1))};
  if (!(std::abs(range.lo) <= kMaxMagnitude && std::abs(range.hi) <= kMaxMagnitude)) {
    throw UsageError("--" + flag + ": bounds must be finite numbers in [-" + FormatG(kMaxMagnitude) + ", " +
                     FormatG(kMaxMagnitude) + "]");
  }
  if (!(range.lo <= range.hi)) throw UsageError("--" + flag + ": needs lo <= hi, got '" + text + "'");
  return range;
}

const std::string* RangeFlag(int component) {
  static const std::string* const flags[6] = {&FLAGS_x, &FLAGS_y, &FLAGS_z, &FLAGS_roll, &FLAGS_pitch, &FLAGS_yaw};
  return flags[component];
}

// A number for the CSV: never NaN or inf (empty instead).
std::string Cell(double v) {
  if (!std::isfinite(v)) return "";
  std::ostringstream os;
  os << std::setprecision(17) << v;
  return os.str();
}

void WriteCsv(const Model& model, const WorkspaceResult& result, std::ostream& csv) {
  for (int c = 0; c < 6; ++c) {
    if (model.end_effector.controlled[static_cast<size_t>(c)]) csv << kEndEffectorComponentNames[static_cast<size_t>(c)] << ",";
  }
  csv << "reachable,residual_energy,sigma_min,error,rcond,max_limit_violation,limited_by,wave,start";
  for (int k = 0; k < model.num_controls(); ++k) csv << ",u" << k;
  csv << "\n";
  for (const WorkspaceSample& s : result.samples) {
    for (int c = 0; c < 6; ++c) {
      if (!model.end_effector.controlled[static_cast<size_t>(c)]) continue;
      csv << Cell(c < 3 ? s.pose.position[c] : s.pose.rpy[c - 3]) << ",";
    }
    std::string limited = s.limited_by;
    for (char& ch : limited) {
      if (ch == ',' || ch == '"' || ch == '\n' || ch == '\r') ch = ';';
    }
    csv << (s.reachable ? 1 : 0) << "," << Cell(s.residual_energy) << "," << Cell(s.reachable ? s.sigma_min : 0.0)
        << "," << Cell(s.error) << "," << Cell(s.rcond) << "," << Cell(s.max_limit_violation) << "," << limited << ","
        << s.wave << "," << s.start;
    for (int k = 0; k < model.num_controls(); ++k) {
      csv << ",";
      if (s.reachable) csv << Cell(s.controls[k]);
    }
    csv << "\n";
  }
}

// DIR/workspace_slice.dat (first two sampled components, reachable,
// sigma_min; a grid's other sampled components at the value nearest home)
// and reachability.png, sigma_min.png. Returns the files written.
std::vector<std::string> WritePlots(const Model& model, const WorkspaceOptions& options,
                                    const WorkspaceResult& result, const std::string& dir, std::string* warning) {
  std::vector<std::string> files;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir)) throw UsageError("--plot: cannot create folder '" + dir + "'");
  const int a = options.ranges[0].component;
  const int b = options.ranges.size() > 1 ? options.ranges[1].component : -1;
  const EndEffectorPose home = ComputeEndEffectorPose(model, State::Home(model));
  auto value = [](const PoseTarget& p, int c) { return c < 3 ? p.position[c] : p.rpy[c - 3]; };
  // Other sampled components: keep the samples whose value is the one nearest home.
  std::vector<double> keep(options.ranges.size(), 0);
  for (size_t d = 2; d < options.ranges.size(); ++d) {
    const int c = options.ranges[d].component;
    const double h = c < 3 ? home.position[c] : home.rpy[c - 3];
    double best = std::numeric_limits<double>::infinity();
    for (const WorkspaceSample& s : result.samples) {
      if (std::abs(value(s.pose, c) - h) < std::abs(best - h)) best = value(s.pose, c);
    }
    keep[d] = best;
  }
  {
    std::ofstream dat(dir + "/workspace_slice.dat");
    dat << std::setprecision(17);
    for (const WorkspaceSample& s : result.samples) {
      bool in_slice = true;
      for (size_t d = 2; d < options.ranges.size(); ++d) {
        in_slice = in_slice && value(s.pose, options.ranges[d].component) == keep[d];
      }
      if (!in_slice && options.random_samples == 0) continue;
      dat << value(s.pose, a) << " " << (b >= 0 ? value(s.pose, b) : 0.0) << " " << (s.reachable ? 1 : 0) << " "
          << (s.reachable ? s.sigma_min : 0.0) << "\n";
    }
    if (!dat) throw std::runtime_error("--plot: cannot write " + dir + "/workspace_slice.dat");
  }
  files.push_back(dir + "/workspace_slice.dat");
  if (FindGnuplot().empty()) {
    *warning = "gnuplot not found: wrote the data of the maps only";
    return files;
  }
  auto unit = [](int c) { return c < 3 ? " [m]" : " [rad]"; };
  const std::string xl = std::string(kEndEffectorComponentNames[static_cast<size_t>(a)]) + unit(a);
  const std::string yl = b >= 0 ? std::string(kEndEffectorComponentNames[static_cast<size_t>(b)]) + unit(b) : "-";
  const std::string title = "workspace of " + model.name;
  // Unreachable samples are never drawn as a colour of the scale: on the
  // sigma_min map a 0 would read as "reachable but singular". Grey crosses
  // and the red-to-blue ramp, as in the 3D viewer (viewer/js/src/workspace.js).
  const std::string unreachable =
      "'' using 1:($3 > 0.5 ? 1/0 : $2) with points pt 2 ps 1.2 lc rgb '#8b929c' title 'unreachable'";
  for (const std::string& what : {std::string("reachability"), std::string("sigma_min")}) {
    std::ostringstream script;
    script << TerminalCommand("png", 900, 700) << "\nset output '" << what << ".png'\n"
           << "set title " << GnuplotQuote(title + ": " + (what == "sigma_min"
                                                               ? "smallest singular value of dX/du"
                                                               : "reachable or not"))
           << "\nset xlabel " << GnuplotQuote(xl) << "\nset ylabel " << GnuplotQuote(yl) << "\n"
           << "set size ratio -1\nset key below center horizontal\n";
    if (what == "reachability") {
      script << "plot 'workspace_slice.dat' using 1:($3 > 0.5 ? $2 : 1/0) with points pt 5 ps 1.5 "
                "lc rgb '#43a047' title 'reachable', "
             << unreachable << "\n";
    } else {
      script << "set palette defined (0 '#c62828', 1 '#ef6c00', 2 '#d4a20a', 3 '#43a047', 4 '#1e88e5')\n"
                "set cbrange [0:*]\n"
                "set cblabel 'sigma_min [m or rad per control unit] (0: singular)'\n"
                "plot 'workspace_slice.dat' using 1:2:($3 > 0.5 ? $4 : 1/0) with points pt 5 ps 1.5 palette "
                "notitle, "
             << unreachable << "\n";
    }
    const std::string error = RunGnuplot(script.str(), dir);
    if (!error.empty()) {
      *warning = error;
      return files;
    }
    files.push_back(dir + "/" + what + ".png");
  }
  return files;
}

}  // namespace

int RunWorkspace(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "workspace");
  const std::string model_path = RequireFlag(FLAGS_model, "model", "workspace");
  const std::string out_path = RequireFlag(FLAGS_out, "out", "workspace");
  const Model model = LoadModelOrThrow(model_path);

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
  options.resolution = FLAGS_resolution;
  options.random_samples = FLAGS_samples;
  options.seed = static_cast<std::uint64_t>(FLAGS_seed);
  options.threads = FLAGS_threads;
  options.control = ControlOptionsFromFlags();
  std::string why;
  if (!options.IsValid(model, &why)) throw UsageError("ccma workspace: " + why);

  if (!FLAGS_plot.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(FLAGS_plot, ec);
    if (!std::filesystem::is_directory(FLAGS_plot)) throw UsageError("--plot: cannot create folder '" + FLAGS_plot + "'");
  }
  OutputFile file(out_path, "out");  // checked before the long run
  // Progress on stderr only for a person watching (a terminal).
  const bool show = isatty(STDERR_FILENO) != 0;
  int last_percent = -1;
  const WorkspaceResult result = ComputeWorkspace(model, options, [&](long long done, long long total) {
    if (!show) return;
    const int percent = static_cast<int>(100 * done / std::max<long long>(total, 1));
    if (percent == last_percent) return;
    last_percent = percent;
    const int bar = percent / 4;
    std::cerr << "\r[" << std::string(static_cast<size_t>(bar), '#') << std::string(static_cast<size_t>(25 - bar), ' ')
              << "] " << percent << "% (" << done << "/" << total << ")" << (done == total ? "\n" : "") << std::flush;
  });
  WriteCsv(model, result, file.stream());
  file.Commit();

  nlohmann::json out;
  out["model"] = model.name;
  out["out"] = out_path;
  out["samples"] = result.samples.size();
  out["reachable"] = result.reachable;
  out["seconds"] = result.seconds;
  out["threads"] = options.threads;
  out["mode"] = options.random_samples > 0 ? "random" : "grid";
  nlohmann::json components = nlohmann::json::array();
  for (int c : result.components) components.push_back(kEndEffectorComponentNames[static_cast<size_t>(c)]);
  out["components"] = components;
  if (!FLAGS_plot.empty()) {
    std::string warning;
    out["plots"] = WritePlots(model, options, result, FLAGS_plot, &warning);
    if (!warning.empty()) {
      out["plot_warning"] = warning;
      std::cerr << "ccma workspace: warning: " << warning << "\n";
    }
  }
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
