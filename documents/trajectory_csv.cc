#include "documents/trajectory_csv.h"

#include <iomanip>
#include <sstream>
#include <string>

namespace ccma::documents {
namespace {

// The header: every name carries its unit (_s, _m, _rad, _m2, _ms).
void WriteHeader(const Model& model, std::ostream& csv) {
  // Clearance columns only with collision geometry (model_format.md).
  const std::string clearance = model.collision.enabled ? ",clearance_m,clearance_pair" : "";
  csv << "time_s,target_x_m,target_y_m,target_z_m,target_roll_rad,target_pitch_rad,target_yaw_rad,"
         "x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad";
  for (int k = 0; k < model.num_bases(); ++k) {
    for (const BaseControl& c : KindOf(model.mobile_bases[static_cast<size_t>(k)]).controls()) {
      csv << ",u" << k << "_" << c.name << "_" << c.unit;
    }
  }
  auto unit = [](const Joint& j) { return j.type == JointType::kRevolute ? "_rad" : "_m"; };
  for (const Joint& joint : model.joints) {
    if (joint.actuated) csv << ",u_" << joint.name << unit(joint);
  }
  for (const Joint& joint : model.joints) {
    if (joint.has_coordinate()) csv << ",q_" << joint.name << unit(joint);
  }
  csv << ",residual_energy_m2,error_m_or_rad,iterations,solve_time_ms,reached,limits_violated" << clearance;
}

// Effort columns (statics, only with masses, a payload or effort limits):
// one per control, then whether every effort is within its limits.
void WriteEffortHeader(const Model& model, std::ostream& csv) {
  for (int k = 0; k < model.num_bases(); ++k) {
    // A control in m takes a force [N], one in rad a moment [N*m].
    for (const BaseControl& c : KindOf(model.mobile_bases[static_cast<size_t>(k)]).controls()) {
      csv << ",effort_u" << k << "_" << c.name << (std::string(c.unit) == "m" ? "_N" : "_Nm");
    }
  }
  for (const Joint& joint : model.joints) {
    if (joint.actuated) csv << ",effort_" << joint.name << (joint.type == JointType::kRevolute ? "_Nm" : "_N");
  }
  csv << ",within_limits";
}

void WriteEffortCells(const EffortEvaluator& efforts, const TrajectoryStep& s, std::ostream& csv) {
  const StaticsReport r = efforts.At(s.state, s.controls);
  for (Eigen::Index c = 0; c < r.control_efforts.size(); ++c) csv << "," << r.control_efforts[c];
  csv << "," << (r.within_limits ? 1 : 0);
}

// The row's clearance cells: the smallest clearance [m] and its pair "a|b"
// (names never hold '|'); both empty when no pair is checked.
std::string ClearanceCells(const ClearanceSummary& c) {
  if (!c.any) return ",,";
  std::ostringstream cells;
  cells << std::setprecision(17) << "," << c.min << "," << c.a << "|" << c.b;
  return cells.str();
}

void WriteRow(const Model& model, const ClearanceSummary* clearance, const State& state, const TrajectoryStep& s,
              std::ostream& csv) {
  csv << s.time;
  for (int i = 0; i < 3; ++i) csv << "," << s.target.position[i];
  for (int i = 0; i < 3; ++i) csv << "," << s.target.rpy[i];
  for (int i = 0; i < 3; ++i) csv << "," << s.reached.position[i];
  for (int i = 0; i < 3; ++i) csv << "," << s.reached.rpy[i];
  for (int i = 0; i < s.controls.size(); ++i) csv << "," << s.controls[i];
  int violated = 0;
  for (const JointCoordinateReport& r : JointCoordinates(model, state)) {
    csv << "," << r.q;
    violated += !r.within_limits;
  }
  csv << "," << s.result.residual_energy << "," << s.result.error << "," << s.result.iterations << ","
      << s.result.time_ms << "," << (s.result.reached ? 1 : 0) << "," << violated
      << (clearance != nullptr ? ClearanceCells(*clearance) : "");
}

}  // namespace

TrajectoryCsv::TrajectoryCsv(const Model& model, std::ostream& csv)
    : model_(model), csv_(csv), collision_(model), efforts_(HasLoads(model)), effort_evaluator_(model) {
  csv_ << std::setprecision(17);
  WriteHeader(model_, csv_);
  if (efforts_) WriteEffortHeader(model_, csv_);
  csv_ << "\n";
}

void TrajectoryCsv::Write(const TrajectoryStep& step) {
  ClearanceSummary clearance;
  if (collision_.enabled()) {
    clearance = MinimumClearance(collision_, step.state);
    if (clearance.any && (!path_clearance_.any || clearance.min < path_clearance_.min)) path_clearance_ = clearance;
  }
  WriteRow(model_, collision_.enabled() ? &clearance : nullptr, step.state, step, csv_);
  if (efforts_) WriteEffortCells(effort_evaluator_, step, csv_);
  csv_ << "\n";
}

}  // namespace ccma::documents
