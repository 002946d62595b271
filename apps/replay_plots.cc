// `ccma replay --out=DIR`: the plots of a replay (apps/plots.h), written as
// one gnuplot script that reads the CSV files of replay_report.h.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "apps/plots.h"
#include "ccma/internal/format.h"

namespace ccma::cli {
namespace {

// end_effector.csv's columns (1-based): commanded, tracked, error, torn.
int CommandedColumn(int c) { return 2 + c; }
int TrackedColumn(int c) { return 8 + c; }
int ErrorColumn(int c) { return 14 + c; }
const char kCommandedColour[] = "#1f77b4", kTrackedColour[] = "#ff7f0e", kFailColour[] = "#e00000";

// The red lines of the plots' heading: what failed, short; `torn_mark`
// says how torn samples are marked.
std::vector<std::string> FailureHeadlines(const ReplayResult& r, const std::string& torn_mark = "red") {
  std::vector<std::string> out;
  if (!r.converged) {
    out.push_back("FAILED: the control solution did not reach a waypoint; the plan stops at t = " +
                  FormatG(r.failed_step_time) + " s (red dotted line)");
  }
  if (r.torn) {
    out.push_back("FAILED: chain torn (could not follow the bases) in " + std::to_string(r.torn_samples) + " of " +
                  std::to_string(r.samples.size()) + " samples from t = " + FormatG(r.first_torn_time) +
                  " s (" + torn_mark + "), worst E = " + FormatG(r.max_residual_energy) + " m^2");
  }
  if (r.samples.empty()) out.push_back("FAILED: no samples");
  return out;
}

// Labels 101.. at the top of the page: the title, then the failures in red.
std::string HeadingLabels(const std::string& title, const ReplayResult& r, int height,
                          const std::string& torn_mark) {
  std::ostringstream s;
  s << "set label 101 " << GnuplotQuote(title) << " at screen 0.5, screen " << FormatG(1 - 22.0 / height)
    << " center font ',13'\n";
  int n = 0;
  for (const std::string& line : FailureHeadlines(r, torn_mark)) {
    s << "set label " << 102 + n << " " << GnuplotQuote(line) << " at screen 0.5, screen "
      << FormatG(1 - (46.0 + 20 * n) / height) << " center font ',11' textcolor rgb '" << kFailColour << "'\n";
    ++n;
  }
  return s.str();
}

std::string UnsetHeadingLabels(const ReplayResult& r) {
  std::string s = "unset label 101\n";
  for (size_t n = 0; n < FailureHeadlines(r).size(); ++n) s += "unset label " + std::to_string(102 + n) + "\n";
  return s;
}

int HeadingHeight(const ReplayResult& r) { return 40 + 20 * static_cast<int>(FailureHeadlines(r).size()); }

// The time intervals of torn samples (each sample covers half the way to its
// neighbours), merged; at most ~300, so that a script stays small.
std::vector<std::pair<double, double>> TornIntervals(const ReplayResult& r) {
  std::vector<std::pair<double, double>> out;
  const auto& s = r.samples;
  if (s.empty()) return out;
  const double min_gap = (s.back().time - s.front().time) / 300;
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s[i].torn) continue;
    const double from = i > 0 ? 0.5 * (s[i - 1].time + s[i].time) : s[i].time;
    const double to = i + 1 < s.size() ? 0.5 * (s[i].time + s[i + 1].time) : s[i].time;
    if (!out.empty() && from - out.back().second <= min_gap) {
      out.back().second = to;
    } else {
      out.emplace_back(from, to);
    }
  }
  return out;
}

// Red bands behind every panel where the chain was torn (objects 1000..).
std::string TornBands(const ReplayResult& r) {
  std::ostringstream s;
  int id = 1000;
  for (const auto& [from, to] : TornIntervals(r)) {
    s << "set object " << id++ << " rect from first " << FormatG(from) << ", graph 0 to first " << FormatG(to)
      << ", graph 1 behind fillcolor rgb '" << kFailColour << "' fillstyle transparent solid 0.18 noborder\n";
  }
  return s.str();
}

