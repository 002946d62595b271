#include "viewer/workspace_cloud.h"

#include <array>
#include <cmath>
#include <filesystem>

#include "analyses/workspace.h"
#include "viewer/csv_reader.h"
#include "viewer/view_frames.h"

namespace ccma::viewer {

static_assert(kMaxWorkspaceRows == WorkspaceOptions::kMaxSamples, "a view must accept every map ccma writes");

WorkspaceCloud CloudFromWorkspaceCsv(const Model& model, const std::string& csv_path) {
  // limited_by holds joint names, the one text column of the map. Only the
  // columns drawn are kept: a map's controls (u0, u1, ...) are checked and
  // dropped row by row.
  std::vector<std::string> columns = {"reachable", "sigma_min"};
  for (const char* name : kEndEffectorComponentNames) columns.emplace_back(name);
  CsvReader t(csv_path, CsvLimits{kMaxWorkspaceFileBytes, kMaxWorkspaceRows, {"limited_by"}}, columns);
  const int reachable = t.Find("reachable", true);
  const int sigma_min = t.Find("sigma_min", true);
  // The pose columns are the model's controlled components: another set
  // means a map of another model, whose points would land in the wrong place.
  WorkspaceCloud cloud;
  std::array<int, 3> position{-1, -1, -1};
  for (int c = 0; c < 6; ++c) {
    const std::string name = kEndEffectorComponentNames[static_cast<size_t>(c)];
    const bool controlled = model.end_effector.controlled[static_cast<size_t>(c)];
    const int col = t.Find(name, false);
    if (controlled && col < 0) {
      throw ViewInputError(csv_path + ": no column '" + name + "' in the header (" + model.name +
                           " controls it: is this a map of another model?)");
    }
    if (!controlled && col >= 0) {
      throw ViewInputError(csv_path + ": column '" + name + "': " + model.name +
                           " does not control it (is this a map of another model?)");
    }
    if (col < 0) continue;
    cloud.components.push_back(name);
    if (c < 3) position[static_cast<size_t>(c)] = col;
  }
  cloud.source = std::filesystem::path(csv_path).filename().string();
  const Eigen::Vector3d home = model.end_effector.p_W_home;
  while (t.Next()) {
    Eigen::Vector3d p = home;
    for (int i = 0; i < 3; ++i) {
      const int col = position[static_cast<size_t>(i)];
      if (col < 0) continue;
      if (std::isnan(t.Cell(col))) throw ViewInputError(t.Where(col) + ": empty");
      p[i] = t.Cell(col);
    }
    const double flag = t.Cell(reachable);
    if (!(flag == 0.0 || flag == 1.0)) throw ViewInputError(t.Where(reachable) + ": not 0 or 1");
    const bool reached = flag == 1.0;
    // An unreachable row's sigma_min means nothing (ccma writes 0); the
    // reachable flag says what it is.
    double sigma = 0;
    if (reached) {
      sigma = t.Cell(sigma_min);
      if (!(sigma >= 0)) throw ViewInputError(t.Where(sigma_min) + ": a reachable row needs a number >= 0");
    }
    cloud.points.push_back(p);
    cloud.reachable.push_back(reached ? 1 : 0);
    cloud.sigma_min.push_back(sigma);
    cloud.reachable_count += reached ? 1 : 0;
  }
  return cloud;
}

}  // namespace ccma::viewer
