// `ccma trajectory --model=FILE --waypoints=FILE.csv --out=FILE.csv [control flags]`:
// follow end-effector waypoints in small steps; one CSV row per step.
#include <string>
#include <vector>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "apps/work_bound.h"
#include "documents/trajectory_csv.h"
#include "documents/trajectory_document.h"
#include "problems/compensated_trajectory.h"

namespace ccma::cli {

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
  documents::TrajectorySolution solution;
  solution.control = &control;
  solution.waypoints = waypoints.size();
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
    solution.tally.Add(s);
    estimate.Update(++done);
  };
  if (FLAGS_compensate) solution.compensation.emplace();
  solution.result = FLAGS_compensate
                        ? FollowWaypointsCompensated(control, waypoints, WrenchFlag(), on_step, &*solution.compensation)
                        : FollowWaypoints(control, waypoints, on_step);
  file.Commit();
  solution.path_clearance = csv.min_clearance();
  documents::Document document = documents::TrajectoryDocument(solution);
  document.json["out"] = out_path;
  PrintDocument(document, "trajectory");
  return 0;
}

}  // namespace ccma::cli
