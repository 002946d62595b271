// `ccma trajectory --model=FILE --waypoints=FILE.csv --out=FILE.csv [control flags]`:
// follow end-effector waypoints in small steps; one CSV row per step.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"

namespace ccma::cli {
namespace {

// The header: every name carries its unit (_s, _m, _rad, _m2, _ms).
void WriteHeader(const Model& model, std::ostream& csv) {
  // Clearance columns only with collision geometry (model_format.md).
  const std::string clearance = model.collision.enabled ? ",clearance_m,clearance_pair" : "";
  csv << "time_s,target_x_m,target_y_m,target_z_m,target_roll_rad,target_pitch_rad,target_yaw_rad,"
         "x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad";
  for (int k = 0; k < model.num_bases(); ++k) {
    csv << ",u" << k << "_x_m,u" << k << "_y_m,u" << k << "_theta_rad";
  }
  auto unit = [](const Joint& j) { return j.type == JointType::kRevolute ? "_rad" : "_m"; };
  for (const Joint& joint : model.joints) {
    if (joint.actuated) csv << ",u_" << joint.name << unit(joint);
  }
  for (const Joint& joint : model.joints) {
    if (joint.has_coordinate()) csv << ",q_" << joint.name << unit(joint);
  }
  csv << ",residual_energy_m2,error_m_or_rad,iterations,solve_time_ms,reached,limits_violated" << clearance << "\n";
}

// The row's clearance cells: the smallest clearance [m] and its pair "a|b"
// (names never hold '|'); both empty when no pair is checked.
std::string ClearanceCells(const ClearanceSummary& c) {
  if (!c.any) return ",,";
  std::ostringstream cells;
  cells << std::setprecision(17) << "," << c.min << "," << c.a << "|" << c.b;
  return cells.str();
}

void WriteRow(const Model& model, const ClearanceSummary* clearance, const State& state, const TrajectoryStep& s,
              std::ostream& csv) {
  csv << s.time;
  for (int i = 0; i < 3; ++i) csv << "," << s.target.position[i];
  for (int i = 0; i < 3; ++i) csv << "," << s.target.rpy[i];
  for (int i = 0; i < 3; ++i) csv << "," << s.reached.position[i];
  for (int i = 0; i < 3; ++i) csv << "," << s.reached.rpy[i];
  for (int i = 0; i < s.controls.size(); ++i) csv << "," << s.controls[i];
  int violated = 0;
  for (const JointCoordinateReport& r : JointCoordinates(model, state)) {
    csv << "," << r.q;
    violated += !r.within_limits;
  }
  csv << "," << s.result.residual_energy << "," << s.result.error << "," << s.result.iterations << ","
      << s.result.time_ms << "," << (s.result.reached ? 1 : 0) << "," << violated
      << (clearance != nullptr ? ClearanceCells(*clearance) : "") << "\n";
}

}  // namespace

int RunTrajectory(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "trajectory");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "trajectory"));
  const std::vector<Waypoint> waypoints = WaypointsFlag("trajectory");
  const std::string out_path = RequireFlag(FLAGS_out, "out", "trajectory");
  ControlOptions options = ControlOptionsFromFlags();
  ApplySecondaryFlags(&options);
  const Eigen::VectorXd start = ControlsFlagOrHome(model);

  ControlProblem control(model, options);
  control.SetControls(start);
  const CollisionModel collision(model);
  ClearanceSummary path_clearance;  // the smallest over the rows
  OutputFile file(out_path, "out");  // nothing half-written; links and devices kept
  std::ostream& csv = file.stream();
  csv << std::setprecision(17);
  WriteHeader(model, csv);
  // Conditioning along the path (steps that could not form it report 0).
  double min_sigma = std::numeric_limits<double>::infinity();
  double min_rcond = std::numeric_limits<double>::infinity();
  int null_space_steps = 0;
  double secondary_objective = 0;
  const TrajectoryResult result = FollowWaypoints(control, waypoints, [&](const TrajectoryStep& s) {
    ClearanceSummary clearance;
    if (collision.enabled()) {
      clearance = MinimumClearance(collision, s.state);
      if (clearance.any && (!path_clearance.any || clearance.min < path_clearance.min)) path_clearance = clearance;
    }
    WriteRow(model, collision.enabled() ? &clearance : nullptr, s.state, s, csv);
    min_sigma = std::min(min_sigma, s.result.min_singular_value_dX_du);
    min_rcond = std::min(min_rcond, s.result.rcond);
    null_space_steps += s.result.null_space_steps;
    secondary_objective = s.result.secondary_objective;
  });
  file.Commit();

  nlohmann::json out;
  out["model"] = model.name;
  out["method"] = FLAGS_method;
  out["converged"] = result.converged;
  out["waypoints"] = waypoints.size();
  out["steps"] = result.steps;
  out["iterations"] = result.iterations;
  out["max_residual_energy"] = result.max_residual_energy;
  out["max_error"] = result.max_error;
  if (result.steps > 0) {
    out["conditioning"] = {{"min_singular_value_dX_du_on_path", min_sigma},
                           {"min_dG_ds_pivot_ratio_on_path", min_rcond}};
  }
  if (options.secondary.enabled()) {
    out["secondary"] = SecondaryJson(options.secondary, null_space_steps, secondary_objective);
  }
  out["solve_time_ms"] = result.solve_time_ms;
  out["out"] = out_path;
  out["controls"] = ToJson(control.controls());
  out["end_effector"] = ToJson(control.forward().end_effector());
  AddClearance(model, control.forward().state(), "trajectory", &out);
  if (path_clearance.any) {
    out["clearance"]["min_on_path"] = path_clearance.min;
    out["clearance"]["pair_on_path"] = {path_clearance.a, path_clearance.b};
  }
  if (!result.warning.empty()) {
    out["warning"] = result.warning;
    std::cerr << "ccma trajectory: warning: " << result.warning << "\n";
  }
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
