// `ccma`: the command-line tool (contract: shared/cli.md).
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <gflags/gflags.h>
#include <glog/logging.h>

#include "apps/cli.h"
#include "apps/commands.h"

DEFINE_string(model, "", "model file (YAML or JSON, see model_format.md)");
DECLARE_string(waypoints);
DEFINE_string(controls, "",
              "comma-separated controls, 3 per mobile base: x [m], y [m], theta [rad]");

namespace ccma::cli {

Model LoadModelOrThrow(const std::string& path) {
  std::vector<std::string> warnings;
  Model model = LoadModel(path, &warnings);
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  return model;
}

std::vector<Waypoint> WaypointsFlag(const std::string& command) {
  try {
    return LoadWaypoints(RequireFlag(FLAGS_waypoints, "waypoints", command));
  } catch (const WaypointError& e) {
    throw UsageError("ccma " + command + ": " + e.what());
  }
}

Eigen::VectorXd ControlsFlagOrHome(const Model& model) {
  if (FLAGS_controls.empty()) return model.home_controls();
  const Eigen::VectorXd u = ParseNumberList(FLAGS_controls, "controls");
  if (u.size() != model.num_controls()) {
    throw UsageError("--controls: model '" + model.name + "' has " +
                     std::to_string(model.num_bases()) + " mobile bases, so " +
                     std::to_string(model.num_controls()) + " controls; got " +
                     std::to_string(u.size()));
  }
  return u;
}

}  // namespace ccma::cli

namespace {

const char kUsage[] =
    "ccma: simulation and kinematic control of Constrained Collaborative Mobile Agents\n"
    "\n"
    "usage:\n"
    "  ccma check    --model=FILE\n"
    "  ccma simulate --model=FILE [--controls=u0,u1,...]\n"
    "  ccma control  --model=FILE --target=x,y,z,roll,pitch,yaw [--controls=...]\n"
    "                [--method=lm|bfgs] [--max_step_m=0.01] [--max_step_rad=0.005] [--lambda=0.5]\n"
    "  ccma trajectory --model=FILE --waypoints=FILE.csv --out=FILE.csv [control flags]\n"
    "  ccma generate --agents=N --out=FILE       (Stewart-like model with N bases)\n"
    "  ccma bench --model=FILE | --all | --scaling [--steps=N] [--seed=1] [--out=DIR]\n"
    "  ccma replay --model=FILE --waypoints=FILE.csv --out=DIR [--noise=default|none] [--seed=1]\n"
    "\n"
    "Results are one JSON document on stdout; diagnostics go to stderr.\n"
    "Exit status: 0 ok, 1 failure, 2 bad usage or bad model file.\n";

}  // namespace

int main(int argc, char** argv) {
  google::InitGoogleLogging(argv[0]);
  FLAGS_minloglevel = google::GLOG_ERROR;  // Ceres' own chatter stays quiet
  gflags::SetUsageMessage(kUsage);

  if (argc < 2) {
    std::cerr << kUsage;
    return 2;
  }
  const std::string command = argv[1];
  if (command == "--help" || command == "-h" || command == "help") {
    std::cout << kUsage;
    return 0;
  }
  const std::map<std::string, int (*)(const std::vector<std::string>&)> commands = {
      {"check", ccma::cli::RunCheck},
      {"simulate", ccma::cli::RunSimulate},
      {"control", ccma::cli::RunControl},
      {"trajectory", ccma::cli::RunTrajectory},
      {"generate", ccma::cli::RunGenerate},
      {"bench", ccma::cli::RunBench},
      {"replay", ccma::cli::RunReplay}};
  const auto it = commands.find(command);
  if (it == commands.end()) {
    std::cerr << "ccma: unknown command '" << command << "'\n\n" << kUsage;
    return 2;
  }
  const std::vector<std::string> args(argv + 2, argv + argc);
  for (const std::string& arg : args) {
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return 0;
    }
  }
  try {
    return it->second(args);
  } catch (const ccma::cli::UsageError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const ccma::ModelError& e) {
    std::cerr << "ccma " << command << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "ccma " << command << ": error: " << e.what() << "\n";
    return 1;
  }
}
