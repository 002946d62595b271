// The point cloud `ccma view --workspace` draws over the mechanism: one
// end-effector position per row of a `ccma workspace` CSV (docs/workspace.md),
// with whether it was reached and how well conditioned it is there.
//
// Positions: the row's x, y, z where the CSV has them, the end-effector
// point at home (Model::end_effector.p_W_home) for components it lacks.
// Orientation columns (roll, pitch, yaw) are not positions: rows that differ
// only in orientation give the same point.
//
// The file is untrusted: a regular file of at most kMaxWorkspaceFileBytes
// and kMaxWorkspaceRows rows (the most `ccma workspace` writes); the
// columns `reachable` and `sigma_min` and the pose columns of the model's
// controlled components are required (found by name); every cell but
// `limited_by` is empty or a finite number within [-1e6, 1e6]; pose cells
// are not empty, `reachable` is 0 or 1, a reachable row's `sigma_min` is a
// number >= 0. Otherwise ViewInputError naming the file, line and column.
#ifndef CCMA_VIEWER_WORKSPACE_CLOUD_H_
#define CCMA_VIEWER_WORKSPACE_CLOUD_H_

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/model.h"

namespace ccma::viewer {

// A workspace map's rows: WorkspaceOptions::kMaxSamples, the largest grid.
constexpr long kMaxWorkspaceRows = 1000000;
// Its size: a million rows of a six-base model's controls are ~400 MB.
constexpr std::size_t kMaxWorkspaceFileBytes = std::size_t{1} << 30;  // 1 GiB

struct WorkspaceCloud {
  std::vector<Eigen::Vector3d> points;  // end-effector position per row, world frame [m]
  std::vector<char> reachable;          // 1 or 0 per row
  std::vector<double> sigma_min;        // per row [m or rad per control unit]; 0 where unreachable
  std::vector<std::string> components;  // the CSV's pose columns, in the order x y z roll pitch yaw
  std::string source;                   // the CSV's file name (no folder)
  long reachable_count = 0;
};

// Reads and checks `csv_path`, a map of `model` written by `ccma workspace`.
// Throws ViewInputError.
WorkspaceCloud CloudFromWorkspaceCsv(const Model& model, const std::string& csv_path);

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_WORKSPACE_CLOUD_H_
