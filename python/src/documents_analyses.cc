// The documents of the analysing commands: design, replay
// (python/src/documents.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "analyses/design_objective.h"
#include "analyses/payload.h"
#include "documents/json_values.h"
#include "documents/replay_report.h"
#include "ccma/end_effector.h"
#include "ccma/internal/format.h"
#include "python/src/documents.h"

namespace ccma::python {

using documents::BodiesToJson;
using documents::ClearanceToJson;
using documents::ToJson;

namespace {

// apps/design_command.cc: TargetsJson.
nlohmann::json TargetsJson(const std::vector<DesignTargetResult>& results, bool reached_only) {
  nlohmann::json out = nlohmann::json::array();
  for (const DesignTargetResult& r : results) {
    if (reached_only) {
      out.push_back(r.reached);
    } else {
      out.push_back({{"reached", r.reached},
                     {"error", std::isfinite(r.error) ? r.error : -1.0},
                     {"min_singular_value", r.min_singular_value},
                     {"within_limits", r.within_limits}});
    }
  }
  return out;
}

// apps/design_command.cc: AddChanges.
void AddChanges(const Model& model, const Model& designed, const DesignParameters& params, const DesignResult& r,
                nlohmann::json* out) {
  nlohmann::json changed = nlohmann::json::array();
  for (int k = 0; k < params.size(); ++k) {
    changed.push_back({{"parameter", params.list[k].label}, {"old", r.p0[k]}, {"new", r.p[k]}, {"unit", "m"}});
  }
  (*out)["changed"] = changed;
  nlohmann::json points = nlohmann::json::array();
  for (int j = 0; j < static_cast<int>(model.joints.size()); ++j) {
    const Eigen::Vector3d a = JointPointWorld(model, j), b = JointPointWorld(designed, j);
    if (a != b) {
      points.push_back({{"joint", model.joints[j].name}, {"old_point", ToJson(Eigen::VectorXd(a))},
                        {"new_point", ToJson(Eigen::VectorXd(b))}});
    }
  }
  (*out)["changed_points"] = points;
}

nlohmann::json ObjectiveValueJson(const ObjectiveAtTarget& v) {
  if (!v.defined) return nullptr;
  return {{"value", v.value}, {"limiting", v.limiting}};
}

}  // namespace

nlohmann::json DesignDocument(const Model& model, const Model& designed, const DesignParameters& params,
                              const DesignResult& r, const std::vector<DesignTargetResult>& final_check,
                              const DesignOptions& options) {
  bool all_reached = true;
  double min_sigma = std::numeric_limits<double>::infinity();
  for (const DesignTargetResult& t : final_check) {
    all_reached = all_reached && t.reached;
    min_sigma = std::min(min_sigma, t.min_singular_value);
  }
  const bool converged = all_reached && min_sigma >= options.min_singular_value;
  nlohmann::json out;
  out["model"] = model.name;
  out["converged"] = converged;
  out["reached"] = TargetsJson(final_check, true);
  out["reached_before"] = TargetsJson(r.initial, true);
  out["targets"] = TargetsJson(final_check, false);
  out["iterations"] = r.iterations;
  AddChanges(model, designed, params, r, &out);
  if (options.objective != DesignObjective::kReach) {
    out["objective"] = {{"name", DesignObjectiveName(options.objective)},
                        {"unit", DesignObjectiveUnit(options.objective)},
                        {"maximised", IsMaximised(options.objective)},
                        {"before", ObjectiveValueJson(r.objective_before)},
                        {"after", ObjectiveValueJson(r.objective_after)},
                        {"iterations", r.objective_iterations},
                        {"stopped", r.objective_message}};
    if (converged && !r.objective_after.defined) {
      out["warning"] = "the " + std::string(DesignObjectiveName(options.objective)) +
                       " objective is not defined: " + r.objective_after.why;
    }
  }
  if (!converged) out["warning"] = r.message.empty() ? "not every target is reached with margin" : r.message;
  return out;
}

namespace {

// apps/replay_command.cc: OptionsJson.
nlohmann::json ReplayOptionsJson(const ReplayOptions& options) {
  const SimulationNoise& n = options.noise;
  const TrackingGains& g = options.gains;
  return {{"noise",
           {{"mocap_position_sigma_m", n.position_sigma}, {"mocap_heading_sigma_rad", n.heading_sigma},
            {"mocap_latency_s", n.mocap_latency}, {"mocap_hz", n.mocap_hz}, {"command_latency_s", n.command_latency},
            {"slip", n.slip}, {"slip_sigma", n.slip_sigma}, {"seed", n.seed}}},
          {"controller",
           {{"kp", g.kp_position}, {"ki", g.ki_position}, {"rate_hz", g.rate_hz},
            {"max_wheel_speed", g.max_wheel_speed}, {"velocity_feedforward", g.velocity_feedforward}}}};
}

}  // namespace

nlohmann::json ReplayDocument(const Model& model, const ReplayOptions& options, const ReplayResult& r) {
  nlohmann::json out;
  out["model"] = model.name;
  out["simulation"] = true;
  out["converged"] = r.converged;
  out["torn"] = r.torn;
  out["torn_samples"] = r.torn_samples;
  if (std::isfinite(r.first_torn_time)) out["first_torn_time_s"] = r.first_torn_time;
  out["max_residual_energy"] = r.max_residual_energy;
  out["torn_residual_energy"] = r.torn_residual_energy;
  if (std::isfinite(r.failed_step_time)) out["failed_step_time_s"] = r.failed_step_time;
  out["trustworthy"] = r.trustworthy();
  out["duration_s"] = r.duration_s;
  out["samples"] = r.samples.size();
  out.update(ReplayOptionsJson(options));
  out["rmse"] = documents::ReplayRmseJson(model, r.rmse);
  if (r.gait) out["gait"] = documents::ReplayGaitJson(model, options, r);
  if (documents::IsPaperModel(model)) {
    nlohmann::json paper = nlohmann::json::array();
    for (const documents::PaperRow& row : documents::PaperHardwareRmse()) {
      paper.push_back({{"experiment", row.experiment}, {"y_mm", row.y_mm}, {"z_mm", row.z_mm},
                       {"x_mm", row.x_mm}, {"yaw_rad", row.yaw_rad}});
    }
    out["paper_hardware_rmse"] = paper;
  }
  std::string warning;
  for (const std::string& failure : documents::ReplayFailures(r)) JoinWarning(failure, &warning);
  if (!warning.empty()) out["warning"] = warning;
  return out;
}

}  // namespace ccma::python
