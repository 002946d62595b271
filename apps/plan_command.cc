// `ccma plan --model=FILE --waypoints=FILE.csv --out=FILE.csv [plan flags] [control flags]`:
// the controls of all the steps of a waypoint path optimised together
// (problems/plan.h), from the greedy trajectory; the same CSV as trajectory.
#include <iostream>
#include <memory>
#include <string>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "ccma/internal/format.h"
#include "documents/plan_document.h"
#include "documents/trajectory_csv.h"

DEFINE_int32(plan_iterations, 200, "plan: Gauss-Newton iterations of the whole path, [1, 10000] [count]");
DEFINE_double(path_weight, 1e-2,
              "plan: weight of the end-effector error between waypoints (the straight path), [0, 1e6] [1]");
DEFINE_double(smoothness_weight, 1.0, "plan: weight of the bases' second differences, [0, 1e6] [1]");
DEFINE_double(travel_weight, 1e-2, "plan: weight of the bases' step lengths squared, [0, 1e6] [1]");
DEFINE_double(plan_time_s, 120,
              "plan: wall-clock bound on the detour seeds and the optimisation, [0, 1e6]; when "
              "reached the plan is finished from where it is and the JSON's stopped_by says so [s]");

namespace ccma::cli {
namespace {

// Seconds between two progress lines of a long plan.
constexpr double kProgressEvery = 10.0;

PlanOptions PlanOptionsFromFlags() {
  PlanOptions options;
  const PlanCommandSettings settings{FLAGS_path_weight, FLAGS_smoothness_weight, FLAGS_travel_weight,
                                     FLAGS_plan_iterations, FLAGS_plan_time_s};
  if (std::string why; !PlanOptionsFromSettings(settings, &options, &why)) throw UsageError("ccma plan: --" + why);
  // A line on stderr at least every kProgressEvery seconds of a long plan.
  auto last = std::make_shared<double>(0.0);
  options.on_progress = [last](const PlanProgress& p) {
    if (p.elapsed_s - *last < kProgressEvery) return;
    *last = p.elapsed_s;
    std::cerr << "ccma plan: " << p.phase << " " << p.done << "/" << p.total << " after "
              << FormatG(p.elapsed_s, 3) << " s\n";
  };
  return options;
}

// A note on stderr when the time bound stopped the optimisation.
void NoteTheTimeBound(const PlanResult& result) {
  if (result.stopped_by == "plan_time_s") {
    std::cerr << "ccma plan: note: the optimisation stopped at the time bound --plan_time_s="
              << FormatG(FLAGS_plan_time_s) << " after " << result.iterations
              << " iterations; the plan was finished from there\n";
  }
}

}  // namespace

int RunPlan(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "plan");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "plan"));
  const std::vector<Waypoint> waypoints = WaypointsFlag("plan");
  const std::string out_path = RequireFlag(FLAGS_out, "out", "plan");
  const PlanOptions plan_options = PlanOptionsFromFlags();
  const ControlOptions options = ControlOptionsFromFlags();
  if (options.method != ControlMethod::kLevenbergMarquardt) throw UsageError("ccma plan: --method must be lm");
  for (const MobileBase& base : model.mobile_bases) {
    if (base.type == BaseType::kDifferential) {
      throw UsageError("ccma plan: model '" + model.name + "' has differential bases, which plan does not handle yet "
                       "(use ccma trajectory)");
    }
  }
  ControlProblem control(model, options);
  control.SetControls(ControlsFlagOrHome(model));
  const PlanResult result = PlanTrajectory(control, waypoints, plan_options);
  OutputFile file(out_path, "out");
  documents::TrajectoryCsv csv(model, file.stream());
  for (const TrajectoryStep& step : result.steps) csv.Write(step);
  file.Commit();

  NoteTheTimeBound(result);
  documents::Document document = documents::PlanDocument(control, result, waypoints.size(), csv.min_clearance());
  document.json["out"] = out_path;
  PrintDocument(document, "plan");
  return 0;
}

}  // namespace ccma::cli
