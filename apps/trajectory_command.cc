// `ccma trajectory --model=FILE --waypoints=FILE.csv --out=FILE.csv [control flags]`:
// follow end-effector waypoints in small steps; one CSV row per step.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iomanip>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/json_output.h"

DECLARE_string(model);
DECLARE_string(method);
DEFINE_string(waypoints, "", "waypoint CSV: time,x,y,z,roll,pitch,yaw (see ccma/waypoints.h)");
DEFINE_string(out, "", "output: CSV file (trajectory), model file (generate), folder (bench)");

namespace ccma::cli {

int RunTrajectory(const std::vector<std::string>& args) {
  std::set<std::string> allowed = kControlFlags;
  allowed.insert("waypoints");
  allowed.insert("out");
  ParseFlags(args, allowed, "trajectory");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "trajectory"));
  const std::vector<Waypoint> waypoints = WaypointsFlag("trajectory");
  const std::string out_path = RequireFlag(FLAGS_out, "out", "trajectory");
  const ControlOptions options = ControlOptionsFromFlags();
  const Eigen::VectorXd start = ControlsFlagOrHome(model);

  // Write to a temporary file and rename at the end: nothing half-written.
  const std::string temp_path = out_path + ".partial";
  std::ofstream csv(temp_path);
  if (!csv) throw UsageError("ccma trajectory: --out: cannot write '" + out_path + "'");
  csv << std::setprecision(17);
  csv << "time,target_x,target_y,target_z,target_roll,target_pitch,target_yaw,"
         "x,y,z,roll,pitch,yaw";
  for (int k = 0; k < model.num_bases(); ++k) {
    csv << ",u" << k << "_x,u" << k << "_y,u" << k << "_theta";
  }
  csv << ",residual_energy,error,iterations,solve_time_ms,reached\n";

  ControlProblem control(model, options);
  control.SetControls(start);
  const TrajectoryResult result = FollowWaypoints(control, waypoints, [&](const TrajectoryStep& s) {
    csv << s.time;
    for (int i = 0; i < 3; ++i) csv << "," << s.target.position[i];
    for (int i = 0; i < 3; ++i) csv << "," << s.target.rpy[i];
    for (int i = 0; i < 3; ++i) csv << "," << s.reached.position[i];
    for (int i = 0; i < 3; ++i) csv << "," << s.reached.rpy[i];
    for (int i = 0; i < s.controls.size(); ++i) csv << "," << s.controls[i];
    csv << "," << s.result.residual_energy << "," << s.result.error << "," << s.result.iterations
        << "," << s.result.time_ms << "," << (s.result.reached ? 1 : 0) << "\n";
  });
  csv.close();
  if (!csv || std::rename(temp_path.c_str(), out_path.c_str()) != 0) {
    std::remove(temp_path.c_str());
    throw std::runtime_error("could not write '" + out_path + "'");
  }

  nlohmann::json out;
  out["model"] = model.name;
  out["method"] = FLAGS_method;
  out["converged"] = result.converged;
  out["waypoints"] = waypoints.size();
  out["steps"] = result.steps;
  out["iterations"] = result.iterations;
  out["max_residual_energy"] = result.max_residual_energy;
  out["max_error"] = result.max_error;
  out["solve_time_ms"] = result.solve_time_ms;
  out["out"] = out_path;
  out["controls"] = ToJson(control.controls());
  out["end_effector"] = ToJson(control.forward().end_effector());
  if (!result.warning.empty()) {
    out["warning"] = result.warning;
    std::cerr << "ccma trajectory: warning: " << result.warning << "\n";
  }
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
