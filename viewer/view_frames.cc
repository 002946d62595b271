#include "viewer/view_frames.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "ccma/model_loader.h"

namespace ccma::viewer {
namespace {

// A CSV as written by ccma: '#' comment lines, one header, rows of numbers.
struct Table {
  std::string path;
  std::vector<std::string> header;
  std::map<std::string, int> column;
  std::vector<std::vector<double>> rows;
  std::vector<int> lines;  // file line of each row

  // Index of a column, or -1 (optional) / throw (required).
  int Find(const std::string& name, bool required) const {
    const auto it = column.find(name);
    if (it != column.end()) return it->second;
    if (required) throw ViewInputError(path + ": no column '" + Printable(name) + "' in the header");
    return -1;
  }
};

std::vector<std::string> SplitCommas(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

double ParseNumber(const Table& t, int line, const std::string& text, int col) {
  const std::string where = t.path + ":" + std::to_string(line) + ": column '" + Printable(t.header[col]) + "'";
  if (text.empty()) return std::nan("");  // an empty cell (e.g. a failed step's value)
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || errno == ERANGE) {
    throw ViewInputError(where + ": not a number: " + Quote(text));
  }
  if (!std::isfinite(v) || std::abs(v) > kMaxMagnitude * 100) {
    throw ViewInputError(where + ": " + Quote(text) + " is outside [-1e6, 1e6]");
  }
  return v;
}

Table ReadTable(const std::string& path) {
  std::string text, error;
  if (!internal::ReadRegularFile(path, kMaxViewFileBytes, "CSV file", &text, &error)) throw ViewInputError(error);
  Table t;
  t.path = path;
  std::stringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cells = SplitCommas(line);
    if (t.header.empty()) {
      t.header = cells;
      for (size_t i = 0; i < cells.size(); ++i) t.column[cells[i]] = static_cast<int>(i);
      continue;
    }
    if (cells.size() != t.header.size()) {
      throw ViewInputError(path + ":" + std::to_string(number) + ": " + std::to_string(cells.size()) +
                           " cells, the header has " + std::to_string(t.header.size()));
    }
    std::vector<double> row(cells.size());
    for (size_t i = 0; i < cells.size(); ++i) row[i] = ParseNumber(t, number, cells[i], static_cast<int>(i));
    t.rows.push_back(std::move(row));
    t.lines.push_back(number);
    if (t.rows.size() > static_cast<size_t>(kMaxReplaySamples)) {
      throw ViewInputError(path + ": more than " + std::to_string(kMaxReplaySamples) + " rows");
    }
  }
  if (t.header.empty()) throw ViewInputError(path + ": no header line");
  if (t.rows.empty()) throw ViewInputError(path + ": no rows");
  return t;
}

// A value that must be present and finite (controls, times).
double Required(const Table& t, size_t row, int col) {
  const double v = t.rows[row][col];
  if (std::isnan(v)) {
    throw ViewInputError(t.path + ":" + std::to_string(t.lines[row]) + ": column '" + Printable(t.header[col]) +
                         "': empty");
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

Eigen::VectorXd Controls(const Model& model, const Table& t, size_t row, const std::vector<int>& cols) {
  Eigen::VectorXd u = model.home_controls();
  for (size_t i = 0; i < cols.size(); ++i) {
    if (cols[i] >= 0) u[i] = Required(t, row, cols[i]);
  }
  return u;
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
  const Table t = ReadTable(csv_path);
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
