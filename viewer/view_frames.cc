#include "viewer/view_frames.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "viewer/csv_table.h"

namespace ccma::viewer {
namespace {

using Table = CsvTable;

// A trajectory's clearance_pair (cli.md) names two shapes: text.
CsvLimits ViewLimits() { return CsvLimits{kMaxViewFileBytes, kMaxReplaySamples, {"clearance_pair"}}; }

Table ReadTable(const std::string& path) { return ReadCsvTable(path, ViewLimits()); }

// A value that must be present and finite (controls, times).
double Required(const Table& t, size_t row, int col) {
  const double v = t.rows[row][col];
  if (std::isnan(v)) {
    throw ViewInputError(t.Where(row, col) + ": empty");
  }
  return v;
}

std::optional<Eigen::Vector3d> Point(const Table& t, size_t row, const std::array<int, 3>& cols) {
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) p[i] = t.rows[row][cols[i]];
  if (!p.allFinite()) return std::nullopt;
  return p;
}

std::string JointUnit(const Joint& j) { return j.type == JointType::kRevolute ? "_rad" : "_m"; }

// Columns of the controls: 3 per base (`prefix`k_x_m ...), then actuated joints.
std::vector<int> ControlColumns(const Model& model, const Table& t, const std::string& prefix, bool joints_required) {
  std::vector<int> cols;
  for (int k = 0; k < model.num_bases(); ++k) {
    const std::string p = prefix + std::to_string(k);
    for (const char* c : {"_x_m", "_y_m", "_theta_rad"}) cols.push_back(t.Find(p + c, true));
  }
  for (const Joint& j : model.joints) {
    if (j.actuated) cols.push_back(t.Find("u_" + j.name + JointUnit(j), joints_required));
  }
  return cols;
}

// A row's controls. Cells may hold up to 1e6 (times), but a control must lie
// within kMaxMagnitude as everywhere else: refused here, naming the cell,
// rather than later by the solver without file or line.
Eigen::VectorXd Controls(const Model& model, const Table& t, size_t row, const std::vector<int>& cols) {
  Eigen::VectorXd u = model.home_controls();
  for (size_t i = 0; i < cols.size(); ++i) {
    if (cols[i] < 0) continue;
    u[i] = Required(t, row, cols[i]);
    if (!(std::abs(u[i]) <= kMaxMagnitude)) {
      throw ViewInputError(t.Where(row, cols[i]) + ": a control of " + FormatG(u[i]) +
                           " is outside [-1e4, 1e4] (m or rad)");
    }
  }
  return u;
}

// The frames of a trajectory CSV's table (FramesFromTrajectory).
std::vector<ViewFrame> FramesFromTrajectoryTable(const Model& model, const Table& t) {
  const std::vector<int> controls = ControlColumns(model, t, "u", true);
  const int time = t.Find("time_s", true);
  const std::array<int, 3> target{t.Find("target_x_m", true), t.Find("target_y_m", true), t.Find("target_z_m", true)};
  const std::array<int, 3> reached{t.Find("x_m", true), t.Find("y_m", true), t.Find("z_m", true)};
  const int reached_flag = t.Find("reached", false);
  std::vector<ViewFrame> frames;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    ViewFrame f;
    f.time = Required(t, r, time);
    f.controls = Controls(model, t, r, controls);
    f.commanded = Point(t, r, target);
    f.tracked = Point(t, r, reached);
    f.flagged = reached_flag >= 0 && t.rows[r][reached_flag] != 1.0;
    frames.push_back(std::move(f));
  }
  return Thin(std::move(frames), MaxViewFrames(model));
}

}  // namespace

int MaxViewFrames(const Model& model) {
  const long by_poses = kMaxViewPoses / std::max(1, model.num_bodies());
  return static_cast<int>(std::max(2L, std::min<long>(kMaxViewFrames, by_poses)));
}

std::vector<ViewFrame> Thin(std::vector<ViewFrame> frames, int max_frames) {
  const int n = static_cast<int>(frames.size());
  if (n <= max_frames || max_frames < 2) return frames;
  std::vector<ViewFrame> kept;
  kept.reserve(max_frames);
  for (int i = 0; i < max_frames; ++i) {
    const long index = std::lround(static_cast<double>(i) * (n - 1) / (max_frames - 1));
    kept.push_back(std::move(frames[index]));
  }
  return kept;
}

std::vector<ViewFrame> FramesFromTrajectory(const Model& model, const std::string& csv_path) {
  return FramesFromTrajectoryTable(model, ReadTable(csv_path));
}

std::vector<ViewFrame> FramesFromTrajectoryText(const Model& model, const std::string& text,
                                                const std::string& source) {
  return FramesFromTrajectoryTable(model, ParseCsvTable(text, source, ViewLimits()));
}

std::vector<ViewFrame> FramesFromReplay(const Model& model, const std::string& dir) {
  const Table ee = ReadTable(dir + "/end_effector.csv");
  const Table bases = ReadTable(dir + "/bases.csv");
  if (ee.rows.size() != bases.rows.size()) {
    throw ViewInputError(dir + ": end_effector.csv has " + std::to_string(ee.rows.size()) +
                         " rows but bases.csv has " + std::to_string(bases.rows.size()));
  }
  const std::vector<int> controls = ControlColumns(model, bases, "base", false);
  const int time = ee.Find("time_s", true);
  const std::array<int, 3> cmd{ee.Find("cmd_x_m", true), ee.Find("cmd_y_m", true), ee.Find("cmd_z_m", true)};
  const std::array<int, 3> tracked{ee.Find("x_m", true), ee.Find("y_m", true), ee.Find("z_m", true)};
  const int torn = ee.Find("torn", false);
  std::vector<ViewFrame> frames;
  for (size_t r = 0; r < ee.rows.size(); ++r) {
    ViewFrame f;
    f.time = Required(ee, r, time);
    f.controls = Controls(model, bases, r, controls);
    f.commanded = Point(ee, r, cmd);
    f.tracked = Point(ee, r, tracked);
    f.flagged = torn >= 0 && ee.rows[r][torn] != 0.0;
    frames.push_back(std::move(f));
  }
  return Thin(std::move(frames), MaxViewFrames(model));
}

}  // namespace ccma::viewer
