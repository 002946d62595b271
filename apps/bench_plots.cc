// `ccma bench --out=DIR`: the convergence plots (apps/plots.h).
#include <fstream>
#include <sstream>

#include "apps/plots.h"

namespace ccma::cli {

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

}  // namespace ccma::cli
