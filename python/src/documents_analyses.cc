// The documents of the analysing commands: statics, check, design, replay
// (python/src/documents.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "analyses/design_objective.h"
#include "analyses/payload.h"
#include "apps/json_output.h"
#include "apps/replay_report.h"
#include "ccma/end_effector.h"
#include "ccma/internal/format.h"
#include "python/src/documents.h"

namespace ccma::python {

using cli::BodiesToJson;
using cli::ClearanceToJson;
using cli::ToJson;

namespace {

nlohmann::json Vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// apps/statics_command.cc: ReportJson.
nlohmann::json StaticsReportJson(const StaticsReport& r) {
  nlohmann::json out;
  nlohmann::json joints = nlohmann::json::array(), actuators = nlohmann::json::array();
  for (const JointReaction& j : r.joints) {
    joints.push_back({{"name", j.name}, {"point", Vec(j.point)}, {"force", Vec(j.force)}, {"moment", Vec(j.moment)}});
  }
  for (const ActuatorEffort& a : r.actuators) {
    actuators.push_back({{"name", a.name}, {"kind", a.kind}, {"effort", a.effort}});
  }
  out["joints"] = joints;
  out["actuators"] = actuators;
  out["determinate"] = r.determinate;
  out["balanced"] = r.balanced;
  out["unbalanced_load"] = r.residual;
  if (r.limits_given) {
    out["within_limits"] = r.within_limits;
    out["limiting"] = r.limiting;
  }
  return out;
}

// apps/statics_command.cc: Warnings.
std::string StaticsWarning(const StaticsReport& r, bool assembled, double residual_energy) {
  std::string w;
  if (!assembled) JoinWarning("not assembled (E = " + FormatG(residual_energy) + "): the reactions are not meaningful", &w);
  if (!r.balanced) {
    JoinWarning("the joints cannot hold the loads (" + FormatG(r.residual) +
             " N or N*m left over): the mechanism moves freely under them",
         &w);
  }
  if (!r.determinate) JoinWarning("statically indeterminate: the minimum-norm reactions are reported", &w);
  if (r.compliant && !r.compliance.held) {
    JoinWarning("the loaded mechanism is not held: a motion that no spring resists moves the end-effector", &w);
  }
  if (r.compliant && !r.compliance.range_note.empty()) JoinWarning(r.compliance.range_note, &w);
  if (!r.within_limits) {
    std::string names;
    for (const std::string& n : r.limiting) names += (names.empty() ? "'" : ", '") + n + "'";
    JoinWarning("beyond their effort or push limits: " + names, &w);
  }
  return w;
}

}  // namespace

nlohmann::json StaticsDocument(const Model& model, const State& s, const Eigen::VectorXd& u, double residual_energy,
                               double assembly_tolerance, const ExternalWrench& wrench, const BasePoseNoise& noise) {
  const StaticsReport report = ComputeStatics(model, s, u, wrench);  // std::invalid_argument: ValueError
  const bool assembled = residual_energy < assembly_tolerance;
  nlohmann::json out = StaticsReportJson(report);
  cli::AddComplianceJson(report, &out);
  out["model"] = model.name;
  out["assembled"] = assembled;
  out["residual_energy"] = residual_energy;
  out["controls"] = ToJson(u);
  out["end_effector"] = ToJson(ComputeEndEffectorPose(model, s));
  out["bodies"] = BodiesToJson(model, s);
  const Eigen::Matrix<double, 6, 6> sigma = EndEffectorCovariance(model, s, u, noise);
  if (sigma.allFinite()) {
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 6; ++r) rows.push_back(ToJson(Eigen::VectorXd(sigma.row(r).transpose())));
    out["ee_covariance"] = rows;
  }
  out["noise"] = {{"mocap_noise_m", noise.position_sigma}, {"mocap_noise_rad", noise.heading_sigma}};
  if (report.limits_given) {
    const PayloadCapacity capacity = ComputePayloadCapacity(model, s, u);
    if (Reportable(capacity)) {
      const std::string limiting = capacity.broken_unloaded.empty() ? capacity.limiting : capacity.broken_unloaded;
      out["payload_capacity"] = {{"mass", ReportedMass(capacity)}, {"limiting", limiting}};
      if (!capacity.note.empty()) out["payload_capacity"]["note"] = capacity.note;
    }
  }
  const nlohmann::json clearance = ClearanceToJson(model, s);
  if (!clearance.is_null()) out["clearance"] = clearance;
  const std::string warning = StaticsWarning(report, assembled, residual_energy);
  if (!warning.empty()) out["warning"] = warning;
  return out;
}

