#include "apps/plots.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "ccma/rotation.h"

extern char** environ;

namespace ccma::cli {
namespace {

std::string G(double v) {  // %g, for every number in a message or script
  char text[64];
  std::snprintf(text, sizeof(text), "%g", v);
  return text;
}

std::string Fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

// Control characters (and DEL) replaced by '?': text for one line.
std::string OneLine(const std::string& text) {
  std::string out = text;
  for (char& c : out) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) c = '?';
  }
  return out;
}

// Writes all of `data` to `fd`; "" or why not. SIGPIPE (gnuplot gone) is
// blocked in this thread meanwhile and a SIGPIPE we caused is discarded.
std::string WriteAll(int fd, const std::string& data) {
  sigset_t pipe_set, old_mask, pending;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, &old_mask);
  sigpending(&pending);
  const bool was_pending = sigismember(&pending, SIGPIPE) == 1;
  std::string error;
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = std::string("writing the script to gnuplot failed: ") + std::strerror(errno);
      break;
    }
    done += static_cast<size_t>(n);
  }
  sigpending(&pending);
  if (!was_pending && sigismember(&pending, SIGPIPE) == 1) {
    const timespec zero{0, 0};
    sigtimedwait(&pipe_set, nullptr, &zero);
  }
  pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
  return error;
}

// The first lines of what gnuplot wrote on stderr, for a message.
std::string Excerpt(FILE* file) {
  std::string text;
  std::rewind(file);
  char buffer[4096];
  size_t n;
  while (text.size() < 600 && (n = std::fread(buffer, 1, sizeof(buffer), file)) > 0) text.append(buffer, n);
  std::string lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line) && lines.size() < 400;) {
    if (line.find_first_not_of(" \t\r^") == std::string::npos) continue;
    lines += (lines.empty() ? "" : " | ") + OneLine(line);
  }
  return lines.substr(0, 400);
}

}  // namespace

std::string GnuplotQuote(const std::string& text) {
  std::string run;  // the text with control characters replaced
  for (const char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    run += u < 0x20 || u == 0x7f ? '?' : c;
  }
  if (run.find('\'') == std::string::npos) return "'" + run + "'";
  // ('it'."'".'s'): single-quoted runs, each quote as "'" (a double-quoted
  // string holding no backslash and no backquote), joined by `.`.
  std::string out = "(";
  size_t start = 0;
  for (size_t q = run.find('\''); q != std::string::npos; q = run.find('\'', start)) {
    if (q > start) out += "'" + run.substr(start, q - start) + "'.";
    out += "\"'\".";
    start = q + 1;
  }
  if (start < run.size()) out += "'" + run.substr(start) + "'.";
  out.pop_back();  // the last '.'
  return out + ")";
}

