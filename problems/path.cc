#include "problems/path.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "ccma/rotation.h"

namespace ccma {

PosePath::PosePath(const Model& model, const PoseTarget& from, const PoseTarget& to, double max_step_m,
                   double max_step_rad)
    : from_(from), to_(to) {
  if (!(max_step_m > 0) || !(max_step_rad > 0)) {
    throw std::invalid_argument("path: the step sizes must be positive");
  }
  const auto& controlled = model.end_effector.controlled;
  double squared = 0;
  for (int k = 0; k < 3; ++k) {
    if (controlled[k]) squared += std::pow(to.position[k] - from.position[k], 2);
  }
  distance_ = std::sqrt(squared);
  full_rotation_ = controlled[kRoll] && controlled[kPitch] && controlled[kYaw];
  R_from_ = RotationFromRpy(from.rpy);
  phi_ = QuaternionLog(Eigen::Quaterniond(RotationFromRpy(to.rpy) * R_from_.transpose()));
  angle_change_.setZero();
  angle_ = full_rotation_ ? phi_.norm() : 0.0;
  for (int k = 0; k < 3 && !full_rotation_; ++k) {
    if (!controlled[3 + k]) continue;
    angle_change_[k] = WrapAngle(to.rpy[k] - from.rpy[k]);
    angle_ = std::max(angle_, std::abs(angle_change_[k]));
  }
  // Counted in double and bounded before the conversion to int.
  const double count =
      std::max({1.0, std::ceil(distance_ / max_step_m - 1e-9), std::ceil(angle_ / max_step_rad - 1e-9)});
  if (!(count <= static_cast<double>(kMaxPathSteps))) {
    throw std::invalid_argument("path: " + FormatG(distance_) + " m and " + FormatG(angle_) +
                                " rad in steps of " + FormatG(max_step_m) + " m and " + FormatG(max_step_rad) +
                                " rad would take more than " + std::to_string(kMaxPathSteps) + " steps");
  }
  steps_ = static_cast<int>(count);
}

PoseTarget PosePath::At(int i) const {
  if (i >= steps_) return to_;
  const double t = double(i) / steps_;
  PoseTarget target = to_;
  target.position = from_.position + t * (to_.position - from_.position);
  target.rpy = full_rotation_ ? RpyFromRotation(QuaternionExp(t * phi_).toRotationMatrix() * R_from_)
                              : Eigen::Vector3d(from_.rpy + t * angle_change_);
  return target;
}

}  // namespace ccma