// Key entries for the failure marks.
std::string KeyEntries(const ReplayResult& r) {
  std::string s;
  if (r.torn) {
    s += ", keyentry with boxes fillcolor rgb '" + std::string(kFailColour) +
         "' fillstyle transparent solid 0.18 noborder title 'chain torn'";
  }
  if (!std::isnan(r.failed_step_time)) {
    s += ", keyentry with lines lw 2 dt 3 lc rgb '" + std::string(kFailColour) + "' title 'failed plan step'";
  }
  return s;
}

// The plots draw at most about this many samples of a series: a long replay's
// CSVs keep every sample, its plots every n-th (gnuplot's `every`), so that
// gnuplot's time stays bounded (a million samples took it minutes).
constexpr size_t kMaxPlottedSamples = 4000;

// " every n" for the samples' files (bases.csv, end_effector.csv), or "".
std::string Every(const ReplayResult& r) {
  const size_t n = (r.samples.size() + kMaxPlottedSamples - 1) / kMaxPlottedSamples;
  return n > 1 ? " every " + std::to_string(n) : "";
}

// `using` of a column in display units (positions m -> mm).
std::string Scaled(int column, bool angle) {
  return angle ? std::to_string(column) : "(1000*$" + std::to_string(column) + ")";
}

std::string EndEffectorFigure(const std::string& format, const Model& model, const ReplayResult& r,
                              const std::string& path_name) {
  const std::vector<int> components = documents::ReportedComponents(model);
  const int panels = static_cast<int>(components.size()) + 1;
  const int height = 110 + HeadingHeight(r) + 210 * panels;
  const double top = 1 - (HeadingHeight(r) + 20.0) / height, bottom = 55.0 / height;
  std::ostringstream s;
  s << TerminalCommand(format, 1200, height) << "set output 'end_effector." << format << "'\n"
    << "set multiplot layout " << panels << ",1 margins 0.07,0.72," << FormatG(bottom) << "," << FormatG(top)
    << " spacing 0.08," << FormatG(28.0 / height) << "\n"
    << "set grid\nset key at screen 0.99, graph 1 right top Left reverse\nset xrange [" << FormatG(r.samples.front().time) << ":"
    << FormatG(r.samples.back().time) << "]\nset format x ''\nunset xlabel\n"
    << HeadingLabels("SIMULATION (ccma replay): " + model.name + " end-effector on " + path_name +
                         ", tracked vs commanded",
                     r, height, "red bands");
  s << TornBands(r);
  if (!std::isnan(r.failed_step_time)) {
    s << "set arrow 1 from first " << FormatG(r.failed_step_time) << ", graph 0 to first " << FormatG(r.failed_step_time)
      << ", graph 1 nohead front lw 2 dt 3 lc rgb '" << kFailColour << "'\n";
  }
  for (size_t i = 0; i < components.size(); ++i) {
    const int c = components[i];
    const bool angle = documents::IsAngle(c);
    s << "set ylabel '" << documents::ComponentName(c) << (angle ? " [rad]'\n" : " [mm]'\n") << "plot 'end_effector.csv'" << Every(r) << " using 1:"
      << Scaled(CommandedColumn(c), angle) << " with lines lw 2 lc rgb '" << kCommandedColour
      << "' title 'commanded', ''" << Every(r) << " using 1:" << Scaled(TrackedColumn(c), angle) << " with lines lw 1.5 dt 2 lc rgb '"
      << kTrackedColour << "' title 'tracked'";
    s << KeyEntries(r) << "\n";
    if (i == 0) s << UnsetHeadingLabels(r);
  }
  // The error panel: positions [mm] on the left axis, angles [rad] on the right.
  bool positions = false, angles = false;
  for (const int c : components) (documents::IsAngle(c) ? angles : positions) = true;
  const bool both = positions && angles;
  s << "set format x '%g'\nset xlabel 'time [s]'\nset ylabel "
    << (positions ? "'error, tracked - commanded [mm]'" : "'error, tracked - commanded [rad]'") << "\n";
  if (both) s << "set ytics nomirror\nset y2tics\nset y2label 'error [rad] (dashed lines)'\n";
  s << "plot ";
  for (size_t i = 0; i < components.size(); ++i) {
    const int c = components[i];
    const bool angle = documents::IsAngle(c);
    const std::string axes = both && angle ? " axes x1y2" : " axes x1y1";
    s << (i ? ", " : "") << "'end_effector.csv'" << Every(r) << " using 1:" << ErrorColumn(c) << axes << " with lines lw 1.5"
      << (both && angle ? " dt 2" : "") << " lc rgb '" << DistinctColour(int(i), 8) << "' title '"
      << documents::ComponentName(c) << (angle ? " [rad]'" : " [mm]'");
  }
  s << KeyEntries(r) << "\nunset multiplot\nunset arrow\nunset object\nunset y2tics\nunset y2label\nset ytics mirror\nunset xrange\n"
    << "set format x '%g'\nset output\n";
  return s.str();
}

