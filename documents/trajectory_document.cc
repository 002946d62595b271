#include "documents/trajectory_document.h"

#include <algorithm>

#include "documents/json_values.h"

namespace ccma::documents {

void PathTally::Add(const TrajectoryStep& step) {
  min_sigma = std::min(min_sigma, step.result.min_singular_value_dX_du);
  min_rcond = std::min(min_rcond, step.result.rcond);
  null_space_steps += step.result.null_space_steps;
  secondary_objective = step.result.secondary_objective;
  last_state = step.state;
}

void AddPathClearance(const ClearanceSummary& path, nlohmann::json* out) {
  if (!path.any) return;
  (*out)["clearance"]["min_on_path"] = path.min;
  (*out)["clearance"]["pair_on_path"] = {path.a, path.b};
}

Document TrajectoryDocument(const TrajectorySolution& s) {
  const ControlProblem& control = *s.control;
  const Model& model = control.forward().model();
  const ControlOptions& options = control.options();
  const TrajectoryResult& r = s.result;
  Document doc;
  nlohmann::json& out = doc.json;
  out["model"] = model.name;
  out["method"] = options.method == ControlMethod::kBfgs ? "bfgs" : "lm";
  out["converged"] = r.converged;
  out["waypoints"] = s.waypoints;
  out["steps"] = r.steps;
  out["iterations"] = r.iterations;
  out["max_residual_energy"] = r.max_residual_energy;
  out["max_error"] = r.max_error;
  if (r.steps > 0) {
    out["conditioning"] = {{"min_singular_value_dX_du_on_path", s.tally.min_sigma},
                           {"min_dG_ds_pivot_ratio_on_path", s.tally.min_rcond}};
  }
  if (options.secondary.enabled()) {
    out["secondary"] = SecondaryJson(options.secondary, s.tally.null_space_steps, s.tally.secondary_objective);
  }
  out["solve_time_ms"] = r.solve_time_ms;
  out["controls"] = ToJson(control.controls());
  // Where the path ended: the loaded configuration when compensated.
  const State& final_state =
      s.compensation && s.tally.last_state ? *s.tally.last_state : control.forward().state();
  out["end_effector"] = ToJson(ComputeEndEffectorPose(model, final_state));
  if (s.compensation) out["compensation"] = {{"rounds", s.compensation->rounds}, {"max_miss", s.compensation->max_miss}};
  AddClearance(model, final_state, &out, &doc.warnings);
  AddPathClearance(s.path_clearance, &out);
  doc.Warn(r.warning);
  return doc;
}

}  // namespace ccma::documents
