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

std::string G(double v) { return FormatG(v); }  // %g, for every number in a message or script

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
                  G(r.failed_step_time) + " s (red dotted line)");
  }
  if (r.torn) {
    out.push_back("FAILED: chain torn (could not follow the bases) in " + std::to_string(r.torn_samples) + " of " +
                  std::to_string(r.samples.size()) + " samples from t = " + G(r.first_torn_time) +
                  " s (" + torn_mark + "), worst E = " + G(r.max_residual_energy) + " m^2");
  }
  if (r.samples.empty()) out.push_back("FAILED: no samples");
  return out;
}

// Labels 101.. at the top of the page: the title, then the failures in red.
std::string HeadingLabels(const std::string& title, const ReplayResult& r, int height,
                          const std::string& torn_mark) {
  std::ostringstream s;
  s << "set label 101 " << GnuplotQuote(title) << " at screen 0.5, screen " << G(1 - 22.0 / height)
    << " center font ',13'\n";
  int n = 0;
  for (const std::string& line : FailureHeadlines(r, torn_mark)) {
    s << "set label " << 102 + n << " " << GnuplotQuote(line) << " at screen 0.5, screen "
      << G(1 - (46.0 + 20 * n) / height) << " center font ',11' textcolor rgb '" << kFailColour << "'\n";
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
    s << "set object " << id++ << " rect from first " << G(from) << ", graph 0 to first " << G(to)
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

// `using` of a column in display units (positions m -> mm).
std::string Scaled(int column, bool angle) {
  return angle ? std::to_string(column) : "(1000*$" + std::to_string(column) + ")";
}

std::string EndEffectorFigure(const std::string& format, const Model& model, const ReplayResult& r,
                              const std::string& path_name) {
  const std::vector<int> components = ReportedComponents(model);
  const int panels = static_cast<int>(components.size()) + 1;
  const int height = 110 + HeadingHeight(r) + 210 * panels;
  const double top = 1 - (HeadingHeight(r) + 20.0) / height, bottom = 55.0 / height;
  std::ostringstream s;
  s << TerminalCommand(format, 1200, height) << "set output 'end_effector." << format << "'\n"
    << "set multiplot layout " << panels << ",1 margins 0.07,0.72," << G(bottom) << "," << G(top)
    << " spacing 0.08," << G(28.0 / height) << "\n"
    << "set grid\nset key at screen 0.99, graph 1 right top Left reverse\nset xrange [" << G(r.samples.front().time) << ":"
    << G(r.samples.back().time) << "]\nset format x ''\nunset xlabel\n"
    << HeadingLabels("SIMULATION (ccma replay): " + model.name + " end-effector on " + path_name +
                         ", tracked vs commanded",
                     r, height, "red bands");
  s << TornBands(r);
  if (!std::isnan(r.failed_step_time)) {
    s << "set arrow 1 from first " << G(r.failed_step_time) << ", graph 0 to first " << G(r.failed_step_time)
      << ", graph 1 nohead front lw 2 dt 3 lc rgb '" << kFailColour << "'\n";
  }
  for (size_t i = 0; i < components.size(); ++i) {
    const int c = components[i];
    const bool angle = IsAngle(c);
    s << "set ylabel '" << ComponentName(c) << (angle ? " [rad]'\n" : " [mm]'\n") << "plot 'end_effector.csv' using 1:"
      << Scaled(CommandedColumn(c), angle) << " with lines lw 2 lc rgb '" << kCommandedColour
      << "' title 'commanded', '' using 1:" << Scaled(TrackedColumn(c), angle) << " with lines lw 1.5 dt 2 lc rgb '"
      << kTrackedColour << "' title 'tracked'";
    s << KeyEntries(r) << "\n";
    if (i == 0) s << UnsetHeadingLabels(r);
  }
  // The error panel: positions [mm] on the left axis, angles [rad] on the right.
  bool positions = false, angles = false;
  for (const int c : components) (IsAngle(c) ? angles : positions) = true;
  const bool both = positions && angles;
  s << "set format x '%g'\nset xlabel 'time [s]'\nset ylabel "
    << (positions ? "'error, tracked - commanded [mm]'" : "'error, tracked - commanded [rad]'") << "\n";
  if (both) s << "set ytics nomirror\nset y2tics\nset y2label 'error [rad] (dashed lines)'\n";
  s << "plot ";
  for (size_t i = 0; i < components.size(); ++i) {
    const int c = components[i];
    const bool angle = IsAngle(c);
    const std::string axes = both && angle ? " axes x1y2" : " axes x1y1";
    s << (i ? ", " : "") << "'end_effector.csv' using 1:" << ErrorColumn(c) << axes << " with lines lw 1.5"
      << (both && angle ? " dt 2" : "") << " lc rgb '" << DistinctColour(int(i), 8) << "' title '"
      << ComponentName(c) << (angle ? " [rad]'" : " [mm]'");
  }
  s << KeyEntries(r) << "\nunset multiplot\nunset arrow\nunset object\nunset y2tics\nunset y2label\nset ytics mirror\nunset xrange\n"
    << "set format x '%g'\nset output\n";
  return s.str();
}

std::string BasesFigure(const std::string& format, const Model& model, const ReplayResult& r) {
  const int n = model.num_bases();
  const bool named = n <= 8;  // a key entry per base only for a few
  // The page follows the data's aspect (equal axes), within limits.
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (const ReplaySample& sample : r.samples) {
    for (const Eigen::VectorXd* u : {&sample.set_controls, &sample.true_controls}) {
      for (int k = 0; k < n; ++k) {
        if (!std::isfinite((*u)[3 * k]) || !std::isfinite((*u)[3 * k + 1])) continue;
        x0 = std::min(x0, (*u)[3 * k]), x1 = std::max(x1, (*u)[3 * k]);
        y0 = std::min(y0, (*u)[3 * k + 1]), y1 = std::max(y1, (*u)[3 * k + 1]);
      }
    }
  }
  const double aspect = x1 > x0 && y1 > y0 ? (y1 - y0) / (x1 - x0) : 1.0;
  const int width = 1000, key_height = 40 + 18 * ((n <= 8 ? n + 4 : 4) + 1) / 2;
  const int plot_height = static_cast<int>(std::clamp(860 * aspect, 350.0, 1100.0));
  const int height = HeadingHeight(r) + 20 + plot_height + 60 + key_height;
  std::ostringstream s;
  s << TerminalCommand(format, width, height) << "set output 'bases_xy." << format << "'\n"
    << "set size ratio -1\nset grid\nset tmargin at screen " << G(1 - (HeadingHeight(r) + 20.0) / height)
    << "\nset bmargin at screen " << G((key_height + 50.0) / height) << "\nset xlabel 'x [m]'\nset ylabel 'y [m]'\n"
    << "set key below horizontal\n"
    << HeadingLabels("SIMULATION (ccma replay): " + model.name + ", " + std::to_string(n) +
                         " mobile bases in the ground plane" + (named ? "" : " (one colour per base)"),
                     r, height, "red dots")
    << "$starts << EOD\n" << std::setprecision(12);
  for (int k = 0; k < n && !r.samples.empty(); ++k) {
    s << r.samples.front().true_controls[3 * k] << "," << r.samples.front().true_controls[3 * k + 1] << "\n";
  }
  s << "EOD\nplot ";
  const int torn_column = 2 + 6 * n + model.num_actuated_joints();  // bases, joints, torn
  for (int k = 0; r.torn && k < n; ++k) {  // under the paths
    s << "'bases.csv' using ($" << torn_column << ">0 ? $" << 5 + 6 * k << " : NaN):" << 6 + 6 * k
      << " with points pt 7 ps 0.4 lc rgb '" << kFailColour << "' "
      << (k == 0 ? "title 'tracked pose while the chain was torn'" : "notitle") << ", ";
  }
  for (int k = 0; k < n; ++k) {
    const std::string colour = DistinctColour(k, n);
    s << (k ? ", " : "") << "'bases.csv' using " << 2 + 6 * k << ":" << 3 + 6 * k << " with lines lw 2 lc rgb '"
      << colour << "' " << (named ? "title " + GnuplotQuote(model.mobile_bases[k].name) : std::string("notitle"))
      << ", '' using " << 5 + 6 * k << ":" << 6 + 6 * k << " with lines lw 1.5 dt 2 lc rgb '" << colour
      << "' notitle";
  }
  s << ", $starts using 1:2 with points pt 6 ps 1.2 lc rgb 'black' title 'start'"
    << ", keyentry with lines lw 2 lc rgb 'black' title 'set pose (solid)'"
    << ", keyentry with lines lw 1.5 dt 2 lc rgb 'black' title 'tracked pose (dashed)'\n"
    << UnsetHeadingLabels(r) << "set size noratio\nset tmargin\nset bmargin\nset key default\nset output\n";
  return s.str();
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