// The extent of paths in the ground plane [m] (finite points only).
struct Extent {
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  void Add(double x, double y) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  void Add(const Extent& e) {
    if (!e.empty()) Add(e.x0, e.y0), Add(e.x1, e.y1);
  }
  bool empty() const { return !(x1 >= x0); }
  double width() const { return empty() ? 0 : x1 - x0; }
  double height() const { return empty() ? 0 : y1 - y0; }
};

// Smallest side of a window [m]: a base that hardly moves still gets a
// readable frame.
constexpr double kMinWindow = 0.01;

// The smallest 1, 1.5, 2, 3, 4, 5, 6 or 8 times a power of ten at least
// `length` > 0: a window side that reads well in a title.
double NiceLength(double length) {
  const double least = length * (1 - 1e-9);  // 0.3 stays 0.3 whatever the rounding
  const double decade = std::pow(10.0, std::floor(std::log10(least)));
  for (const double step : {1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0}) {
    if (step * decade >= least) return step * decade;
  }
  return 10 * decade;
}

// Each base's extent over the samples: its set and true x, y.
std::vector<Extent> BaseExtents(const Model& model, const ReplayResult& r) {
  const int n = model.num_bases();
  std::vector<Extent> extents(static_cast<size_t>(n));
  for (const ReplaySample& sample : r.samples) {
    for (int k = 0; k < n; ++k) {
      const int i = model.base_control(k);
      extents[k].Add(sample.set_controls[i], sample.set_controls[i + 1]);
      extents[k].Add(sample.true_controls[i], sample.true_controls[i + 1]);
    }
  }
  return extents;
}

// A range bound with enough digits for a centimetre window far from the origin.
std::string Bound(double v) { return FormatG(v, 10); }

// `set xrange` and `set yrange`: the extent with `margin` [m] on every side,
// the shorter side widened (about its centre) to a third of the longer one
// so that a row of bases does not make a sliver (the page's aspect follows
// the ranges; `set size ratio -1` keeps the axes equal).
std::string FittedRanges(const Extent& e, double margin) {
  if (e.empty()) return "set autoscale\n";
  const double w = e.width() + 2 * margin, h = e.height() + 2 * margin;
  const double wx = std::max(w, h / 3) / 2, wy = std::max(h, w / 3) / 2;  // half sides
  const double cx = 0.5 * (e.x0 + e.x1), cy = 0.5 * (e.y0 + e.y1);
  return "set xrange [" + Bound(cx - wx) + ":" + Bound(cx + wx) + "]\nset yrange [" + Bound(cy - wy) + ":" +
         Bound(cy + wy) + "]\n";
}

