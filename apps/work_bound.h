// The commands whose work is bounded by its estimated cost (`ccma workspace`,
// `ccma design`; docs/security.md, "Work bounded by its cost"): the options
// of their WorkEstimate (analyses/work_estimate.h) from --max_minutes, lines
// said on stderr.
#ifndef CCMA_APPS_WORK_BOUND_H_
#define CCMA_APPS_WORK_BOUND_H_

#include <string>

#include "analyses/work_estimate.h"

namespace ccma::cli {

// For `ccma COMMAND` counting `noun`: who "ccma COMMAND", the bound
// --max_minutes (UsageError outside (0, 10080]), lines on stderr. With
// `terminal_bar` the command draws a bar of its own on a terminal: there
// the estimate is said on a line of its own and the progress lines left out.
WorkEstimateOptions CommandWorkEstimate(const std::string& command, const std::string& noun, bool terminal_bar);

}  // namespace ccma::cli

#endif  // CCMA_APPS_WORK_BOUND_H_
