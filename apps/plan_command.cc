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
#include "documents/trajectory_csv.h"
#include "ccma/internal/format.h"

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
  options.path_weight = FLAGS_path_weight;
  options.smoothness_weight = FLAGS_smoothness_weight;
  options.travel_weight = FLAGS_travel_weight;
  options.max_iterations = FLAGS_plan_iterations;
  options.max_seconds = FLAGS_plan_time_s;
  std::string why;
  if (!options.IsValid(&why)) {
    if (why.rfind("max_iterations", 0) == 0) why.replace(0, 14, "plan_iterations");
    if (why.rfind("max_seconds", 0) == 0) why.replace(0, 11, "plan_time_s");
    throw UsageError("ccma plan: --" + why);
  }
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

nlohmann::json MeasuresJson(const PathMeasures& m) {
  nlohmann::json j = {{"reached_waypoints", m.reached_waypoints}, {"travel_m", m.travel_m}};
  if (std::isfinite(m.min_clearance_m)) j["min_clearance_m"] = m.min_clearance_m;
  return j;
}

// How the optimisation stopped and the plan was finished (JSON stopped_by,
// finishing, shortfall); a note on stderr when the time bound stopped it.
void AddFinishing(const PlanResult& result, nlohmann::json* out) {
  AddPlanFinishing(result, out);
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

  nlohmann::json out;
  out["model"] = model.name;
  out["converged"] = result.converged;
  out["used"] = result.used_plan ? "plan" : "greedy";
  out["waypoints"] = waypoints.size();
  out["steps"] = result.steps.size();
  out["iterations"] = result.iterations;
  AddFinishing(result, &out);
  out["greedy"] = MeasuresJson(result.greedy);
  out["plan"] = MeasuresJson(result.plan);
  out["solve_time_ms"] = result.solve_time_ms;
  out["out"] = out_path;
  out["controls"] = ToJson(control.controls());
  out["end_effector"] = ToJson(control.forward().end_effector());
  AddClearance(model, control.forward().state(), "plan", &out);
  if (csv.min_clearance().any) {
    out["clearance"]["min_on_path"] = csv.min_clearance().min;
    out["clearance"]["pair_on_path"] = {csv.min_clearance().a, csv.min_clearance().b};
  }
  std::string warning;
  if (!result.used_plan) warning = "kept the greedy trajectory: " + result.note;
  if (!result.converged) {
    warning += std::string(warning.empty() ? "" : "; ") + "not every waypoint was reached" +
               (result.greedy_warning.empty() ? "" : " (greedy: " + result.greedy_warning + ")");
  }
  if (!warning.empty()) {
    out["warning"] = warning;
    std::cerr << "ccma plan: warning: " << warning << "\n";
  }
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
