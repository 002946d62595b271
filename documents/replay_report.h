// What `ccma replay --out=DIR` reports besides its plots: the end-effector
// components it shows, the RMSE table (with the paper's hardware rows) and
// the CSV files the plots read.
#ifndef CCMA_DOCUMENTS_REPLAY_REPORT_H_
#define CCMA_DOCUMENTS_REPLAY_REPORT_H_

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ccma/model.h"
#include "documents/table.h"
#include "execution/replay.h"

namespace ccma::documents {

// The end-effector components a replay reports, in display order: the
// paper's y, z, x, yaw for a model controlling exactly x, y, z and yaw;
// otherwise x, y, z, roll, pitch, yaw, those the model controls.
std::vector<int> ReportedComponents(const Model& model);
// "x", "y", ..., and their display units: positions in mm, angles in rad.
std::string ComponentName(int component);
bool IsAngle(int component);
// The paper's hardware RMSE rows apply: the model is 4dof_reduced or 4dof_complete.
bool IsPaperModel(const Model& model);

struct PaperRow {
  const char* experiment;
  double y_mm, z_mm, x_mm, yaw_rad;
};
// The paper's hardware RMSE (Section IV).
const std::vector<PaperRow>& PaperHardwareRmse();

// One line per way the replay failed (plan not converged, chain torn, no
// samples), each starting with what failed; empty when trustworthy.
std::vector<std::string> ReplayFailures(const ReplayResult& result);

// An RMSE per reported component [m, rad] as the JSON's "rmse" object
// (x_mm ... in mm, yaw_rad ... in rad).
nlohmann::json ReplayRmseJson(const Model& model, const std::array<double, 6>& rmse_m_rad);
// Models with legged bases: the JSON's "gait" object (the gait used and the
// two shares of the error, ReplayResult::gait_rmse and tracking_rmse).
nlohmann::json ReplayGaitJson(const Model& model, const ReplayOptions& options, const ReplayResult& result);

// The RMSE table (markdown): "WARNING: ..." lines at its top when the result
// is not trustworthy, then the reported components of the simulation, and the
// paper's hardware rows for the paper's models only. `setting` describes the
// run (model, path, noise) in one sentence.
std::string ReplayRmseTable(const Model& model, const ReplayResult& result, const std::string& setting);

// The tables of a replay (Python's ReplayResult.tables): per sample, the
// end-effector commanded, tracked and their difference (err_*: mm and
// wrapped rad), E and torn; and every base's set and true controls, every
// actuated joint's control, and torn.
Table ReplayEndEffectorTable(const ReplayResult& result);
Table ReplayBasesTable(const Model& model, const ReplayResult& result);

// The significant digits of the replay's CSV files.
constexpr int kReplayCsvDigits = 12;

// The CSV files the plots read (in DIR): end_effector.csv and bases.csv (the
// two tables), each after a comment line that labels it SIMULATION.
void WriteReplayCsv(const std::string& dir, const Model& model, const ReplayResult& result);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_REPLAY_REPORT_H_
