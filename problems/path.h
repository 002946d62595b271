// Straight end-effector paths, split into small steps (paper Section III-B:
// the controller walks to a target in steps of ~10 mm and 0.005 rad).
//
// Over the model's controlled components only: the translation is a straight
// line; the rotation is the geodesic (slerp) when roll, pitch and yaw are all
// controlled, otherwise each controlled angle moves linearly the short way.
#ifndef CCMA_PROBLEMS_PATH_H_
#define CCMA_PROBLEMS_PATH_H_

#include <Eigen/Core>

#include "ccma/end_effector.h"
#include "ccma/model.h"

namespace ccma {

class PosePath {
 public:
  // From `from` to `to` in steps of at most max_step_m [m] of translation and
  // max_step_rad [rad] of rotation (both > 0). Throws std::invalid_argument if
  // that takes more than kMaxPathSteps steps (ccma/limits.h).
  PosePath(const Model& model, const PoseTarget& from, const PoseTarget& to, double max_step_m,
           double max_step_rad);

  // Number of steps (>= 1).
  int steps() const { return steps_; }
  // The target of step i in [1, steps()]; At(steps()) is `to` exactly.
  PoseTarget At(int i) const;
  // Length of the path over the controlled components: translation [m] and
  // largest rotation [rad].
  double distance_m() const { return distance_; }
  double angle_rad() const { return angle_; }

 private:
  PoseTarget from_, to_;
  bool full_rotation_ = false;
  Eigen::Matrix3d R_from_;
  Eigen::Vector3d phi_;           // geodesic rotation vector (full rotation)
  Eigen::Vector3d angle_change_;  // per-angle change (subset of angles)
  double distance_ = 0, angle_ = 0;
  int steps_ = 1;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_PATH_H_
