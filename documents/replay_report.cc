// What `ccma replay` reports besides its plots (apps/replay_report.h): the
// components shown, the RMSE table and the CSV files.
#include "documents/replay_report.h"

#include <fstream>
#include <sstream>

#include "ccma/internal/format.h"
#include "ccma/rotation.h"

namespace ccma::documents {

std::vector<int> ReportedComponents(const Model& model) {
  const auto& c = model.end_effector.controlled;
  if (c[kX] && c[kY] && c[kZ] && c[kYaw] && !c[kRoll] && !c[kPitch]) return {kY, kZ, kX, kYaw};
  std::vector<int> out;
  for (int k = 0; k < 6; ++k) {
    if (c[k]) out.push_back(k);
  }
  return out;
}

std::string ComponentName(int component) {
  static const char* kNames[] = {"x", "y", "z", "roll", "pitch", "yaw"};
  return kNames[component];
}

bool IsAngle(int component) { return component >= 3; }

bool IsPaperModel(const Model& model) { return model.name == "4dof_reduced" || model.name == "4dof_complete"; }

const std::vector<PaperRow>& PaperHardwareRmse() {
  static const std::vector<PaperRow> kRows = {{"reduced scheme, sequential (Fig. 7)", 18, 12, 17, 0.09},
                                              {"reduced scheme, combined (Fig. 10)", 18, 22, 24, 0.13},
                                              {"complete scheme, combined", 10, 17, 13, 0.10}};
  return kRows;
}

std::vector<std::string> ReplayFailures(const ReplayResult& r) {
  std::vector<std::string> out;
  if (!r.converged) {
    out.push_back("not converged: the control solution did not reach every waypoint (the replay stops at t = " +
                  FormatG(r.failed_step_time) + " s): " + OneLine(r.warning));
  }
  if (r.torn) {
    out.push_back("chain torn: the chain could not follow the bases in " + std::to_string(r.torn_samples) + " of " +
                  std::to_string(r.samples.size()) + " samples (residual energy above " +
                  FormatG(r.torn_residual_energy) + " m^2), first at t = " + FormatG(r.first_torn_time) +
                  " s, worst E = " + FormatG(r.max_residual_energy) + " m^2");
  }
  if (r.samples.empty()) out.push_back("no samples: nothing was simulated");
  return out;
}

std::string ReplayRmseTable(const Model& model, const ReplayResult& r, const std::string& setting) {
  std::ostringstream table;
  if (!r.trustworthy()) {
    std::string reasons;
    auto add = [&](const std::string& reason) { reasons += (reasons.empty() ? "" : "; ") + reason; };
    if (!r.converged) add("the control solution did not reach every waypoint (stops at t = " + FormatG(r.failed_step_time) + " s)");
    if (r.torn) add("the chain was torn in " + std::to_string(r.torn_samples) + " samples");
    if (r.samples.empty()) add("no samples");
    table << "WARNING: NOT TRUSTWORTHY, " << reasons << ": the RMSE below does not measure tracking.\n\n";
  }
  const std::vector<int> components = ReportedComponents(model);
  table << "RMSE of the end-effector, tracked against commanded. ccma: SIMULATION of " << setting << "."
        << (IsPaperModel(model) ? " Paper: hardware prototypes." : "") << "\n\n| source |";
  for (const int c : components) table << " " << ComponentName(c) << (IsAngle(c) ? " [rad] |" : " [mm] |");
  table << "\n|---|";
  for (size_t i = 0; i < components.size(); ++i) table << "---|";
  table << "\n| ccma simulation" << (r.trustworthy() ? "" : " (FAILED)") << " |";
  for (const int c : components) table << " " << (IsAngle(c) ? FormatFixed(r.rmse[c], 5) : FormatFixed(1000 * r.rmse[c], 3)) << " |";
  table << "\n";
  if (IsPaperModel(model)) {
    for (const PaperRow& row : PaperHardwareRmse()) {
      table << "| paper, " << row.experiment << " |";
      for (const int c : components) {
        table << " "
              << (c == kX ? FormatG(row.x_mm) : c == kY ? FormatG(row.y_mm) : c == kZ ? FormatG(row.z_mm) : c == kYaw ? FormatG(row.yaw_rad) : "-")
              << " |";
      }
      table << "\n";
    }
  }
  return table.str();
}

Table ReplayEndEffectorTable(const ReplayResult& r) {
  static const char* kUnits[] = {"m", "m", "m", "rad", "rad", "rad"};
  Table t;
  std::vector<double>& time = t.Add("time_s").values;
  for (const ReplaySample& s : r.samples) time.push_back(s.time);
  for (int c = 0; c < 6; ++c) {
    std::vector<double>& v = t.Add("cmd_" + ComponentName(c) + "_" + kUnits[c]).values;
    for (const ReplaySample& s : r.samples) v.push_back(s.commanded[c]);
  }
  for (int c = 0; c < 6; ++c) {
    std::vector<double>& v = t.Add(ComponentName(c) + "_" + kUnits[c]).values;
    for (const ReplaySample& s : r.samples) v.push_back(s.tracked[c]);
  }
  // err = tracked - commanded: angles wrapped [rad], positions [mm].
  for (int c = 0; c < 6; ++c) {
    std::vector<double>& v = t.Add("err_" + ComponentName(c) + (IsAngle(c) ? "_rad" : "_mm")).values;
    for (const ReplaySample& s : r.samples) {
      v.push_back(IsAngle(c) ? WrapAngle(s.tracked[c] - s.commanded[c]) : 1000 * (s.tracked[c] - s.commanded[c]));
    }
  }
  std::vector<double>& energy = t.Add("residual_energy_m2").values;
  std::vector<double>& torn = t.Add("torn", ColumnKind::kFlag).values;
  for (const ReplaySample& s : r.samples) {
    energy.push_back(s.residual_energy);
    torn.push_back(s.torn ? 1 : 0);
  }
  return t;
}

Table ReplayBasesTable(const Model& model, const ReplayResult& r) {
  Table t;
  std::vector<double>& time = t.Add("time_s").values;
  for (const ReplaySample& s : r.samples) time.push_back(s.time);
  for (int k = 0; k < model.num_bases(); ++k) {
    // Every control of the base's type (a legged base's height, roll and pitch too), set then true.
    const std::vector<BaseControl>& controls = KindOf(model.mobile_bases[static_cast<size_t>(k)]).controls();
    const int first = model.base_control(k);
    for (const char* which : {"set", "base"}) {
      const bool set = std::string(which) == "set";
      for (int c = 0; c < static_cast<int>(controls.size()); ++c) {
        const BaseControl& control = controls[static_cast<size_t>(c)];
        std::vector<double>& v = t.Add(which + std::to_string(k) + "_" + control.name + "_" + control.unit).values;
        for (const ReplaySample& s : r.samples) v.push_back(set ? s.set_controls[first + c] : s.true_controls[first + c]);
      }
    }
  }
  // Actuated joints hold their set-points (execution/replay.h): one column each.
  for (const Joint& joint : model.joints) {
    if (!joint.actuated) continue;
    std::vector<double>& v = t.Add("u_" + joint.name + (joint.type == JointType::kRevolute ? "_rad" : "_m")).values;
    for (const ReplaySample& s : r.samples) v.push_back(s.true_controls[joint.control]);
  }
  std::vector<double>& torn = t.Add("torn", ColumnKind::kFlag).values;
  for (const ReplaySample& s : r.samples) torn.push_back(s.torn ? 1 : 0);
  return t;
}

void WriteReplayCsv(const std::string& dir, const Model& model, const ReplayResult& r) {
  std::ofstream ee(dir + "/end_effector.csv");
  ee << "# SIMULATION (ccma replay): commanded = control solution, tracked = chain on the driven bases; "
        "err = tracked - commanded; torn = 1 where the chain could not follow the bases\n";
  WriteCsv(ReplayEndEffectorTable(r), ee, kReplayCsvDigits);
  std::ofstream bases(dir + "/bases.csv");
  bases << "# SIMULATION (ccma replay): set and true poses of every base (k = index in the model:";
  for (int k = 0; k < model.num_bases(); ++k) bases << " " << k << " = " << OneLine(model.mobile_bases[k].name);
  bases << ")\n";
  WriteCsv(ReplayBasesTable(model, r), bases, kReplayCsvDigits);
}

nlohmann::json ReplayRmseJson(const Model& model, const std::array<double, 6>& rmse_m_rad) {
  nlohmann::json rmse = nlohmann::json::object();
  for (const int c : ReportedComponents(model)) {
    rmse[ComponentName(c) + (IsAngle(c) ? "_rad" : "_mm")] = IsAngle(c) ? rmse_m_rad[c] : 1000 * rmse_m_rad[c];
  }
  return rmse;
}

nlohmann::json ReplayGaitJson(const Model& model, const ReplayOptions& options, const ReplayResult& result) {
  return {{"hz", options.gait.hz},
          {"bob_m", options.gait.bob_m},
          {"sway_rad", options.gait.sway_rad},
          {"rmse_from_gait", ReplayRmseJson(model, result.gait_rmse)},
          {"rmse_from_tracking", ReplayRmseJson(model, result.tracking_rmse)}};
}

}  // namespace ccma::documents