std::string FindGnuplot() {
  const char* env = std::getenv("PATH");
  const std::string path = env != nullptr && *env != '\0' ? env : "/usr/local/bin:/usr/bin:/bin";
  std::istringstream dirs(path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (dir.empty() || dir[0] != '/') continue;  // never the working directory
    const std::string candidate = dir + "/gnuplot";
    struct stat info;
    if (stat(candidate.c_str(), &info) == 0 && S_ISREG(info.st_mode) && access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
  }
  return "";
}

std::string RunGnuplot(const std::string& script, const std::string& working_dir) {
  const std::string gnuplot = FindGnuplot();
  if (gnuplot.empty()) return "gnuplot not found on PATH: plots skipped (apt-get install gnuplot-nox)";
  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) return std::string("cannot create a pipe: ") + std::strerror(errno);
  FILE* err = std::tmpfile();  // gnuplot's stderr: a file, so it can never block gnuplot
  if (err == nullptr) {
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    return std::string("cannot create a temporary file: ") + std::strerror(errno);
  }
  fcntl(fileno(err), F_SETFD, FD_CLOEXEC);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fileno(err), STDERR_FILENO);
  posix_spawn_file_actions_addchdir_np(&actions, working_dir.c_str());
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  char arg0[] = "gnuplot";
  char* argv[] = {arg0, nullptr};
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, gnuplot.c_str(), &actions, &attributes, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  close(pipe_fds[0]);
  if (spawned != 0) {
    close(pipe_fds[1]);
    std::fclose(err);
    return "cannot start " + gnuplot + " in '" + OneLine(working_dir) + "': " + std::strerror(spawned);
  }
  const std::string write_error = WriteAll(pipe_fds[1], script);
  close(pipe_fds[1]);  // end of the script: gnuplot exits
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      std::fclose(err);
      return std::string("waiting for gnuplot failed: ") + std::strerror(errno);
    }
  }
  const std::string messages = Excerpt(err);
  std::fclose(err);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && write_error.empty()) return "";
  std::string why = WIFEXITED(status) && WEXITSTATUS(status) != 0
                        ? "gnuplot exited with status " + std::to_string(WEXITSTATUS(status))
                    : WIFSIGNALED(status) ? "gnuplot was killed by signal " + std::to_string(WTERMSIG(status))
                                          : write_error;  // gnuplot ended before reading all of the script
  if (!messages.empty()) why += ": " + messages;
  return why;
}

std::string DistinctColour(int i, int n) {
  static const char* kFew[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd",
                               "#8c564b", "#e377c2", "#17becf", "#bcbd22"};
  if (n <= 8) return kFew[((i % 8) + 8) % 8];
  // Hues around the circle (red left out: it marks failures), alternating
  // brightness so that neighbours differ twice.
  const double h = 6.0 * (0.06 + 0.86 * (i % n) / n), s = 0.85, v = i % 2 ? 0.62 : 0.92;
  const double c = v * s, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = v - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0: r = c, g = x; break;
    case 1: r = x, g = c; break;
    case 2: g = c, b = x; break;
    case 3: g = x, b = c; break;
    case 4: r = x, b = c; break;
    default: r = c, b = x; break;
  }
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", static_cast<int>(std::lround(255 * (r + m))),
                static_cast<int>(std::lround(255 * (g + m))), static_cast<int>(std::lround(255 * (b + m))));
  return text;
}

std::string TerminalCommand(const std::string& format, int width, int height) {
  const std::string size = " size " + std::to_string(width) + "," + std::to_string(height);
  return (format == "png" ? "set terminal pngcairo" + size + " font 'sans,10' noenhanced\n"
                          : "set terminal svg" + size + " font 'sans,10' noenhanced background rgb 'white'\n");
}

// ---- bench -----------------------------------------------------------------

std::vector<std::string> PlotConvergence(const std::string& dir, const std::vector<std::string>& models,
                                         std::string* warning) {
  std::vector<std::string> files;
  if (FindGnuplot().empty()) {
    *warning = "gnuplot not found: plots skipped (apt-get install gnuplot-nox, or scripts/setup.sh)";
    return files;
  }
  for (const std::string method : {"lm", "bfgs"}) {
    std::ostringstream plots;
    for (const int column : {2, 3}) {
      plots << (column == 2 ? "set ylabel 'objective O [m^2]'\n" : "set ylabel 'end-effector error [m or rad]'\n")
            << "plot ";
      for (size_t i = 0; i < models.size(); ++i) {
        plots << (i ? ", " : "") << GnuplotQuote(models[i] + "_convergence_" + method + ".dat") << " using 1:"
              << column << " with linespoints lw 2 lc rgb '" << DistinctColour(int(i), int(models.size()))
              << "' title " << GnuplotQuote(models[i]);
      }
      plots << "\n";
    }
    const std::string title = "ccma: one control step (10 mm + 0.005 rad), " +
                              std::string(method == "lm" ? "Levenberg-Marquardt" : "BFGS") + " outer loop";
    std::ostringstream script;
    script << "# ccma bench: run in the output folder (gnuplot convergence_" << method << ".gnuplot)\n";
    for (const std::string format : {"png", "svg"}) {
      const std::string file = "convergence_" + method + "." + format;
      script << TerminalCommand(format, 1400, 560) << "set output '" << file << "'\n"
             << "set multiplot layout 1,2 title " << GnuplotQuote(title) << "\n"
             << "set xlabel 'wall time [ms]'\nset logscale y\nset format y '1e%T'\nset key top right\nset grid\n"
             << plots.str() << "unset multiplot\nset output\n";
      files.push_back(dir + "/" + file);
    }
    std::ofstream(dir + "/convergence_" + method + ".gnuplot") << script.str();
    const std::string error = RunGnuplot(script.str(), dir);
    if (!error.empty()) *warning = "plotting convergence_" + method + ": " + error;
  }
  return files;
}

