// The documents of the solving commands: simulate, control, trajectory, plan
// (python/src/documents.h).
#include <algorithm>
#include <cmath>

#include "analyses/configuration_difference.h"
#include "documents/json_values.h"
#include "ccma/internal/format.h"
#include "python/src/documents.h"

namespace ccma::python {

using documents::BodiesToJson;
using documents::ClearanceToJson;
using documents::JointsToJson;
using documents::LimitsViolatedToJson;
using documents::ToJson;

namespace {

// The clearance of the configuration, when the model has collision geometry
// (json_output.h AddClearance, without its stderr line).
void PutClearance(const Model& model, const State& s, nlohmann::json* out) {
  const nlohmann::json clearance = ClearanceToJson(model, s);
  if (!clearance.is_null()) (*out)["clearance"] = clearance;
}

}  // namespace

void AddPathClearance(const ClearanceSummary& path, nlohmann::json* out) {
  if (!path.any) return;
  (*out)["clearance"]["min_on_path"] = path.min;
  (*out)["clearance"]["pair_on_path"] = {path.a, path.b};
}

nlohmann::json TrajectoryDocument(const ControlProblem& control, const TrajectoryResult& r, std::size_t waypoints,
                                  const PathSummary& path) {
  const Model& model = control.forward().model();
  const ControlOptions& options = control.options();
  nlohmann::json out;
  out["model"] = model.name;
  out["method"] = options.method == ControlMethod::kBfgs ? "bfgs" : "lm";
  out["converged"] = r.converged;
  out["waypoints"] = waypoints;
  out["steps"] = r.steps;
  out["iterations"] = r.iterations;
  out["max_residual_energy"] = r.max_residual_energy;
  out["max_error"] = r.max_error;
  if (r.steps > 0) {
    out["conditioning"] = {{"min_singular_value_dX_du_on_path", path.min_sigma},
                           {"min_dG_ds_pivot_ratio_on_path", path.min_rcond}};
  }
  if (options.secondary.enabled()) {
    out["secondary"] = documents::SecondaryJson(options.secondary, path.null_space_steps, path.secondary_objective);
  }
  out["solve_time_ms"] = r.solve_time_ms;
  out["controls"] = ToJson(control.controls());
  const State& final_state = path.loaded_state ? *path.loaded_state : control.forward().state();
  out["end_effector"] = ToJson(ComputeEndEffectorPose(model, final_state));
  if (path.compensation) {
    out["compensation"] = {{"rounds", path.compensation->rounds}, {"max_miss", path.compensation->max_miss}};
  }
  PutClearance(model, final_state, &out);
  AddPathClearance(path.path_clearance, &out);
  if (!r.warning.empty()) out["warning"] = r.warning;
  return out;
}

namespace {

nlohmann::json MeasuresJson(const PathMeasures& m) {
  nlohmann::json j = {{"reached_waypoints", m.reached_waypoints}, {"travel_m", m.travel_m}};
  if (std::isfinite(m.min_clearance_m)) j["min_clearance_m"] = m.min_clearance_m;
  return j;
}

}  // namespace

nlohmann::json PlanDocument(const ControlProblem& control, const PlanResult& r, std::size_t waypoints,
                            const ClearanceSummary& path_clearance) {
  const Model& model = control.forward().model();
  nlohmann::json out;
  out["model"] = model.name;
  out["converged"] = r.converged;
  out["used"] = r.used_plan ? "plan" : "greedy";
  out["waypoints"] = waypoints;
  out["steps"] = r.steps.size();
  out["iterations"] = r.iterations;
  documents::AddPlanFinishing(r, &out);
  out["greedy"] = MeasuresJson(r.greedy);
  out["plan"] = MeasuresJson(r.plan);
  out["solve_time_ms"] = r.solve_time_ms;
  out["controls"] = ToJson(control.controls());
  out["end_effector"] = ToJson(control.forward().end_effector());
  PutClearance(model, control.forward().state(), &out);
  AddPathClearance(path_clearance, &out);
  std::string warning;
  if (!r.used_plan) warning = "kept the greedy trajectory: " + r.note;
  if (!r.converged) {
    JoinWarning(std::string("not every waypoint was reached") +
             (r.greedy_warning.empty() ? "" : " (greedy: " + r.greedy_warning + ")"),
         &warning);
  }
  if (!warning.empty()) out["warning"] = warning;
  return out;
}

}  // namespace ccma::python