// A square window of side `side` [m] centred on the extent.
std::string WindowRanges(const Extent& e, double side) {
  if (e.empty()) return "set autoscale\n";
  const double cx = 0.5 * (e.x0 + e.x1), cy = 0.5 * (e.y0 + e.y1);
  return "set xrange [" + Bound(cx - side / 2) + ":" + Bound(cx + side / 2) + "]\nset yrange [" +
         Bound(cy - side / 2) + ":" + Bound(cy + side / 2) + "]\n";
}

// $starts: each base's true x, y at the first sample, one line per base.
std::string StartsBlock(const Model& model, const ReplayResult& r) {
  std::ostringstream s;
  s << "$starts << EOD\n" << std::setprecision(12);
  for (int k = 0; k < model.num_bases() && !r.samples.empty(); ++k) {
    const int i = model.base_control(k);
    s << r.samples.front().true_controls[i] << "," << r.samples.front().true_controls[i + 1] << "\n";
  }
  s << "EOD\n";
  return s.str();
}

// bases.csv's column (1-based) of base k's set x and of its true x: after
// time_s, each base's set controls, then its true ones.
int SetXColumn(const Model& model, int k) { return 2 + 2 * model.base_control(k); }
int TrueXColumn(const Model& model, int k) {
  return SetXColumn(model, k) + KindOf(model.mobile_bases[static_cast<size_t>(k)]).num_controls();
}

// Red dots where base k's tracked pose was recorded while the chain was
// torn (drawn under its paths), followed by ", ".
std::string TornClause(const Model& model, const ReplayResult& r, int k, bool titled) {
  const int torn_column = 2 + 2 * model.num_base_controls() + model.num_actuated_joints();  // bases, joints, torn
  const int x = TrueXColumn(model, k);
  std::ostringstream s;
  s << "'bases.csv'" << Every(r) << " using ($" << torn_column << ">0 ? $" << x << " : NaN):" << x + 1
    << " with points pt 7 ps 0.4 lc rgb '" << kFailColour << "' "
    << (titled ? "title 'tracked pose while the chain was torn'" : "notitle") << ", ";
  return s.str();
}

// Base k's set path (solid, with `title`) and tracked path (dashed) in its colour.
std::string PathClauses(const Model& model, const ReplayResult& r, int k, const std::string& title) {
  const std::string colour = DistinctColour(k, model.num_bases());
  std::ostringstream s;
  const int set_x = SetXColumn(model, k), true_x = TrueXColumn(model, k);
  s << "'bases.csv'" << Every(r) << " using " << set_x << ":" << set_x + 1 << " with lines lw 2 lc rgb '" << colour
    << "' " << title << ", ''" << Every(r) << " using " << true_x << ":" << true_x + 1 << " with lines lw 1.5 dt 2 lc rgb '" << colour << "' notitle";
  return s.str();
}

// Every base's paths and start in one plot; a key entry per base when
// `named`; `windows` adds each base's panel window as a square in its colour.
std::string AllBasesPlot(const Model& model, const ReplayResult& r, bool named, bool windows) {
  const int n = model.num_bases();
  std::string s = "plot ";
  for (int k = 0; r.torn && k < n; ++k) s += TornClause(model, r, k, k == 0);
  for (int k = 0; windows && k < n; ++k) {
    s += "$windows using 1:2:3:3 every ::" + std::to_string(k) + "::" + std::to_string(k) +
         " with boxxyerror fillstyle empty lw 1 lc rgb '" + DistinctColour(k, n) + "' notitle, ";
  }
  for (int k = 0; k < n; ++k) {
    s += (k ? ", " : "") +
         PathClauses(model, r, k, named ? "title " + GnuplotQuote(model.mobile_bases[k].name) : std::string("notitle"));
  }
  return s + ", $starts using 1:2 with points pt 6 ps 1.2 lc rgb 'black' title 'start'" +
         ", keyentry with lines lw 2 lc rgb 'black' title 'set pose (solid)'" +
         ", keyentry with lines lw 1.5 dt 2 lc rgb 'black' title 'tracked pose (dashed)'\n";
}

