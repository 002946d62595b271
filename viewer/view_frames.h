// What `ccma view` animates: a list of frames, each the controls to assemble
// the mechanism at, with the end-effector paths to draw. Read from the files
// other commands write: a trajectory CSV (`ccma trajectory`) or a replay
// directory (`ccma replay`: end_effector.csv and bases.csv).
//
// The files are untrusted: each must be a regular file of at most
// kMaxViewFileBytes; columns are found by their header names; every number
// must be finite and within kMaxMagnitude (ccma/limits.h); messages name the
// file, line and column. Long recordings are thinned evenly to at most
// MaxViewFrames(model) frames (first and last always kept).
#ifndef CCMA_VIEWER_VIEW_FRAMES_H_
#define CCMA_VIEWER_VIEW_FRAMES_H_

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/model.h"

namespace ccma::viewer {

// Bad input for the viewer; the message names file, line and column.
class ViewInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

constexpr std::size_t kMaxViewFileBytes = std::size_t{256} << 20;  // 256 MiB
constexpr int kMaxViewFrames = 2000;       // frames in one page
constexpr long kMaxViewPoses = 200000;     // frames x bodies in one page

struct ViewFrame {
  double time = 0;                     // s
  Eigen::VectorXd controls;            // Model::num_controls() entries
  std::optional<Eigen::Vector3d> commanded;  // end-effector target / commanded [m]
  std::optional<Eigen::Vector3d> tracked;    // end-effector reached / tracked [m]
  bool flagged = false;                // the source marked it (not reached, torn)
};

// At most kMaxViewFrames frames, and at most kMaxViewPoses poses in all.
int MaxViewFrames(const Model& model);

// The control columns of a trajectory CSV for this model, in control order
// (u<k>_x_m, u<k>_y_m, u<k>_theta_rad ..., then u_<joint>_rad|_m): the
// names `ccma trajectory` writes and `ccma dynamics` reads.
std::vector<std::string> TrajectoryControlColumns(const Model& model);

// The effort column of each control in a `ccma dynamics` CSV, control order:
// the control column with its unit replaced (u0_x_m -> u0_x_N, u0_theta_rad
// -> u0_theta_Nm, u_<joint>_rad -> u_<joint>_Nm, u_<joint>_m -> u_<joint>_N).
std::vector<std::string> EffortColumns(const Model& model);

// Rows of a `ccma trajectory` CSV: controls from u<k>_x_m, u<k>_y_m,
// u<k>_theta_rad and u_<joint>_rad|_m; commanded = target_x_m.., tracked =
// x_m..; flagged where reached is 0. Throws ViewInputError (naming file,
// line and column) for a bad cell, including a control outside [-1e4, 1e4].
std::vector<ViewFrame> FramesFromTrajectory(const Model& model, const std::string& csv_path);

// The same for the text of a trajectory CSV already in memory; `source`
// names it in messages.
std::vector<ViewFrame> FramesFromTrajectoryText(const Model& model, const std::string& text,
                                                const std::string& source);

// Samples of a `ccma replay` directory: controls from bases.csv (true poses
// base<k>_x_m.., actuated joints u_<joint>_.. when present, else home),
// commanded cmd_x_m.. and tracked x_m.. from end_effector.csv; flagged where
// torn. Throws ViewInputError as FramesFromTrajectory does.
std::vector<ViewFrame> FramesFromReplay(const Model& model, const std::string& dir);

// Keeps at most `max_frames` frames, evenly spread, first and last included.
std::vector<ViewFrame> Thin(std::vector<ViewFrame> frames, int max_frames);

}  // namespace ccma::viewer

#endif  // CCMA_VIEWER_VIEW_FRAMES_H_
