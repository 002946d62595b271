// The plots of the `ccma` tool (gnuplot, through apps/gnuplot.h): the
// convergence of `ccma bench`, the replay's end-effector and bases, the
// workspace maps. Each writes its script beside the pictures, or only the
// data with a warning when gnuplot is missing.
#ifndef CCMA_APPS_PLOTS_H_
#define CCMA_APPS_PLOTS_H_

#include <string>
#include <vector>

#include "analyses/workspace.h"
#include "apps/gnuplot.h"
#include "documents/replay_report.h"
#include "ccma/model.h"
#include "execution/replay.h"

namespace ccma::cli {

// ---- bench ---------------------------------------------------------------
// Plots DIR/<model>_convergence_{lm,bfgs}.dat of `models` into
// DIR/convergence_{lm,bfgs}.{png,svg} (scripts kept as convergence_*.gnuplot).
// Returns the files written; `warning` is set when gnuplot is missing or fails.
std::vector<std::string> PlotConvergence(const std::string& dir, const std::vector<std::string>& models,
                                         std::string* warning);

// ---- replay (the CSV files and the RMSE table: replay_report.h) -----------
// The gnuplot script (relative file names only) that draws
// end_effector.{png,svg} and bases_xy.{png,svg} from the CSV files.
std::string ReplayPlotScript(const Model& model, const ReplayResult& result, const std::string& path_name);

// Writes DIR/replay.gnuplot and runs it in DIR. Returns the plots written;
// `warning` is set when gnuplot is missing or fails.
std::vector<std::string> PlotReplay(const std::string& dir, const Model& model, const ReplayResult& result,
                                    const std::string& path_name, std::string* warning);

// ---- workspace -----------------------------------------------------------
// DIR/workspace_slice.dat (first two sampled components, reachable,
// sigma_min; a grid's other sampled components at the value nearest home)
// and DIR/reachability.png, DIR/sigma_min.png. Creates DIR (UsageError when
// it cannot). Returns the files written; `warning` is set when gnuplot is
// missing (then only the data is written) or fails.
std::vector<std::string> PlotWorkspaceMaps(const Model& model, const WorkspaceOptions& options,
                                           const WorkspaceResult& result, const std::string& dir,
                                           std::string* warning);

}  // namespace ccma::cli

#endif  // CCMA_APPS_PLOTS_H_
