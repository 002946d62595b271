// Plots and reports of the `ccma` tool: one place that talks to gnuplot.
//
// Safety: gnuplot is started without a shell (posix_spawn, argument vector
// {"gnuplot"}), the script goes to its stdin, and it runs in the output
// folder, so scripts name only fixed relative files (end_effector.csv, ...)
// and never a user's path. Every other string that enters a script (titles
// with model and base names) goes through GnuplotQuote.
#ifndef CCMA_APPS_PLOTS_H_
#define CCMA_APPS_PLOTS_H_

#include <string>
#include <vector>

#include "ccma/model.h"
#include "execution/replay.h"

namespace ccma::cli {

// A gnuplot string expression whose value is `text`, safe for any input:
// single-quoted, where gnuplot expands neither backquotes (command
// substitution) nor @macros nor backslash escapes. Control characters such
// as newline, which would end the command, become '?'. Quotes: gnuplot's
// documented '' for a quote fails where a quote follows another quote (its
// scanner ends the string there: '''a' is '' followed by 'a'), so text with
// quotes becomes a parenthesized concatenation of single-quoted runs and
// "'" (a double-quoted string holding just a quote): it's -> ('it'."'".'s').
// Accepted wherever the scripts here take a string (titles, labels, key
// entries, data file names). Use with `noenhanced` text (set globally by
// TerminalCommand), so the text is also shown literally.
std::string GnuplotQuote(const std::string& text);

// The gnuplot executable found on PATH (searched here, not by a shell), or "".
std::string FindGnuplot();

// Runs gnuplot on `script` (written to its stdin through a pipe) with
// `working_dir` as its working directory; its stdout goes to /dev/null, its
// stderr is kept for the message. Never throws: returns "" on success, else
// why it failed (not found, could not start, exit status and first error).
std::string RunGnuplot(const std::string& script, const std::string& working_dir);

// n colours as far apart as hue allows, "#rrggbb", for item i in [0, n).
std::string DistinctColour(int i, int n);

// `set terminal` for "png" (cairo) or "svg" with a size in pixels.
std::string TerminalCommand(const std::string& format, int width, int height);

// ---- bench ---------------------------------------------------------------
// Plots DIR/<model>_convergence_{lm,bfgs}.dat of `models` into
// DIR/convergence_{lm,bfgs}.{png,svg} (scripts kept as convergence_*.gnuplot).
// Returns the files written; `warning` is set when gnuplot is missing or fails.
std::vector<std::string> PlotConvergence(const std::string& dir, const std::vector<std::string>& models,
                                         std::string* warning);

// ---- replay --------------------------------------------------------------
// The end-effector components a replay reports, in display order: the
// paper's y, z, x, yaw for a model controlling exactly x, y, z and yaw;
// otherwise x, y, z, roll, pitch, yaw, those the model controls.
std::vector<int> ReportedComponents(const Model& model);
// "x", "y", ..., and their display units: positions in mm, angles in rad.
std::string ComponentName(int component);
bool IsAngle(int component);
// The paper's hardware RMSE rows apply: the model is 4dof_reduced or 4dof_complete.
bool IsPaperModel(const Model& model);

struct PaperRow {
  const char* experiment;
  double y_mm, z_mm, x_mm, yaw_rad;
};
// The paper's hardware RMSE (Section IV).
const std::vector<PaperRow>& PaperHardwareRmse();

// One line per way the replay failed (plan not converged, chain torn, no
// samples), each starting with what failed; empty when trustworthy.
std::vector<std::string> ReplayFailures(const ReplayResult& result);

// The RMSE table (markdown): "WARNING: ..." lines at its top when the result
// is not trustworthy, then the reported components of the simulation, and the
// paper's hardware rows for the paper's models only. `setting` describes the
// run (model, path, noise) in one sentence.
std::string ReplayRmseTable(const Model& model, const ReplayResult& result, const std::string& setting);

// The CSV files the plots read (in DIR): end_effector.csv and bases.csv,
// labelled SIMULATION, with units in the header and a torn 0/1 column.
void WriteReplayCsv(const std::string& dir, const Model& model, const ReplayResult& result);

// The gnuplot script (relative file names only) that draws
// end_effector.{png,svg} and bases_xy.{png,svg} from the CSV files.
std::string ReplayPlotScript(const Model& model, const ReplayResult& result, const std::string& path_name);

// Writes DIR/replay.gnuplot and runs it in DIR. Returns the plots written;
// `warning` is set when gnuplot is missing or fails.
std::vector<std::string> PlotReplay(const std::string& dir, const Model& model, const ReplayResult& result,
                                    const std::string& path_name, std::string* warning);

}  // namespace ccma::cli

#endif  // CCMA_APPS_PLOTS_H_
