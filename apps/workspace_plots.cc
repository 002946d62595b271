// `ccma workspace --plot=DIR`: the reachability and sigma_min maps over the
// first two sampled components (apps/plots.h).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "apps/cli.h"
#include "apps/output_file.h"
#include "apps/plots.h"

namespace ccma::cli {
namespace {

double Value(const PoseTarget& p, int c) { return c < 3 ? p.position[c] : p.rpy[c - 3]; }

// For every sampled component after the first two, the sampled value
// nearest home: a grid's slice keeps the samples at those values.
std::vector<double> SliceValues(const Model& model, const WorkspaceOptions& options, const WorkspaceResult& result) {
  const EndEffectorPose home = ComputeEndEffectorPose(model, State::Home(model));
  std::vector<double> keep(options.ranges.size(), 0);
  for (size_t d = 2; d < options.ranges.size(); ++d) {
    const int c = options.ranges[d].component;
    const double h = c < 3 ? home.position[c] : home.rpy[c - 3];
    double best = std::numeric_limits<double>::infinity();
    for (const WorkspaceSample& s : result.samples) {
      if (std::abs(Value(s.pose, c) - h) < std::abs(best - h)) best = Value(s.pose, c);
    }
    keep[d] = best;
  }
  return keep;
}

// DIR/workspace_slice.dat: first two sampled components, reachable,
// sigma_min, one line per sample of the slice (every sample when random).
void WriteSliceData(const std::string& dir, const WorkspaceOptions& options, const WorkspaceResult& result,
                    const std::vector<double>& keep) {
  const int a = options.ranges[0].component;
  const int b = options.ranges.size() > 1 ? options.ranges[1].component : -1;
  std::ofstream dat(dir + "/workspace_slice.dat");
  dat << std::setprecision(17);
  for (const WorkspaceSample& s : result.samples) {
    bool in_slice = true;
    for (size_t d = 2; d < options.ranges.size(); ++d) {
      in_slice = in_slice && Value(s.pose, options.ranges[d].component) == keep[d];
    }
    if (!in_slice && options.random_samples == 0) continue;
    dat << Value(s.pose, a) << " " << (b >= 0 ? Value(s.pose, b) : 0.0) << " " << (s.reachable ? 1 : 0) << " "
        << (s.reachable ? s.sigma_min : 0.0) << "\n";
  }
  if (!dat) throw std::runtime_error("--plot: cannot write " + dir + "/workspace_slice.dat");
}

// The script of `what` ("reachability" or "sigma_min") over components a, b
// (b = -1: one range only).
std::string MapScript(const std::string& what, const Model& model, int a, int b) {
  auto unit = [](int c) { return c < 3 ? " [m]" : " [rad]"; };
  const std::string xl = std::string(kEndEffectorComponentNames[static_cast<size_t>(a)]) + unit(a);
  const std::string yl = b >= 0 ? std::string(kEndEffectorComponentNames[static_cast<size_t>(b)]) + unit(b) : "-";
  const std::string title = "workspace of " + model.name;
  // Unreachable samples are never drawn as a colour of the scale: on the
  // sigma_min map a 0 would read as "reachable but singular". Grey crosses
  // and the red-to-blue ramp, as in the 3D viewer (viewer/js/src/workspace.js).
  const std::string unreachable =
      "'' using 1:($3 > 0.5 ? 1/0 : $2) with points pt 2 ps 1.2 lc rgb '#8b929c' title 'unreachable'";
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
  return script.str();
}

// Draws reachability.png and sigma_min.png in `scratch` (which holds the
// data); returns the names drawn. A failure is a warning, as a missing gnuplot.
std::vector<std::string> DrawMaps(const Model& model, const WorkspaceOptions& options, const std::string& scratch,
                                  std::string* warning) {
  std::vector<std::string> drawn;
  if (FindGnuplot().empty()) {
    *warning = "gnuplot not found: wrote the data of the maps only";
    return drawn;
  }
  const int a = options.ranges[0].component;
  const int b = options.ranges.size() > 1 ? options.ranges[1].component : -1;
  for (const std::string& what : {std::string("reachability"), std::string("sigma_min")}) {
    const std::string error = RunGnuplot(MapScript(what, model, a, b), scratch);
    if (!error.empty()) {
      *warning = error;
      break;
    }
    drawn.push_back(what + ".png");
  }
  return drawn;
}

}  // namespace

// Everything is written in a fresh private folder inside DIR (gnuplot opens
// its pictures itself) and then renamed into DIR: a link planted in DIR
// under one of the fixed names is replaced, never written through.
std::vector<std::string> PlotWorkspaceMaps(const Model& model, const WorkspaceOptions& options,
                                           const WorkspaceResult& result, const std::string& dir,
                                           std::string* warning) {
  std::vector<std::string> files;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir)) throw UsageError("--plot: cannot create folder '" + dir + "'");
  const std::string scratch = MakeScratchFolder(dir, "plot");
  try {
    WriteSliceData(scratch, options, result, SliceValues(model, options, result));
    std::vector<std::string> names = DrawMaps(model, options, scratch, warning);
    names.insert(names.begin(), "workspace_slice.dat");
    for (const std::string& name : names) {
      if (!MoveIntoFolder(scratch, name, dir)) throw std::runtime_error("--plot: cannot write " + dir + "/" + name);
      files.push_back(dir + "/" + name);
    }
  } catch (...) {
    RemoveScratchFolder(scratch);
    throw;
  }
  RemoveScratchFolder(scratch);
  return files;
}

}  // namespace ccma::cli