namespace {

// apps/check_command.cc: CheckJson.
nlohmann::json CheckCounts(const Model& model, const MobilityReport& mobility, bool assembled) {
  nlohmann::json out;
  out["model"] = model.name;
  out["bodies"] = model.num_bodies();
  out["mobile_bases"] = model.num_bases();
  out["joints"] = model.joints.size();
  out["state_size"] = model.state_size();
  out["controls"] = model.num_controls();
  out["effective_controls"] = model.effective_control_indices().size();
  out["constraints"] = mobility.constraint_rows;
  out["rigid_with_controls_fixed"] = mobility.rigid_with_controls_fixed;
  out["end_effector_dof"] = mobility.end_effector_dof;
  out["end_effector_dof_nonholonomic"] = mobility.end_effector_dof_nonholonomic;
  out["assembled_at_home"] = assembled;
  out["constraint_rank"] = mobility.constraint_rank;
  out["dof_with_controls_fixed"] = mobility.dof_with_controls_fixed;
  out["dof_with_controls_free"] = mobility.dof_with_controls_free;
  out["smallest_singular_value"] = mobility.smallest_singular_value;
  out["energy_at_home"] = mobility.energy;
  nlohmann::json controlled = nlohmann::json::array();
  for (int c = 0; c < 6; ++c) {
    if (model.end_effector.controlled[c]) controlled.push_back(kEndEffectorComponentNames[c]);
  }
  out["controlled"] = controlled;
  nlohmann::json motions = nlohmann::json::array();
  for (const FreeMotion& motion : mobility.free_motions) {
    nlohmann::json bodies = nlohmann::json::array();
    for (const int b : motion.bodies) bodies.push_back(model.bodies[b].name);
    nlohmann::json joints = nlohmann::json::array();
    for (const int j : motion.joints) joints.push_back(model.joints[j].name);
    motions.push_back({{"bodies", bodies}, {"joints", joints}});
  }
  out["free_motions"] = motions;
  return out;
}

// apps/check_command.cc: FreeMotionText.
std::string FreeMotionText(const Model& model, const std::vector<FreeMotion>& motions) {
  std::string text;
  for (size_t m = 0; m < motions.size(); ++m) {
    text += (m ? "; motion " : "motion ") + std::to_string(m + 1) + " moves ";
    for (size_t i = 0; i < motions[m].bodies.size(); ++i) text += (i ? ", " : "") + model.bodies[motions[m].bodies[i]].name;
    for (size_t i = 0; i < motions[m].joints.size(); ++i) {
      text += (i ? ", " : " (joints ") + model.joints[motions[m].joints[i]].name;
    }
    if (!motions[m].joints.empty()) text += ")";
  }
  return text;
}

// apps/check_command.cc: OnlyIdleMotions.
bool OnlyIdleMotions(const Model& model, const MobilityReport& mobility) {
  if (!mobility.free_motions_listed || mobility.free_motions.empty()) return false;
  const Eigen::MatrixXd dX_ds = EndEffectorJacobian(model, State::Home(model));
  for (const FreeMotion& motion : mobility.free_motions) {
    if ((dX_ds * motion.direction).norm() > 1e-8) return false;
  }
  return true;
}

// apps/check_command.cc: CheckWarnings.
nlohmann::json CheckWarnings(const Model& model, const MobilityReport& mobility, bool assembled) {
  const ForwardOptions defaults;
  int controlled_count = 0;
  for (int c = 0; c < 6; ++c) controlled_count += model.end_effector.controlled[c] ? 1 : 0;
  nlohmann::json warnings = nlohmann::json::array();
  if (!mobility.rigid_with_controls_fixed) {
    const bool idle = OnlyIdleMotions(model, mobility);
    warnings.push_back("not rigid with its controls fixed: " + std::to_string(mobility.dof_with_controls_fixed) +
                       " free motion(s) remain (smallest singular value of dC/ds " +
                       FormatG(mobility.smallest_singular_value) + "): " +
                       (mobility.free_motions_listed ? FreeMotionText(model, mobility.free_motions)
                                                     : std::string("too many to list them")) +
                       (idle ? "; none moves the end-effector (idle motions, docs/numerics.md): control resolves "
                               "them, simulation leaves them where they are"
                             : "; simulation and control are ill-posed"));
  }
  if (!assembled) {
    warnings.push_back("not assembled at home: E = " + FormatG(mobility.energy) + " m^2 (above " +
                       FormatG(defaults.assembly_tolerance) + "); check the joint points and axes");
  }
  if (mobility.end_effector_dof < controlled_count) {
    warnings.push_back("the controls move only " + std::to_string(mobility.end_effector_dof) +
                       " end-effector DOF at home, fewer than the " + std::to_string(controlled_count) +
                       " controlled components");
  }
  if (mobility.end_effector_dof_nonholonomic < std::min(controlled_count, mobility.end_effector_dof)) {
    warnings.push_back("the differential bases, which cannot move sideways, leave the end-effector only " +
                       std::to_string(mobility.end_effector_dof_nonholonomic) +
                       " instantaneous DOF at home, fewer than the " + std::to_string(controlled_count) +
                       " controlled components: most paths are infeasible");
  }
  return warnings;
}

}  // namespace

nlohmann::json CheckDocument(const Model& model) {
  const State home = State::Home(model);
  const MobilityReport mobility = AnalyzeMobility(model, home, model.home_controls());
  const bool assembled = mobility.energy < ForwardOptions().assembly_tolerance;
  nlohmann::json out = CheckCounts(model, mobility, assembled);
  const nlohmann::json warnings = CheckWarnings(model, mobility, assembled);
  if (!warnings.empty()) out["warnings"] = warnings;
  const nlohmann::json clearance = ClearanceToJson(model, home);
  if (!clearance.is_null()) out["clearance"] = clearance;
  return out;
}

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
  out["rmse"] = cli::ReplayRmseJson(model, r.rmse);
  if (r.gait) out["gait"] = cli::ReplayGaitJson(model, options, r);
  if (cli::IsPaperModel(model)) {
    nlohmann::json paper = nlohmann::json::array();
    for (const cli::PaperRow& row : cli::PaperHardwareRmse()) {
      paper.push_back({{"experiment", row.experiment}, {"y_mm", row.y_mm}, {"z_mm", row.z_mm},
                       {"x_mm", row.x_mm}, {"yaw_rad", row.yaw_rad}});
    }
    out["paper_hardware_rmse"] = paper;
  }
  std::string warning;
  for (const std::string& failure : cli::ReplayFailures(r)) JoinWarning(failure, &warning);
  if (!warning.empty()) out["warning"] = warning;
  return out;
}

}  // namespace ccma::python