// Every base in one frame fitted to their paths: for one base, for many
// (more than 8), or when the paths are large against the distances between
// the bases.
std::string SingleBasesFigure(const std::string& format, const Model& model, const ReplayResult& r,
                              const Extent& all) {
  const int n = model.num_bases();
  const bool named = n <= 8;  // a key entry per base only for a few
  const double margin = std::max(0.05 * std::max(all.width(), all.height()), kMinWindow / 2);
  // The page follows the data's aspect (equal axes), within limits.
  const double w = all.width() + 2 * margin, h = all.height() + 2 * margin;
  const double aspect = all.empty() ? 1.0 : std::max(h, w / 3) / std::max(w, h / 3);  // as FittedRanges
  const int width = 1000, key_height = 40 + 18 * ((n <= 8 ? n + 4 : 4) + 1) / 2;
  const int plot_height = static_cast<int>(std::clamp(860 * aspect, 350.0, 1100.0));
  const int height = HeadingHeight(r) + 20 + plot_height + 60 + key_height;
  std::ostringstream s;
  s << TerminalCommand(format, width, height) << "set output 'bases_xy." << format << "'\n"
    << "set size ratio -1\nset grid\nset tmargin at screen " << FormatG(1 - (HeadingHeight(r) + 20.0) / height)
    << "\nset bmargin at screen " << FormatG((key_height + 50.0) / height) << "\nset xlabel 'x [m]'\nset ylabel 'y [m]'\n"
    << "set key below horizontal\n" << FittedRanges(all, margin)
    << HeadingLabels("SIMULATION (ccma replay): " + model.name + ", " + std::to_string(n) +
                         " mobile bases in the ground plane" + (named ? "" : " (one colour per base)"),
                     r, height, "red dots")
    << StartsBlock(model, r) << AllBasesPlot(model, r, named, false) << UnsetHeadingLabels(r)
    << "set size noratio\nset tmargin\nset bmargin\nset autoscale\nset key default\nset output\n";
  return s.str();
}

// A few bases far apart against their paths: the layout of all of them,
// then one panel per base, every panel a square window of the same side
// `side` [m] around that base's path (one scale, so the panels compare).
std::string ZoomedBasesFigure(const std::string& format, const Model& model, const ReplayResult& r,
                              const std::vector<Extent>& extents, const Extent& all, double side) {
  const int n = model.num_bases(), panels = n + 1, columns = panels <= 4 ? 2 : 3;
  const int rows = (panels + columns - 1) / columns, cell = columns == 2 ? 470 : 400;
  // The key: one line per base, the start, set and tracked poses, the torn dots.
  const int width = columns == 2 ? 1000 : 1200, key_height = 30 + 17 * (n + 4);
  const int height = HeadingHeight(r) + 35 + rows * cell + 30 + key_height;
  std::ostringstream s;
  s << TerminalCommand(format, width, height) << "set output 'bases_xy." << format << "'\n"
    << "set grid\nset xlabel 'x [m]'\nset ylabel 'y [m]'\n"
    << HeadingLabels("SIMULATION (ccma replay): " + model.name + ", " + std::to_string(n) +
                         " mobile bases in the ground plane",
                     r, height, "red dots")
    << StartsBlock(model, r) << "$windows << EOD\n" << std::setprecision(12);
  for (const Extent& e : extents) s << 0.5 * (e.x0 + e.x1) << "," << 0.5 * (e.y0 + e.y1) << "," << side / 2 << "\n";
  s << "EOD\nset key at screen 0.5, screen " << FormatG((key_height - 10.0) / height) << " center top\n"
    << "set multiplot layout " << rows << "," << columns << " margins 0.08,0.97," << FormatG((key_height + 20.0) / height)
    << "," << FormatG(1 - (HeadingHeight(r) + 45.0) / height) << " spacing 0.1," << FormatG(70.0 / height) << "\n"
    << "set size ratio -1\nset title 'all bases (squares: the " << FormatG(100 * side) << " cm windows of the panels)'\n"
    << FittedRanges(all, std::max(0.05 * std::max(all.width(), all.height()), side / 2))
    << AllBasesPlot(model, r, true, true) << UnsetHeadingLabels(r) << "unset key\n";
  // One tic step on both axes of every window, 1, 2 or 5 times a power of
  // ten, 3 to 6 intervals (gnuplot's own choice crowds a narrow panel).
  const double least = side / 6 * (1 - 1e-9);  // rounding must not skip 0.3 / 6 = 0.05
  const double decade = std::pow(10.0, std::floor(std::log10(least)));
  const double tic = least <= decade ? decade : least <= 2 * decade ? 2 * decade
                   : least <= 5 * decade ? 5 * decade : 10 * decade;
  s << "set xtics " << FormatG(tic) << "\nset ytics " << FormatG(tic) << "\n";
  for (int k = 0; k < n; ++k) {
    s << "set title " << GnuplotQuote(model.mobile_bases[k].name) << "\n" << WindowRanges(extents[k], side) << "plot "
      << (r.torn ? TornClause(model, r, k, false) : "") << PathClauses(model, r, k, "notitle") << ", $starts using 1:2 every ::"
      << k << "::" << k << " with points pt 6 ps 1.2 lc rgb 'black' notitle\n";
  }
  s << "unset multiplot\nunset title\nset xtics autofreq\nset ytics autofreq\nset size noratio\nset autoscale\n"
    << "set key default\nset output\n";
  return s.str();
}

