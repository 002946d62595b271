#include "documents/control_path_csv.h"

#include <cmath>
#include <optional>
#include <vector>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "viewer/csv_reader.h"
#include "viewer/view_frames.h"

namespace ccma::documents {
namespace {

using viewer::CsvReader;
using viewer::ViewInputError;

viewer::CsvLimits PathLimits() {
  return viewer::CsvLimits{viewer::kMaxViewFileBytes, kMaxPathSteps + 1, {"clearance_pair"}};
}

double Present(const CsvReader& t, int col) {
  const double v = t.Cell(col);
  if (std::isnan(v)) throw ViewInputError(t.Where(col) + ": empty");
  return v;
}

ControlPath ReadRows(const Model& model, CsvReader& t) {
  const std::vector<std::string> names = viewer::TrajectoryControlColumns(model);
  ControlPath path;
  path.source = t.path();
  const int time = t.Find("time_s", true);
  std::vector<int> controls;
  for (const std::string& name : names) controls.push_back(t.Find(name, true));
  const int reached[3] = {t.Find("x_m", false), t.Find("y_m", false), t.Find("z_m", false)};
  while (t.Next()) {
    const double now = Present(t, time);
    if (!path.times.empty() && !(now > path.times.back())) {
      throw ViewInputError(t.Where(time) + ": " + FormatG(now) + " is not after the previous row's " +
                           FormatG(path.times.back()) + " (times must increase)");
    }
    Eigen::VectorXd u(static_cast<Eigen::Index>(controls.size()));
    for (size_t i = 0; i < controls.size(); ++i) {
      u[static_cast<Eigen::Index>(i)] = Present(t, controls[i]);
      if (!(std::abs(u[static_cast<Eigen::Index>(i)]) <= kMaxMagnitude)) {
        throw ViewInputError(t.Where(controls[i]) + ": a control outside [-1e4, 1e4] (m or rad)");
      }
    }
    std::optional<Eigen::Vector3d> point;
    if (reached[0] >= 0 && reached[1] >= 0 && reached[2] >= 0) {
      const Eigen::Vector3d p(t.Cell(reached[0]), t.Cell(reached[1]), t.Cell(reached[2]));
      if (p.allFinite()) point = p;
    }
    path.times.push_back(now);
    path.controls.push_back(u);
    path.lines.push_back(t.line());
    path.reached.push_back(point);
  }
  if (path.times.size() < 2) throw ViewInputError(t.path() + ": one row; dynamics needs at least two (a motion)");
  return path;
}

}  // namespace

ControlPath ReadControlPath(const Model& model, const std::string& csv_path) {
  std::vector<std::string> columns = viewer::TrajectoryControlColumns(model);
  columns.insert(columns.end(), {"time_s", "x_m", "y_m", "z_m"});
  CsvReader t(csv_path, PathLimits(), columns);
  return ReadRows(model, t);
}

ControlPath ReadControlPathText(const Model& model, const std::string& text, const std::string& source) {
  std::vector<std::string> columns = viewer::TrajectoryControlColumns(model);
  columns.insert(columns.end(), {"time_s", "x_m", "y_m", "z_m"});
  CsvReader t(&text, source, PathLimits(), columns);
  return ReadRows(model, t);
}

}  // namespace ccma::documents