// ---- replay ----------------------------------------------------------------

std::vector<int> ReportedComponents(const Model& model) {
  const auto& c = model.end_effector.controlled;
  if (c[kX] && c[kY] && c[kZ] && c[kYaw] && !c[kRoll] && !c[kPitch]) return {kY, kZ, kX, kYaw};
  std::vector<int> out;
  for (int k = 0; k < 6; ++k) {
    if (c[k]) out.push_back(k);
  }
  return out;
}

std::string ComponentName(int component) {
  static const char* kNames[] = {"x", "y", "z", "roll", "pitch", "yaw"};
  return kNames[component];
}

bool IsAngle(int component) { return component >= 3; }

bool IsPaperModel(const Model& model) { return model.name == "4dof_reduced" || model.name == "4dof_complete"; }

const std::vector<PaperRow>& PaperHardwareRmse() {
  static const std::vector<PaperRow> kRows = {{"reduced scheme, sequential (Fig. 7)", 18, 12, 17, 0.09},
                                              {"reduced scheme, combined (Fig. 10)", 18, 22, 24, 0.13},
                                              {"complete scheme, combined", 10, 17, 13, 0.10}};
  return kRows;
}

std::vector<std::string> ReplayFailures(const ReplayResult& r) {
  std::vector<std::string> out;
  if (!r.converged) {
    out.push_back("not converged: the control solution did not reach every waypoint (the replay stops at t = " +
                  G(r.failed_step_time) + " s): " + OneLine(r.warning));
  }
  if (r.torn) {
    out.push_back("chain torn: the chain could not follow the bases in " + std::to_string(r.torn_samples) + " of " +
                  std::to_string(r.samples.size()) + " samples (residual energy above " +
                  G(r.torn_residual_energy) + " m^2), first at t = " + G(r.first_torn_time) +
                  " s, worst E = " + G(r.max_residual_energy) + " m^2");
  }
  if (r.samples.empty()) out.push_back("no samples: nothing was simulated");
  return out;
}

