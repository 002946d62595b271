#include "documents/control_document.h"

#include <utility>

#include "analyses/configuration_difference.h"
#include "ccma/internal/format.h"
#include "documents/json_values.h"

namespace ccma::documents {

ControlSolution MakeControlSolution(const ControlProblem& control, const ControlResult& result,
                                    const PoseTarget& target, std::optional<CompensatedResult> compensation) {
  ControlSolution s;
  static_cast<ControlResult&>(s) = result;
  const Model& model = control.forward().model();
  s.compensation = std::move(compensation);
  if (s.compensation) {
    static_cast<ControlResult&>(s) = s.compensation->control;
    if (!s.compensation->warning.empty()) JoinWarning("--compensate: " + s.compensation->warning, &s.warning);
    s.converged = s.compensation->converged;
    s.error = s.compensation->miss;
  }
  s.target << target.position, target.rpy;
  s.controls = control.controls();
  s.rigid_end_effector = control.forward().end_effector();
  s.end_effector =
      s.compensation ? ComputeEndEffectorPose(model, s.compensation->loaded.state) : s.rigid_end_effector;
  s.model = &model;
  s.state = control.forward().state();
  s.method = control.options().method == ControlMethod::kBfgs ? "bfgs" : "lm";
  s.secondary = control.options().secondary;
  return s;
}

const nlohmann::json& FromHome(const ControlSolution& s) {
  if (s.from_home) return *s.from_home;
  const Model& model = *s.model;
  const FromHomeCheck check = CheckFromHome(model, s.state, s.controls);
  const ConfigurationDifference& difference = check.difference;
  if (!check.reproducible) {
    s.from_home_warning = "these controls, simulated from home (ccma simulate --controls=...), assemble to another "
                          "configuration (end-effector " + FormatG(difference.end_effector_distance) + " m away" +
                          (check.assembled ? "" : ", not assembled") +
                          "): the mechanism has several assembly branches here; reproduce this result exactly with "
                          "ccma simulate --from=<this JSON>";
  }
  nlohmann::json idle = nlohmann::json::array();
  for (const int b : difference.idle_bodies) idle.push_back(model.bodies[b].name);
  s.from_home = nlohmann::json{{"reproducible", check.reproducible},
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

Document ControlDocument(const ControlSolution& s) {
  const Model& model = *s.model;
  Document doc;
  nlohmann::json& out = doc.json;
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
  if (s.compensation) AddCompensationJson(model, s.rigid_end_effector, *s.compensation, &out);
  AddClearance(model, s.compensation ? s.compensation->loaded.state : s.state, &out, &doc.warnings);
  out["from_home"] = FromHome(s);
  const std::string warning = ControlWarning(s);
  doc.Warn(warning);
  return doc;
}

}  // namespace ccma::documents