// bases_xy.FORMAT: the bases' set and tracked paths, axes equal, ranges
// fitted to the paths with a margin. When a few bases stand far apart
// against their paths (more than 3 windows), each also gets its own panel.
std::string BasesFigure(const std::string& format, const Model& model, const ReplayResult& r) {
  const int n = model.num_bases();
  const std::vector<Extent> extents = BaseExtents(model, r);
  Extent all;
  double largest = 0;  // the largest side of one base's path [m]
  for (const Extent& e : extents) {
    all.Add(e);
    largest = std::max({largest, e.width(), e.height()});
  }
  const double side = std::max(1.2 * largest, kMinWindow);
  const bool zoom = n >= 2 && n <= 8 && std::max(all.width(), all.height()) > 3 * side;
  return zoom ? ZoomedBasesFigure(format, model, r, extents, all, NiceLength(side))
              : SingleBasesFigure(format, model, r, all);
}

}  // namespace

std::string ReplayPlotScript(const Model& model, const ReplayResult& r, const std::string& path_name) {
  std::ostringstream s;
  s << "# ccma replay: run in the output folder (gnuplot replay.gnuplot)\nset datafile separator ','\n";
  if (r.samples.empty()) return s.str();
  for (const std::string format : {"png", "svg"}) {
    s << EndEffectorFigure(format, model, r, path_name) << BasesFigure(format, model, r);
  }
  return s.str();
}

std::vector<std::string> PlotReplay(const std::string& dir, const Model& model, const ReplayResult& r,
                                    const std::string& path_name, std::string* warning) {
  std::vector<std::string> files;
  if (FindGnuplot().empty()) {
    *warning = "gnuplot not found: plots skipped (apt-get install gnuplot-nox)";
    return files;
  }
  if (r.samples.empty()) {
    *warning = "no samples: nothing to plot";
    return files;
  }
  const std::string script = ReplayPlotScript(model, r, path_name);
  std::ofstream(dir + "/replay.gnuplot") << script;
  const std::string error = RunGnuplot(script, dir);
  if (!error.empty()) {
    *warning = "plots failed: " + error;
    return files;
  }
  for (const std::string format : {"png", "svg"}) {
    for (const char* name : {"end_effector", "bases_xy"}) files.push_back(dir + "/" + name + "." + format);
  }
  return files;
}

}  // namespace ccma::cli
