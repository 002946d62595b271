#include "documents/replay_document.h"

#include <cmath>
#include <string>

#include "documents/replay_report.h"

namespace ccma::documents {
namespace {

// The simulated imperfections and the tracking controller's gains.
nlohmann::json OptionsJson(const ReplayOptions& options) {
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

// A time that exists only when something happened: the key is left out
// otherwise (no null is ever printed as a result).
void PutTimeIfAny(nlohmann::json* out, const char* key, double seconds) {
  if (std::isfinite(seconds)) (*out)[key] = seconds;
}

nlohmann::json PaperRowsJson() {
  nlohmann::json paper = nlohmann::json::array();
  for (const PaperRow& row : PaperHardwareRmse()) {
    paper.push_back({{"experiment", row.experiment}, {"y_mm", row.y_mm}, {"z_mm", row.z_mm},
                     {"x_mm", row.x_mm}, {"yaw_rad", row.yaw_rad}});
  }
  return paper;
}

}  // namespace

Document ReplayDocument(const Model& model, const ReplayOptions& options, const ReplayResult& r) {
  Document doc;
  nlohmann::json& out = doc.json;
  out["model"] = model.name;
  out["simulation"] = true;
  out["converged"] = r.converged;
  out["torn"] = r.torn;
  out["torn_samples"] = r.torn_samples;
  PutTimeIfAny(&out, "first_torn_time_s", r.first_torn_time);
  out["max_residual_energy"] = r.max_residual_energy;
  out["torn_residual_energy"] = r.torn_residual_energy;
  PutTimeIfAny(&out, "failed_step_time_s", r.failed_step_time);
  out["trustworthy"] = r.trustworthy();
  out["duration_s"] = r.duration_s;
  out["samples"] = r.samples.size();
  out.update(OptionsJson(options));
  out["rmse"] = ReplayRmseJson(model, r.rmse);
  if (r.gait) out["gait"] = ReplayGaitJson(model, options, r);
  if (IsPaperModel(model)) out["paper_hardware_rmse"] = PaperRowsJson();
  std::string warning;
  for (const std::string& failure : ReplayFailures(r)) {
    JoinWarning(failure, &warning);
    doc.warnings.push_back(failure);
  }
  if (!warning.empty()) out["warning"] = warning;
  return doc;
}

}  // namespace ccma::documents
