#include "ccma/rotation.h"

#include <cmath>

namespace ccma {

Eigen::Quaterniond QuaternionExp(const Eigen::Vector3d& w) {
  const double theta_sq = w.squaredNorm();
  double real, imag_factor;
  if (theta_sq < 1e-16) {
    // sin(t/2)/t = 1/2 - t^2/48 + ...; cos(t/2) = 1 - t^2/8 + ...
    real = 1.0 - theta_sq / 8.0;
    imag_factor = 0.5 - theta_sq / 48.0;
  } else {
    const double theta = std::sqrt(theta_sq);
    real = std::cos(0.5 * theta);
    imag_factor = std::sin(0.5 * theta) / theta;
  }
  Eigen::Quaterniond q(real, imag_factor * w.x(), imag_factor * w.y(),
                       imag_factor * w.z());
  q.normalize();
  return q;
}

Eigen::Vector3d QuaternionLog(const Eigen::Quaterniond& q_in) {
  // Use the representative with w >= 0 so the angle lies in [0, pi].
  Eigen::Quaterniond q = q_in.w() < 0 ? Eigen::Quaterniond(-q_in.coeffs()) : q_in;
  const Eigen::Vector3d v = q.vec();
  const double sin_half = v.norm();
  if (sin_half < 1e-12) return 2.0 * v / q.w();  // small angle: 2 v / w
  const double half = std::atan2(sin_half, q.w());
  return (2.0 * half / sin_half) * v;
}

Eigen::Matrix3d RotationZ(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Matrix3d RotationFromRpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d RpyFromRotation(const Eigen::Matrix3d& R) {
  // R(2,0) = -sin(pitch); R(2,1) = cos(p) sin(r); R(2,2) = cos(p) cos(r).
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
  // Roll from the last row; at gimbal lock (cos(p) = 0) only yaw -/+ roll is
  // defined, and roll is reported as 0.
  const double roll = std::hypot(R(2, 1), R(2, 2)) < 1e-15 ? 0.0 : std::atan2(R(2, 1), R(2, 2));
  // Yaw from the second column with roll taken out (Rz(y) = R Rx(r)^T Ry(p)^T):
  // well conditioned at every pitch, so R round-trips even near the lock,
  // where entries like R(1,0) = cos(p) sin(y) lose all their digits.
  const double s = std::sin(roll), c = std::cos(roll);
  const double yaw = std::atan2(s * R(0, 2) - c * R(0, 1), c * R(1, 1) - s * R(1, 2));
  return {roll, pitch, yaw};
}

double WrapAngle(double angle) {
  double a = std::remainder(angle, 2.0 * M_PI);  // in [-pi, pi]
  if (a <= -M_PI) a += 2.0 * M_PI;
  return a;
}

}  // namespace ccma
