// Differential-drive (unicycle) kinematics of a mobile base with two driven
// wheels on one axle (docs/model_format.md, "Differential-drive bases"), and
// the geometry of its motions: one step between two poses is one circular
// arc (or a straight line, or a turn on the spot).
//
// The base frame B has x along the heading; the wheels sit at y = +track/2
// (left) and y = -track/2 (right). With the body twist v [m/s] along x and
// omega [rad/s] about z (Siegwart et al., Section 3.2.4):
//   left  = (v - omega * track / 2) / radius     [rad/s]
//   right = (v + omega * track / 2) / radius
// and the base never moves along its own y axis.
// Poses are (x [m], y [m], theta [rad]) of the base frame in the world.
#ifndef CCMA_DIFFERENTIAL_DRIVE_H_
#define CCMA_DIFFERENTIAL_DRIVE_H_

#include <cmath>

#include <Eigen/Core>

namespace ccma {

class DifferentialDriveKinematics {
 public:
  // Throws std::invalid_argument unless track [m] and radius [m] are both
  // positive and finite.
  DifferentialDriveKinematics(double track, double radius);

  // Inverse kinematics: (left, right) wheel speeds [rad/s] for the body
  // twist v [m/s], omega [rad/s].
  Eigen::Vector2d WheelSpeeds(double v, double omega) const;
  // Forward kinematics: (v [m/s], omega [rad/s]) for wheel speeds [rad/s].
  Eigen::Vector2d Twist(double left, double right) const;

  double track() const { return track_; }
  double radius() const { return radius_; }

 private:
  double track_;
  double radius_;
};

// The contract's feasibility bound on a step's lateral displacement [m].
constexpr double kMaxLateralDisplacement = 1e-9;

// The lateral displacement [m] of a step from pose0 to pose1:
//   -sin(theta_mid) dx + cos(theta_mid) dy,
// theta_mid = theta0 + WrapAngle(theta1 - theta0) / 2 (the mean heading the
// short way round). Zero exactly when the step is one arc.
double LateralDisplacement(const Eigen::Vector3d& pose0, const Eigen::Vector3d& pose1);

// One constant-curvature motion from pose0.
struct Arc {
  // Signed distance driven along the heading [m] (negative: backwards); 0
  // for a turn on the spot.
  double length = 0;
  // Heading change [rad] in (-pi, pi] (the short way); 0 for a straight line.
  double heading_change = 0;
  // The step's lateral displacement [m] (LateralDisplacement): the part of
  // the displacement no arc from pose0 can produce. Where it is not ~0 the
  // arc joins pose0 to pose1 shifted sideways by it.
  double lateral = 0;

  // The step is one arc (|lateral| <= tolerance [m]).
  bool feasible(double tolerance = kMaxLateralDisplacement) const { return std::abs(lateral) <= tolerance; }
};

// The arc from pose0 to pose1: heading change WrapAngle(theta1 - theta0)
// and the arc length whose chord, along theta_mid, has pose1's component
// cos(theta_mid) dx + sin(theta_mid) dy:
//   length = chord * (dtheta / 2) / sin(dtheta / 2)   (chord when dtheta = 0).
Arc ArcBetween(const Eigen::Vector3d& pose0, const Eigen::Vector3d& pose1);

// The pose reached from `pose` by driving `length` [m] along the heading
// while turning by `heading_change` [rad] at constant curvature (exact: the
// unicycle's motion under a constant twist).
Eigen::Vector3d AlongArc(const Eigen::Vector3d& pose, double length, double heading_change);

// The pose a fraction s in [0, 1] of the way along ArcBetween(pose0, pose1):
// AlongArc(pose0, s * length, s * heading_change), plus s times the lateral
// residue (so s = 1 gives pose1's position even for an infeasible step).
// Its heading is theta0 + s * heading_change.
Eigen::Vector3d InterpolateArc(const Eigen::Vector3d& pose0, const Eigen::Vector3d& pose1, double s);

}  // namespace ccma

#endif  // CCMA_DIFFERENTIAL_DRIVE_H_
