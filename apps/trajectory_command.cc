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
#include "documents/trajectory_csv.h"
#include "apps/work_bound.h"
#include "problems/compensated_trajectory.h"

namespace ccma::cli {

namespace {

// What the rows say about the whole path: conditioning (steps that could not
// form it report 0), secondary objectives, the last row's configuration.
struct TrajectoryTally {
  double min_sigma = std::numeric_limits<double>::infinity();
  double min_rcond = std::numeric_limits<double>::infinity();
  int null_space_steps = 0;
  double secondary_objective = 0;
  State last_state;  // the last row's

  void Add(const TrajectoryStep& s) {
    min_sigma = std::min(min_sigma, s.result.min_singular_value_dX_du);
    min_rcond = std::min(min_rcond, s.result.rcond);
    null_space_steps += s.result.null_space_steps;
    secondary_objective = s.result.secondary_objective;
    last_state = s.state;
  }
};

nlohmann::json PathJson(const Model& model, const ControlOptions& options, const TrajectoryResult& result,
                        const TrajectoryTally& tally, size_t waypoints) {
  nlohmann::json out;
  out["model"] = model.name;
  out["method"] = FLAGS_method;
  out["converged"] = result.converged;
  out["waypoints"] = waypoints;
  out["steps"] = result.steps;
  out["iterations"] = result.iterations;
  out["max_residual_energy"] = result.max_residual_energy;
  out["max_error"] = result.max_error;
  if (result.steps > 0) {
    out["conditioning"] = {{"min_singular_value_dX_du_on_path", tally.min_sigma},
                           {"min_dG_ds_pivot_ratio_on_path", tally.min_rcond}};
  }
  if (options.secondary.enabled()) {
    out["secondary"] = SecondaryJson(options.secondary, tally.null_space_steps, tally.secondary_objective);
  }
  out["solve_time_ms"] = result.solve_time_ms;
  return out;
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
  if (!FLAGS_wrench.empty() && !FLAGS_compensate) throw UsageError("--wrench: only with --compensate (the loads it compensates)");

  ControlProblem control(model, options);
  control.SetControls(start);
  OutputFile file(out_path, "out");  // nothing half-written; links and devices kept
  documents::TrajectoryCsv csv(model, file.stream());
  TrajectoryTally tally;
  tally.last_state = control.forward().state();
  // Work bounded by its cost (--max_minutes): the path's steps timed as they are made.
  long steps = 0;
  try {
    steps = CheckPathStepCount(control, waypoints);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("ccma trajectory: ") + e.what());
  }
  WorkEstimate estimate(CommandWorkEstimate("trajectory", FLAGS_compensate ? "compensated path steps" : "path steps",
                                            false),
                        steps);
  long done = 0;
  const auto on_step = [&](const TrajectoryStep& s) {
    csv.Write(s);
    tally.Add(s);
    estimate.Update(++done);
  };
  CompensatedPath compensated;
  const TrajectoryResult result = FLAGS_compensate
                                      ? FollowWaypointsCompensated(control, waypoints, WrenchFlag(), on_step, &compensated)
                                      : FollowWaypoints(control, waypoints, on_step);
  file.Commit();

  nlohmann::json out = PathJson(model, options, result, tally, waypoints.size());
  out["out"] = out_path;
  out["controls"] = ToJson(control.controls());
  // The configuration at the end: the loaded one with --compensate.
  const State& final_state = FLAGS_compensate ? tally.last_state : control.forward().state();
  out["end_effector"] = ToJson(ComputeEndEffectorPose(model, final_state));
  if (FLAGS_compensate) out["compensation"] = {{"rounds", compensated.rounds}, {"max_miss", compensated.max_miss}};
  AddClearance(model, final_state, "trajectory", &out);
  const ClearanceSummary& path_clearance = csv.min_clearance();
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
