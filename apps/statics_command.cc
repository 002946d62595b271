// `ccma statics --model=FILE [--controls=...] [--wrench=fx,fy,fz,mx,my,mz]`:
// static equilibrium of the mechanism assembled at the controls
// (analyses/statics.h): joint reactions and the effort of every control.
#include <cmath>
#include <iostream>
#include <string>

#include "analyses/payload.h"
#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "ccma/internal/format.h"

DECLARE_double(mocap_noise_m);    // apps/replay_command.cc (the replay's noise model)
DECLARE_double(mocap_noise_rad);

namespace ccma::cli {

BasePoseNoise PoseNoiseFromFlags() {
  BasePoseNoise noise;
  const SimulationNoise replay;
  noise.position_sigma = FLAGS_mocap_noise_m >= 0 ? FLAGS_mocap_noise_m : replay.position_sigma;
  noise.heading_sigma = FLAGS_mocap_noise_rad >= 0 ? FLAGS_mocap_noise_rad : replay.heading_sigma;
  if (!(noise.position_sigma <= 1.0) || !(noise.heading_sigma <= 1.0)) {
    throw UsageError("--mocap_noise_m and --mocap_noise_rad must lie in [0, 1] (m, rad)");
  }
  return noise;
}

namespace {

// Sigma_X as 6 rows, or null when dG/ds is singular (no first-order answer).
nlohmann::json CovarianceJson(const Eigen::Matrix<double, 6, 6>& sigma) {
  if (!sigma.allFinite()) return nullptr;
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 6; ++r) rows.push_back({sigma(r, 0), sigma(r, 1), sigma(r, 2), sigma(r, 3), sigma(r, 4), sigma(r, 5)});
  return rows;
}

// The warning of a compliant mechanism that does not hold its end-effector.
constexpr const char* kNotHeld =
    "the loaded mechanism is not held: a motion that no spring resists moves the end-effector";

nlohmann::json Vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json ReportJson(const StaticsReport& r) {
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

// The warnings of a statics report, for JSON and stderr.
std::string Warnings(const StaticsReport& r, const ForwardResult& assembly) {
  std::string w;
  auto add = [&](const std::string& text) { w += (w.empty() ? "" : "; ") + text; };
  if (!assembly.assembled) add("not assembled (E = " + FormatG(assembly.residual_energy) + "): the reactions are not meaningful");
  if (!r.balanced) {
    add("the joints cannot hold the loads (" + FormatG(r.residual) + " N or N*m left over): the mechanism moves freely under them");
  }
  if (!r.determinate) add("statically indeterminate: the minimum-norm reactions are reported");
  if (r.compliant && !r.compliance.held) add(kNotHeld);
  if (r.compliant && !r.compliance.range_note.empty()) add(r.compliance.range_note);
  if (!r.within_limits) {
    std::string names;
    for (const std::string& n : r.limiting) names += (names.empty() ? "'" : ", '") + n + "'";
    add("beyond their effort or push limits: " + names);
  }
  return w;
}

}  // namespace

int RunStatics(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "statics");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "statics"));
  const ExternalWrench wrench = WrenchFlag();
  const BasePoseNoise noise = PoseNoiseFromFlags();
  const Eigen::VectorXd u = ControlsFlagOrHome(model);
  ForwardProblem forward(model);
  const ForwardResult assembly = forward.Assemble(u);
  StaticsReport report;
  try {
    report = ComputeStatics(model, forward.state(), forward.controls(), wrench);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("ccma statics: ") + e.what());
  }
  nlohmann::json out = ReportJson(report);
  AddComplianceJson(report, &out);
  out["model"] = model.name;
  out["assembled"] = assembly.assembled;
  out["residual_energy"] = assembly.residual_energy;
  out["controls"] = ToJson(forward.controls());
  out["end_effector"] = ToJson(forward.end_effector());
  out["bodies"] = BodiesToJson(model, forward.state());
  const nlohmann::json covariance =
      CovarianceJson(EndEffectorCovariance(model, forward.state(), forward.controls(), noise));
  if (!covariance.is_null()) out["ee_covariance"] = covariance;
  out["noise"] = {{"mocap_noise_m", noise.position_sigma}, {"mocap_noise_rad", noise.heading_sigma}};
  if (report.limits_given) {
    const PayloadCapacity capacity = ComputePayloadCapacity(model, forward.state(), forward.controls());
    if (Reportable(capacity)) {
      const std::string limiting = capacity.broken_unloaded.empty() ? capacity.limiting : capacity.broken_unloaded;
      out["payload_capacity"] = {{"mass", ReportedMass(capacity)}, {"limiting", limiting}};
      if (!capacity.note.empty()) {
        out["payload_capacity"]["note"] = capacity.note;
        std::cerr << "ccma statics: warning: " << capacity.note << "\n";
      }
    }
  }
  AddClearance(model, forward.state(), "statics", &out);
  const std::string warning = Warnings(report, assembly);
  if (!warning.empty()) {
    out["warning"] = warning;
    std::cerr << "ccma statics: warning: " << warning << "\n";
  }
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
