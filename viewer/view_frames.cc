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

// Columns of the controls: each base's (`prefix`k_x_m ...: its type's
// controls and units), then actuated joints.
std::vector<int> ControlColumns(const Model& model, const Table& t, const std::string& prefix, bool joints_required) {
  std::vector<int> cols;
  for (int k = 0; k < model.num_bases(); ++k) {
    const std::string p = prefix + std::to_string(k);
    for (const BaseControl& c : KindOf(model.mobile_bases[static_cast<size_t>(k)]).controls()) {
      cols.push_back(t.Find(p + "_" + c.name + "_" + c.unit, true));
    }
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

// Where a table's frames are: the time, the commanded and the tracked point
// (in `points`), the controls (in `control_table`), and the column that flags
// a frame (-1 when absent), any value but `unflagged` flagging it.
struct FrameColumns {
  int time = -1;
  std::array<int, 3> commanded{}, tracked{};
  std::vector<int> controls;
  int flag = -1;
  double unflagged = 0;
};

std::vector<ViewFrame> FramesFromColumns(const Model& model, const Table& points, const Table& control_table,
                                         const FrameColumns& c) {
  std::vector<ViewFrame> frames;
  for (size_t r = 0; r < points.rows.size(); ++r) {
    ViewFrame f;
    f.time = Required(points, r, c.time);
    f.controls = Controls(model, control_table, r, c.controls);
    f.commanded = Point(points, r, c.commanded);
    f.tracked = Point(points, r, c.tracked);
    f.flagged = c.flag >= 0 && points.rows[r][c.flag] != c.unflagged;
    frames.push_back(std::move(f));
  }
  return Thin(std::move(frames), MaxViewFrames(model));
}

// The frames of a trajectory CSV's table (FramesFromTrajectory): a frame is
// flagged when its `reached` is not 1.
std::vector<ViewFrame> FramesFromTrajectoryTable(const Model& model, const Table& t) {
  FrameColumns c;
  c.controls = ControlColumns(model, t, "u", true);
  c.time = t.Find("time_s", true);
  c.commanded = {t.Find("target_x_m", true), t.Find("target_y_m", true), t.Find("target_z_m", true)};
  c.tracked = {t.Find("x_m", true), t.Find("y_m", true), t.Find("z_m", true)};
  c.flag = t.Find("reached", false);
  c.unflagged = 1.0;
  return FramesFromColumns(model, t, t, c);
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
  FrameColumns c;  // a frame is flagged when the replay tore the mechanism
  c.controls = ControlColumns(model, bases, "base", false);
  c.time = ee.Find("time_s", true);
  c.commanded = {ee.Find("cmd_x_m", true), ee.Find("cmd_y_m", true), ee.Find("cmd_z_m", true)};
  c.tracked = {ee.Find("x_m", true), ee.Find("y_m", true), ee.Find("z_m", true)};
  c.flag = ee.Find("torn", false);
  return FramesFromColumns(model, ee, bases, c);
}

}  // namespace ccma::viewer