std::string ReplayRmseTable(const Model& model, const ReplayResult& r, const std::string& setting) {
  std::ostringstream table;
  if (!r.trustworthy()) {
    std::string reasons;
    auto add = [&](const std::string& reason) { reasons += (reasons.empty() ? "" : "; ") + reason; };
    if (!r.converged) add("the control solution did not reach every waypoint (stops at t = " + G(r.failed_step_time) + " s)");
    if (r.torn) add("the chain was torn in " + std::to_string(r.torn_samples) + " samples");
    if (r.samples.empty()) add("no samples");
    table << "WARNING: NOT TRUSTWORTHY, " << reasons << ": the RMSE below does not measure tracking.\n\n";
  }
  const std::vector<int> components = ReportedComponents(model);
  table << "RMSE of the end-effector, tracked against commanded. ccma: SIMULATION of " << setting << "."
        << (IsPaperModel(model) ? " Paper: hardware prototypes." : "") << "\n\n| source |";
  for (const int c : components) table << " " << ComponentName(c) << (IsAngle(c) ? " [rad] |" : " [mm] |");
  table << "\n|---|";
  for (size_t i = 0; i < components.size(); ++i) table << "---|";
  table << "\n| ccma simulation" << (r.trustworthy() ? "" : " (FAILED)") << " |";
  for (const int c : components) table << " " << (IsAngle(c) ? Fixed(r.rmse[c], 5) : Fixed(1000 * r.rmse[c], 3)) << " |";
  table << "\n";
  if (IsPaperModel(model)) {
    for (const PaperRow& row : PaperHardwareRmse()) {
      table << "| paper, " << row.experiment << " |";
      for (const int c : components) {
        table << " "
              << (c == kX ? G(row.x_mm) : c == kY ? G(row.y_mm) : c == kZ ? G(row.z_mm) : c == kYaw ? G(row.yaw_rad) : "-")
              << " |";
      }
      table << "\n";
    }
  }
  return table.str();
}

void WriteReplayCsv(const std::string& dir, const Model& model, const ReplayResult& r) {
  static const char* kUnits[] = {"m", "m", "m", "rad", "rad", "rad"};
  std::ofstream ee(dir + "/end_effector.csv");
  ee << "# SIMULATION (ccma replay): commanded = control solution, tracked = chain on the driven bases; "
        "err = tracked - commanded; torn = 1 where the chain could not follow the bases\ntime_s";
  for (int c = 0; c < 6; ++c) ee << ",cmd_" << ComponentName(c) << "_" << kUnits[c];
  for (int c = 0; c < 6; ++c) ee << "," << ComponentName(c) << "_" << kUnits[c];
  for (int c = 0; c < 6; ++c) ee << ",err_" << ComponentName(c) << (IsAngle(c) ? "_rad" : "_mm");
  ee << ",residual_energy_m2,torn\n" << std::setprecision(12);
  std::ofstream bases(dir + "/bases.csv");
  bases << "# SIMULATION (ccma replay): set and true poses of every base (k = index in the model:";
  for (int k = 0; k < model.num_bases(); ++k) bases << " " << k << " = " << OneLine(model.mobile_bases[k].name);
  bases << ")\ntime_s";
  for (int k = 0; k < model.num_bases(); ++k) {
    bases << ",set" << k << "_x_m,set" << k << "_y_m,set" << k << "_theta_rad,base" << k << "_x_m,base" << k
          << "_y_m,base" << k << "_theta_rad";
  }
  // Actuated joints hold their set-points (execution/replay.h): one column each.
  for (const Joint& joint : model.joints) {
    if (joint.actuated) bases << ",u_" << joint.name << (joint.type == JointType::kRevolute ? "_rad" : "_m");
  }
  bases << ",torn\n" << std::setprecision(12);
  for (const ReplaySample& s : r.samples) {
    ee << s.time;
    for (int c = 0; c < 6; ++c) ee << "," << s.commanded[c];
    for (int c = 0; c < 6; ++c) ee << "," << s.tracked[c];
    for (int c = 0; c < 6; ++c) {
      ee << "," << (IsAngle(c) ? WrapAngle(s.tracked[c] - s.commanded[c]) : 1000 * (s.tracked[c] - s.commanded[c]));
    }
    ee << "," << s.residual_energy << "," << (s.torn ? 1 : 0) << "\n";
    bases << s.time;
    for (int k = 0; k < model.num_bases(); ++k) {
      for (int c = 0; c < 3; ++c) bases << "," << s.set_controls[3 * k + c];
      for (int c = 0; c < 3; ++c) bases << "," << s.true_controls[3 * k + c];
    }
    for (const Joint& joint : model.joints) {
      if (joint.actuated) bases << "," << s.true_controls[joint.control];
    }
    bases << "," << (s.torn ? 1 : 0) << "\n";
  }
}

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
