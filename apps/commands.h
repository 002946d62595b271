// The `ccma` sub-commands. Each parses its own flags, prints one JSON
// document on stdout and returns the exit status; errors are thrown
// (UsageError / ModelError -> 2, anything else -> 1) and reported by main.
#ifndef CCMA_APPS_COMMANDS_H_
#define CCMA_APPS_COMMANDS_H_

#include <set>
#include <string>
#include <vector>

#include "ccma/ccma.h"

namespace ccma::cli {

int RunCheck(const std::vector<std::string>& args);
int RunSimulate(const std::vector<std::string>& args);
int RunControl(const std::vector<std::string>& args);
int RunTrajectory(const std::vector<std::string>& args);
int RunGenerate(const std::vector<std::string>& args);
int RunBench(const std::vector<std::string>& args);
int RunReplay(const std::vector<std::string>& args);

// Flags shared by control and trajectory, and the options they make.
extern const std::set<std::string> kControlFlags;
ControlOptions ControlOptionsFromFlags();

// Loads the model, printing its warnings (unknown keys) on stderr.
Model LoadModelOrThrow(const std::string& path);
// The --waypoints file, its errors turned into UsageError (exit 2).
std::vector<Waypoint> WaypointsFlag(const std::string& command);
// --controls parsed and checked against the model, or its home controls.
Eigen::VectorXd ControlsFlagOrHome(const Model& model);

}  // namespace ccma::cli

#endif  // CCMA_APPS_COMMANDS_H_
