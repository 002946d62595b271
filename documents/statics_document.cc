#include "documents/statics_document.h"

#include <string>

#include "analyses/payload.h"
#include "ccma/internal/format.h"
#include "documents/json_values.h"

namespace ccma::documents {
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

// The reactions and efforts (docs/cli.md, `ccma statics`).
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
std::string Warnings(const StaticsReport& r, bool assembled, double residual_energy) {
  std::string w;
  auto add = [&](const std::string& text) { w += (w.empty() ? "" : "; ") + text; };
  if (!assembled) add("not assembled (E = " + FormatG(residual_energy) + "): the reactions are not meaningful");
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

// The payload capacity when efforts are limited and it can be stated; its
// note (a warning) to `warnings`.
void AddPayloadCapacity(const Model& model, const State& s, const Eigen::VectorXd& u, nlohmann::json* out,
                        std::vector<std::string>* warnings) {
  const PayloadCapacity capacity = ComputePayloadCapacity(model, s, u);
  if (!Reportable(capacity)) return;
  const std::string limiting = capacity.broken_unloaded.empty() ? capacity.limiting : capacity.broken_unloaded;
  (*out)["payload_capacity"] = {{"mass", ReportedMass(capacity)}, {"limiting", limiting}};
  if (!capacity.note.empty()) {
    (*out)["payload_capacity"]["note"] = capacity.note;
    warnings->push_back(capacity.note);
  }
}

}  // namespace

Document StaticsDocument(const Model& model, const State& s, const Eigen::VectorXd& u, bool assembled,
                         double residual_energy, const ExternalWrench& wrench, const BasePoseNoise& noise) {
  const StaticsReport report = ComputeStatics(model, s, u, wrench);
  Document doc;
  doc.json = ReportJson(report);
  nlohmann::json& out = doc.json;
  AddComplianceJson(report, &out);
  out["model"] = model.name;
  out["assembled"] = assembled;
  out["residual_energy"] = residual_energy;
  out["controls"] = ToJson(u);
  out["end_effector"] = ToJson(ComputeEndEffectorPose(model, s));
  out["bodies"] = BodiesToJson(model, s);
  const nlohmann::json covariance = CovarianceJson(EndEffectorCovariance(model, s, u, noise));
  if (!covariance.is_null()) out["ee_covariance"] = covariance;
  out["noise"] = {{"mocap_noise_m", noise.position_sigma}, {"mocap_noise_rad", noise.heading_sigma}};
  if (report.limits_given) AddPayloadCapacity(model, s, u, &out, &doc.warnings);
  AddClearance(model, s, &out, &doc.warnings);
  const std::string warning = Warnings(report, assembled, residual_energy);
  doc.Warn(warning);
  return doc;
}

}  // namespace ccma::documents
