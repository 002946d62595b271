#include "apps/work_bound.h"

#include <unistd.h>

#include <iostream>

#include "apps/cli.h"
#include "apps/flags.h"
#include "ccma/internal/format.h"

namespace ccma::cli {

WorkEstimateOptions CommandWorkEstimate(const std::string& command, const std::string& noun, bool terminal_bar) {
  if (!(FLAGS_max_minutes > 0 && FLAGS_max_minutes <= kLargestMaxMinutes)) {
    throw UsageError("ccma " + command + ": --max_minutes must lie in (0, " + FormatG(kLargestMaxMinutes) +
                     "], got " + FormatG(FLAGS_max_minutes));
  }
  const bool bar = terminal_bar && isatty(STDERR_FILENO) != 0;
  WorkEstimateOptions options;
  options.who = "ccma " + command;
  options.noun = noun;
  options.max_minutes = FLAGS_max_minutes;
  options.raise_with = "--max_minutes";
  options.progress_lines = !bar;
  // Under a bar (which ends in '\r', not '\n') a line starts on a line of its own.
  options.say = [bar](const std::string& line) { std::cerr << (bar ? "\n" : "") << line << std::endl; };
  return options;
}

}  // namespace ccma::cli
