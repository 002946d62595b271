#include "execution/differential_drive.h"

#include <cmath>
#include <stdexcept>

#include "ccma/rotation.h"

namespace ccma {
namespace {

// sin(phi) / phi and (1 - cos(phi)) / phi = 2 sin^2(phi / 2) / phi, both
// accurate to rounding for every phi (1 and 0 at phi = 0).
void ArcFactors(double phi, double* s, double* c) {
  if (phi == 0) {
    *s = 1;
    *c = 0;
    return;
  }
  const double half = std::sin(phi / 2);
  *s = std::sin(phi) / phi;
  *c = 2 * half * half / phi;
}

}  // namespace

DifferentialDriveKinematics::DifferentialDriveKinematics(double track, double radius)
    : track_(track), radius_(radius) {
  if (!(std::isfinite(track) && track > 0)) {
    throw std::invalid_argument("differential drive: track (distance between the wheels) must be positive and "
                                "finite [m]");
  }
  if (!(std::isfinite(radius) && radius > 0)) {
    throw std::invalid_argument("differential drive: wheel radius must be positive and finite [m]");
  }
}

Eigen::Vector2d DifferentialDriveKinematics::WheelSpeeds(double v, double omega) const {
  const double half = omega * track_ / 2;
  return Eigen::Vector2d((v - half) / radius_, (v + half) / radius_);
}

Eigen::Vector2d DifferentialDriveKinematics::Twist(double left, double right) const {
  return Eigen::Vector2d(radius_ * (left + right) / 2, radius_ * (right - left) / track_);
}

double LateralDisplacement(const Eigen::Vector3d& pose0, const Eigen::Vector3d& pose1) {
  const double mid = pose0.z() + WrapAngle(pose1.z() - pose0.z()) / 2;
  return -std::sin(mid) * (pose1.x() - pose0.x()) + std::cos(mid) * (pose1.y() - pose0.y());
}

Arc ArcBetween(const Eigen::Vector3d& pose0, const Eigen::Vector3d& pose1) {
  Arc arc;
  arc.heading_change = WrapAngle(pose1.z() - pose0.z());
  const double mid = pose0.z() + arc.heading_change / 2;
  const double dx = pose1.x() - pose0.x(), dy = pose1.y() - pose0.y();
  const double chord = std::cos(mid) * dx + std::sin(mid) * dy;
  arc.lateral = -std::sin(mid) * dx + std::cos(mid) * dy;
  const double half = arc.heading_change / 2;
  // |half| <= pi/2: sin(half) / half lies in [2/pi, 1].
  arc.length = half == 0 ? chord : chord * half / std::sin(half);
  return arc;
}

Eigen::Vector3d AlongArc(const Eigen::Vector3d& pose, double length, double heading_change) {
  double s = 0, c = 0;
  ArcFactors(heading_change, &s, &c);
  // Displacement in the start frame: length * (s, c); then into the world.
  const double bx = length * s, by = length * c;
  const double cos0 = std::cos(pose.z()), sin0 = std::sin(pose.z());
  return Eigen::Vector3d(pose.x() + cos0 * bx - sin0 * by, pose.y() + sin0 * bx + cos0 * by,
                         pose.z() + heading_change);
}

Eigen::Vector3d InterpolateArc(const Eigen::Vector3d& pose0, const Eigen::Vector3d& pose1, double s) {
  const Arc arc = ArcBetween(pose0, pose1);
  Eigen::Vector3d pose = AlongArc(pose0, s * arc.length, s * arc.heading_change);
  if (arc.lateral != 0) {
    const Eigen::Vector3d end = AlongArc(pose0, arc.length, arc.heading_change);
    pose.head<2>() += s * (pose1.head<2>() - end.head<2>());
  }
  return pose;
}

}  // namespace ccma
