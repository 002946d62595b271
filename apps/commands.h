// The `ccma` sub-commands: one registry (commands.cc) names each command, its
// synopsis, what it does and the flags it accepts; `ccma SUB --help` is made
// from it and from the flags' own descriptions (units) and defaults. Each
// command parses its flags with ParseCommandFlags, prints one JSON document
// on stdout and returns the exit status; errors are thrown (UsageError,
// ModelError, std::invalid_argument -> 2, anything else -> 1) and reported by
// main.cc.
#ifndef CCMA_APPS_COMMANDS_H_
#define CCMA_APPS_COMMANDS_H_

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ccma/ccma.h"

namespace ccma::cli {

struct Command {
  std::string name;
  std::string summary;      // what it does, one line of `ccma --help`
  std::string synopsis;     // the usage line(s)
  std::string description;  // what it does and prints
  std::vector<std::string> flags;  // accepted flags, in help order
  int (*run)(const std::vector<std::string>& args);
  // What a shared flag (--from, --out, ...) means for this command, with its
  // unit in brackets: replaces the flag's own (generic) description in
  // `ccma NAME --help`, so that no command describes another's use of it.
  std::map<std::string, std::string> flag_help = {};
};

// Every sub-command, in help order.
const std::vector<Command>& Commands();
// The registry entry of `name`; throws std::logic_error for an unknown one.
const Command& CommandNamed(const std::string& name);
// `ccma SUB --help`: synopsis, description and every flag with its unit and default.
std::string CommandHelp(const Command& command);
// `ccma --help`: one line per command ("  ccma NAME  summary"), then how to
// get a command's own help.
std::string GlobalHelp();
// "ccma 0.1.0 (Release; Ceres 2.1.0, Eigen 3.4.0)".
std::string VersionLine();

// Parses `args` against the registry's flags of `command` (cli.h ParseFlags).
void ParseCommandFlags(const std::vector<std::string>& args, const std::string& command);

int RunCheck(const std::vector<std::string>& args);
int RunSimulate(const std::vector<std::string>& args);
int RunControl(const std::vector<std::string>& args);
int RunTrajectory(const std::vector<std::string>& args);
int RunPlan(const std::vector<std::string>& args);
int RunStatics(const std::vector<std::string>& args);
int RunDynamics(const std::vector<std::string>& args);
// `ccma dynamics`' entry in Commands() (apps/dynamics_command.cc: with its code).
Command DynamicsCommand();
// `ccma retime` (apps/retime_command.cc).
int RunRetime(const std::vector<std::string>& args);
Command RetimeCommand();
int RunGenerate(const std::vector<std::string>& args);
int RunImport(const std::vector<std::string>& args);
int RunBench(const std::vector<std::string>& args);
int RunReplay(const std::vector<std::string>& args);
int RunView(const std::vector<std::string>& args);
Command ViewCommand();  // (apps/view_command.cc, with its flags)
int RunWorkspace(const std::vector<std::string>& args);
int RunDesign(const std::vector<std::string>& args);
int RunExport(const std::vector<std::string>& args);

// The control flags (method, max_step_m, max_step_rad, lambda) as options;
// throws UsageError when ControlOptions::IsValid says no.
ControlOptions ControlOptionsFromFlags();
// The bases' pose noise of --mocap_noise_m, --mocap_noise_rad: the replay's
// defaults unless given (apps/statics_command.cc); UsageError above 1.
BasePoseNoise PoseNoiseFromFlags();

// Singularity-aware control and redundancy resolution (secondary_flags.cc):
// the flags' names (accepted by control and trajectory),
// their values checked and applied to options->secondary (UsageError naming
// the flag; the JSON's "secondary": documents/json_values.h SecondaryJson).
const std::vector<std::string>& SecondaryFlagNames();
void ApplySecondaryFlags(ControlOptions* options);

// Loads the model, printing its warnings (unknown keys, implausible magnitudes) on stderr.
Model LoadModelOrThrow(const std::string& path);
// The --waypoints file, its errors turned into UsageError (exit 2).
std::vector<Waypoint> WaypointsFlag(const std::string& command);
// --controls parsed and checked against the model (count, range), or its home controls.
Eigen::VectorXd ControlsFlagOrHome(const Model& model);
// --wrench parsed and checked (6 numbers, each in [-1e6, 1e6]), or none.
ExternalWrench WrenchFlag();

}  // namespace ccma::cli

#endif  // CCMA_APPS_COMMANDS_H_
