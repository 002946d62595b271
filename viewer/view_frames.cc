#include "viewer/view_frames.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "viewer/csv_reader.h"

namespace ccma::viewer {
namespace {

// A trajectory's clearance_pair (cli.md) names two shapes: text.
CsvLimits ViewLimits() { return CsvLimits{kMaxViewFileBytes, kMaxReplaySamples, {"clearance_pair"}}; }

// A value that must be present and finite (controls, times).
double Required(const CsvReader& t, int col) {
  const double v = t.Cell(col);
  if (std::isnan(v)) throw ViewInputError(t.Where(col) + ": empty");
  return v;
}

std::optional<Eigen::Vector3d> Point(const CsvReader& t, const std::array<int, 3>& cols) {
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) p[i] = t.Cell(cols[i]);
  if (!p.allFinite()) return std::nullopt;
  return p;
}

std::string JointUnit(const Joint& j) { return j.type == JointType::kRevolute ? "_rad" : "_m"; }

// A control's column: its name and whether a file must have it.
struct ControlColumn {
  std::string name;
  bool required = true;
};

// The columns of the controls: each base's (`prefix`k_x_m ...: its type's
// controls and units, required), then actuated joints'.
std::vector<ControlColumn> ControlColumnNames(const Model& model, const std::string& prefix, bool joints_required) {
  std::vector<ControlColumn> columns;
  for (int k = 0; k < model.num_bases(); ++k) {
    const std::string p = prefix + std::to_string(k);
    for (const BaseControl& c : KindOf(model.mobile_bases[static_cast<size_t>(k)]).controls()) {
      columns.push_back({p + "_" + c.name + "_" + c.unit, true});
    }
  }
  for (const Joint& j : model.joints) {
    if (j.actuated) columns.push_back({"u_" + j.name + JointUnit(j), joints_required});
  }
  return columns;
}

std::vector<std::string> Names(const std::vector<ControlColumn>& columns, std::vector<std::string> more) {
  for (const ControlColumn& c : columns) more.push_back(c.name);
  return more;
}

std::vector<int> Find(const CsvReader& t, const std::vector<ControlColumn>& columns) {
  std::vector<int> cols;
  for (const ControlColumn& c : columns) cols.push_back(t.Find(c.name, c.required));
  return cols;
}

// A row's controls. Cells may hold up to 1e6 (times), but a control must lie
// within kMaxMagnitude as everywhere else: refused here, naming the cell,
// rather than later by the solver without file or line.
Eigen::VectorXd Controls(const Model& model, const CsvReader& t, const std::vector<int>& cols) {
  Eigen::VectorXd u = model.home_controls();
  for (size_t i = 0; i < cols.size(); ++i) {
    if (cols[i] < 0) continue;
    u[i] = Required(t, cols[i]);
    if (!(std::abs(u[i]) <= kMaxMagnitude)) {
      throw ViewInputError(t.Where(cols[i]) + ": a control of " + FormatG(u[i]) + " is outside [-1e4, 1e4] (m or rad)");
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

// Which of n rows become frames: Thin's choice, ascending.
std::vector<long> KeptRows(long n, int max_frames) {
  std::vector<long> rows;
  if (n <= max_frames || max_frames < 2) {
    for (long i = 0; i < n; ++i) rows.push_back(i);
    return rows;
  }
  for (int i = 0; i < max_frames; ++i) rows.push_back(std::lround(static_cast<double>(i) * (n - 1) / (max_frames - 1)));
  return rows;
}

// Reads both tables through (the same one, or two of as many rows), every
// row checked, and keeps as frames only the rows Thin would keep: the
// memory is that of the frames drawn, whatever the file's length.
std::vector<ViewFrame> FramesFromColumns(const Model& model, CsvReader& points, CsvReader& control_table,
                                         const FrameColumns& c, long rows) {
  const std::vector<long> kept = KeptRows(rows, MaxViewFrames(model));
  std::vector<ViewFrame> frames;
  frames.reserve(kept.size());
  size_t next = 0;
  while (points.Next()) {
    if (&control_table != &points && !control_table.Next()) break;
    ViewFrame f;
    f.time = Required(points, c.time);
    f.controls = Controls(model, control_table, c.controls);
    if (next >= kept.size() || kept[next] != points.row()) continue;
    f.commanded = Point(points, c.commanded);
    f.tracked = Point(points, c.tracked);
    f.flagged = c.flag >= 0 && points.Cell(c.flag) != c.unflagged;
    frames.push_back(std::move(f));
    ++next;
  }
  if (points.row() + 1 != rows || control_table.row() + 1 != rows) {
    throw ViewInputError(points.path() + ": the file changed while it was read");
  }
  return frames;
}

// The columns of a trajectory CSV that become frames (FramesFromTrajectory).
const std::vector<std::string> kTrajectoryColumns = {"time_s", "target_x_m", "target_y_m", "target_z_m",
                                                     "x_m",    "y_m",        "z_m",        "reached"};

// The frames of a trajectory CSV (FramesFromTrajectory): a frame is flagged
// when its `reached` is not 1.
std::vector<ViewFrame> FramesFromTrajectoryReader(const Model& model, CsvReader& t,
                                                  const std::vector<ControlColumn>& controls) {
  const long rows = t.CountRows();  // first: a file's shape, then its columns
  FrameColumns c;
  c.controls = Find(t, controls);
  c.time = t.Find("time_s", true);
  c.commanded = {t.Find("target_x_m", true), t.Find("target_y_m", true), t.Find("target_z_m", true)};
  c.tracked = {t.Find("x_m", true), t.Find("y_m", true), t.Find("z_m", true)};
  c.flag = t.Find("reached", false);
  c.unflagged = 1.0;
  return FramesFromColumns(model, t, t, c, rows);
}

}  // namespace

std::vector<std::string> TrajectoryControlColumns(const Model& model) {
  return Names(ControlColumnNames(model, "u", true), {});
}

std::vector<std::string> EffortColumns(const Model& model) {
  std::vector<std::string> out;
  for (const std::string& name : TrajectoryControlColumns(model)) {
    const size_t cut = name.rfind('_');
    out.push_back(name.substr(0, cut) + (name.substr(cut + 1) == "rad" ? "_Nm" : "_N"));
  }
  return out;
}

int MaxViewFrames(const Model& model) {
  const long by_poses = kMaxViewPoses / std::max(1, model.num_bodies());
  return static_cast<int>(std::max(2L, std::min<long>(kMaxViewFrames, by_poses)));
}

std::vector<ViewFrame> Thin(std::vector<ViewFrame> frames, int max_frames) {
  const std::vector<long> rows = KeptRows(static_cast<long>(frames.size()), max_frames);
  if (rows.size() == frames.size()) return frames;
  std::vector<ViewFrame> kept;
  kept.reserve(rows.size());
  for (long index : rows) kept.push_back(std::move(frames[static_cast<size_t>(index)]));
  return kept;
}

std::vector<ViewFrame> FramesFromTrajectory(const Model& model, const std::string& csv_path) {
  const std::vector<ControlColumn> controls = ControlColumnNames(model, "u", true);
  CsvReader t(csv_path, ViewLimits(), Names(controls, kTrajectoryColumns));
  return FramesFromTrajectoryReader(model, t, controls);
}

std::vector<ViewFrame> FramesFromTrajectoryText(const Model& model, const std::string& text,
                                                const std::string& source) {
  const std::vector<ControlColumn> controls = ControlColumnNames(model, "u", true);
  CsvReader t(&text, source, ViewLimits(), Names(controls, kTrajectoryColumns));
  return FramesFromTrajectoryReader(model, t, controls);
}

std::vector<ViewFrame> FramesFromReplay(const Model& model, const std::string& dir) {
  CsvReader ee(dir + "/end_effector.csv", ViewLimits(),
               {"time_s", "cmd_x_m", "cmd_y_m", "cmd_z_m", "x_m", "y_m", "z_m", "torn"});
  const std::vector<ControlColumn> controls = ControlColumnNames(model, "base", false);
  CsvReader bases(dir + "/bases.csv", ViewLimits(), Names(controls, {}));
  const long ee_rows = ee.CountRows(), base_rows = bases.CountRows();
  if (ee_rows != base_rows) {
    throw ViewInputError(dir + ": end_effector.csv has " + std::to_string(ee_rows) + " rows but bases.csv has " +
                         std::to_string(base_rows));
  }
  FrameColumns c;  // a frame is flagged when the replay tore the mechanism
  c.controls = Find(bases, controls);
  c.time = ee.Find("time_s", true);
  c.commanded = {ee.Find("cmd_x_m", true), ee.Find("cmd_y_m", true), ee.Find("cmd_z_m", true)};
  c.tracked = {ee.Find("x_m", true), ee.Find("y_m", true), ee.Find("z_m", true)};
  c.flag = ee.Find("torn", false);
  return FramesFromColumns(model, ee, bases, c, ee_rows);
}

}  // namespace ccma::viewer
