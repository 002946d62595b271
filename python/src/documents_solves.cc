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

// apps/control_command.cc CheckReproducibleFromHome: idle motions (a rod
// spinning about its axis) are not branches (analyses/configuration_difference.h).
const nlohmann::json& FromHome(const ControlSolution& s) {
  if (s.from_home) return *s.from_home;
  const Model& model = *s.model;
  ForwardProblem from_home(model);
  const ForwardResult r = from_home.Assemble(s.controls);
  const ConfigurationDifference difference = CompareConfigurations(model, s.state, from_home.state(), s.controls);
  const bool same = r.assembled && difference.same;
  if (!same) {
    s.from_home_warning = "these controls, simulated from home (ccma simulate --controls=...), assemble to another "
                          "configuration (end-effector " + FormatG(difference.end_effector_distance) + " m away" +
                          (r.assembled ? "" : ", not assembled") +
                          "): the mechanism has several assembly branches here; reproduce this result exactly with "
                          "ccma simulate --from=<this JSON>";
  }
  nlohmann::json idle = nlohmann::json::array();
  for (const int b : difference.idle_bodies) idle.push_back(model.bodies[b].name);
  s.from_home = nlohmann::json{{"reproducible", same},
                               {"end_effector_distance_m", difference.end_effector_distance},
                               {"end_effector_rotation_rad", difference.end_effector_rotation},
                               {"max_state_difference", difference.max_state_difference},
                               {"idle_bodies", idle}};
  return *s.from_home;
}

std::string ControlWarning(const ControlSolution& s) {
  FromHome(s);
  std::string warning = s.warning;
  if (!s.from_home_warning.empty()) JoinWarning(s.from_home_warning, &warning);
  return warning;
}

nlohmann::json ConditioningJson(const ControlResult& r) {
  return {{"dG_ds_pivot_ratio", r.rcond},
          {"min_dG_ds_pivot_ratio_on_path", r.min_rcond},
          {"min_singular_value_dX_du", r.min_singular_value_dX_du},
          {"min_singular_value_dX_du_on_path", r.min_singular_value_dX_du_on_path}};
}

nlohmann::json SecondaryJson(const ControlOptions::Secondary& secondary, int null_space_steps, double objective) {
  nlohmann::json out = {{"null_space_steps", null_space_steps},
                        {"singularity_weight", secondary.singularity_weight},
                        {"singularity_threshold", secondary.singularity_threshold},
                        {"pivot_weight", secondary.pivot_weight},
                        {"pivot_threshold", secondary.pivot_threshold},
                        {"spread_weight", secondary.spread_weight},
                        {"clearance_m", secondary.clearance_m},
                        {"travel_weight", secondary.travel_weight}};
  if (std::isfinite(objective)) out["objective"] = objective;
  return out;
}

nlohmann::json ControlDocument(const ControlSolution& s) {
  const Model& model = *s.model;
  nlohmann::json out;
  out["model"] = model.name;
  out["method"] = s.method;
  out["converged"] = s.converged;
  out["assembled"] = s.assembled;
  out["steps"] = s.steps;
  out["iterations"] = s.iterations;
  out["forward_solves"] = s.forward_solves;
  out["branch_jumps_rejected"] = s.branch_jumps_rejected;
  out["objective"] = s.objective;
  out["error"] = s.error;
  out["residual_energy"] = s.residual_energy;
  out["max_step_residual_energy"] = s.max_step_residual_energy;
  out["conditioning"] = ConditioningJson(s);
  if (s.secondary.enabled()) out["secondary"] = SecondaryJson(s.secondary, s.null_space_steps, s.secondary_objective);
  out["solve_time_ms"] = s.solve_time_ms;
  out["target"] = ToJson(Eigen::VectorXd(s.target));
  out["controls"] = ToJson(s.controls);
  out["end_effector"] = ToJson(s.end_effector);
  out["bodies"] = BodiesToJson(model, s.state);
  out["joints"] = JointsToJson(model, s.state);
  out["limits_violated"] = LimitsViolatedToJson(model, s.state);
  if (s.compensation) {
    documents::AddCompensationJson(model, s.rigid_end_effector, *s.compensation, &out);
    PutClearance(model, s.compensation->loaded.state, &out);
  } else {
    PutClearance(model, s.state, &out);
  }
  out["from_home"] = FromHome(s);
  const std::string warning = ControlWarning(s);
  if (!warning.empty()) out["warning"] = warning;
  return out;
}

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
    out["secondary"] = SecondaryJson(options.secondary, path.null_space_steps, path.secondary_objective);
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
