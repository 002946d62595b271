// Differential-drive bases: unicycle kinematics, the arc joining two poses,
// the tracking law, the exact simulation, and closed-loop replays of models
// with differential (and mixed omni and differential) bases.
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "execution/base_tracking.h"
#include "execution/differential_drive.h"
#include "formats/model_loader.h"
#include "ccma/rotation.h"
#include "execution/replay.h"

namespace ccma {
namespace differential_drive_test {

const double kNaN = std::nan("");
const double kInf = HUGE_VAL;

// ---------------------------------------------------------------- kinematics

TEST(DifferentialDriveKinematics, RejectsGeometryThatIsNotPositiveAndFinite) {
  for (const double bad : {0.0, -0.3, kNaN, kInf, -kInf}) {
    EXPECT_THROW(DifferentialDriveKinematics(bad, 0.05), std::invalid_argument) << bad;
    EXPECT_THROW(DifferentialDriveKinematics(0.3, bad), std::invalid_argument) << bad;
  }
  EXPECT_NO_THROW(DifferentialDriveKinematics(0.3, 0.05));
}

TEST(DifferentialDriveKinematics, InverseThenForwardIsTheIdentity) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-2, 2);
  for (const auto& [track, radius] : {std::pair{0.3, 0.05}, std::pair{0.05, 0.2}, std::pair{1.7, 0.011}}) {
    const DifferentialDriveKinematics k(track, radius);
    for (int trial = 0; trial < 100; ++trial) {
      const double v = d(rng), omega = d(rng);
      const Eigen::Vector2d wheels = k.WheelSpeeds(v, omega);
      const Eigen::Vector2d twist = k.Twist(wheels.x(), wheels.y());
      EXPECT_NEAR(twist.x(), v, 1e-14);
      EXPECT_NEAR(twist.y(), omega, 1e-13);
      // And forward then inverse.
      const double left = d(rng) * 10, right = d(rng) * 10;
      const Eigen::Vector2d t = k.Twist(left, right);
      EXPECT_LT((k.WheelSpeeds(t.x(), t.y()) - Eigen::Vector2d(left, right)).norm(), 1e-12);
    }
  }
}

TEST(DifferentialDriveKinematics, WheelSpeedsWorkedOutByHand) {
  const DifferentialDriveKinematics k(0.3, 0.05);  // track 0.3 m, radius 0.05 m
  // Pure rotation at 2 rad/s: each wheel runs the rim speed 2 * 0.15 = 0.3 m/s,
  // left backwards: left = -right = omega track / (2 radius) = 6 rad/s.
  EXPECT_NEAR(k.WheelSpeeds(0, 2).x(), -6.0, 1e-14);
  EXPECT_NEAR(k.WheelSpeeds(0, 2).y(), 6.0, 1e-14);
  // Straight at 0.5 m/s: both 0.5 / 0.05 = 10 rad/s.
  EXPECT_NEAR(k.WheelSpeeds(0.5, 0).x(), 10.0, 1e-14);
  EXPECT_NEAR(k.WheelSpeeds(0.5, 0).y(), 10.0, 1e-14);
  // 0.3 m/s on a 0.3 m radius (omega 1 rad/s, turning left): the left wheel
  // on a 0.15 m circle (3 rad/s), the right on a 0.45 m circle (9 rad/s).
  EXPECT_NEAR(k.WheelSpeeds(0.3, 1).x(), 3.0, 1e-14);
  EXPECT_NEAR(k.WheelSpeeds(0.3, 1).y(), 9.0, 1e-14);
  // Left wheel held, right at 4 rad/s: pivots about the left wheel,
  // v = 4 * 0.05 / 2 = 0.1 m/s, omega = 4 * 0.05 / 0.3 = 2/3 rad/s.
  EXPECT_NEAR(k.Twist(0, 4).x(), 0.1, 1e-15);
  EXPECT_NEAR(k.Twist(0, 4).y(), 2.0 / 3.0, 1e-15);
}

// ---------------------------------------------------------------- arcs

TEST(ArcBetween, AStraightLineForwardsAndBackwards) {
  const Eigen::Vector3d p0(1.0, 2.0, 0.3);
  const Eigen::Vector3d ahead(1.0 + 0.7 * std::cos(0.3), 2.0 + 0.7 * std::sin(0.3), 0.3);
  const Arc forward = ArcBetween(p0, ahead);
  EXPECT_NEAR(forward.length, 0.7, 1e-15);
  EXPECT_EQ(forward.heading_change, 0.0);
  EXPECT_NEAR(forward.lateral, 0.0, 1e-15);
  EXPECT_TRUE(forward.feasible());
  const Arc backward = ArcBetween(ahead, p0);
  EXPECT_NEAR(backward.length, -0.7, 1e-15);
  EXPECT_NEAR(backward.lateral, 0.0, 1e-15);
  EXPECT_LT((AlongArc(p0, 0.7, 0) - ahead).norm(), 1e-15);
}

TEST(ArcBetween, AQuarterCircleHasLengthPiRadiusOverTwo) {
  const double R = 0.4;
  // Counter-clockwise from the origin facing +x: ends at (R, R) facing +y.
  const Arc left = ArcBetween({0, 0, 0}, {R, R, M_PI / 2});
  EXPECT_NEAR(left.length, M_PI * R / 2, 1e-15);  // 0.6283185...
  EXPECT_NEAR(left.heading_change, M_PI / 2, 1e-15);
  EXPECT_NEAR(left.lateral, 0.0, 1e-15);
  // Clockwise, from a start turned by 1 rad and shifted: the same length.
  const Eigen::Vector3d p0(0.5, -0.2, 1.0);
  const Eigen::Matrix2d R0 = Eigen::Rotation2Dd(1.0).toRotationMatrix();
  Eigen::Vector3d p1;
  p1.head<2>() = p0.head<2>() + R0 * Eigen::Vector2d(R, -R);
  p1.z() = 1.0 - M_PI / 2;
  const Arc right = ArcBetween(p0, p1);
  EXPECT_NEAR(right.length, M_PI * R / 2, 1e-14);
  EXPECT_NEAR(right.heading_change, -M_PI / 2, 1e-15);
  EXPECT_NEAR(right.lateral, 0.0, 1e-15);
  // Driving that arc lands on p1; its midpoint is on the circle, 45 degrees round.
  EXPECT_LT((AlongArc(p0, right.length, right.heading_change) - p1).norm(), 1e-15);
  const Eigen::Vector3d mid = InterpolateArc(p0, p1, 0.5);
  const Eigen::Vector2d centre = p0.head<2>() + R0 * Eigen::Vector2d(0, -R);
  EXPECT_NEAR((mid.head<2>() - centre).norm(), R, 1e-15);
  EXPECT_NEAR(mid.z(), 1.0 - M_PI / 4, 1e-15);
  // A half circle (heading change pi): length pi R.
  EXPECT_NEAR(ArcBetween({0, 0, 0}, {0, 2 * R, M_PI - 1e-12}).length, M_PI * R, 1e-12);
}

TEST(ArcBetween, ATurnOnTheSpotHasNoLengthAndTurnsTheShortWay) {
  const Arc turn = ArcBetween({0.2, -0.1, 0.5}, {0.2, -0.1, 2.0});
  EXPECT_EQ(turn.length, 0.0);
  EXPECT_NEAR(turn.heading_change, 1.5, 1e-15);
  EXPECT_EQ(turn.lateral, 0.0);
  // From 3.0 to -3.0 rad: 2 pi - 6 = 0.283 rad counter-clockwise, not 6 rad back.
  EXPECT_NEAR(ArcBetween({0, 0, 3.0}, {0, 0, -3.0}).heading_change, 2 * M_PI - 6.0, 1e-15);
  // Across the wrap the arc still has its length (a straight line at theta = pi).
  const Arc across = ArcBetween({0, 0, M_PI - 0.1}, {-0.5, 0, -M_PI + 0.1});
  EXPECT_NEAR(across.heading_change, 0.2, 1e-15);
  EXPECT_NEAR(across.lateral, 0.0, 1e-15);
  EXPECT_NEAR(across.length, 0.5 * 0.1 / std::sin(0.1), 1e-15);
}

TEST(LateralDisplacement, ZeroOnEveryArcAndTheSidewaysStepOtherwise) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-2, 2), turn(-3.1, 3.1), len(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d p0{pos(rng), pos(rng), pos(rng)};
    const double length = len(rng), change = turn(rng);
    const Eigen::Vector3d p1 = AlongArc(p0, length, change);
    EXPECT_LT(std::abs(LateralDisplacement(p0, p1)), 1e-14) << trial;
    const Arc arc = ArcBetween(p0, p1);
    EXPECT_NEAR(arc.length, length, 1e-13) << trial;
    EXPECT_NEAR(arc.heading_change, change, 1e-14) << trial;
  }
  // 1 cm to the left of a base facing +x, and of one facing +y (to its right).
  EXPECT_NEAR(LateralDisplacement({0, 0, 0}, {0, 0.01, 0}), 0.01, 1e-17);
  EXPECT_NEAR(LateralDisplacement({0, 0, M_PI / 2}, {0.01, 0, M_PI / 2}), -0.01, 1e-17);
  const Arc sideways = ArcBetween({0, 0, 0}, {0, 0.01, 0});
  EXPECT_FALSE(sideways.feasible());
  EXPECT_EQ(sideways.length, 0.0);
  // The interpolation of an infeasible step still ends on pose1.
  EXPECT_LT((InterpolateArc({0, 0, 0}, {0.1, 0.01, 0.2}, 1.0) - Eigen::Vector3d(0.1, 0.01, 0.2)).norm(), 1e-15);
}

// ---------------------------------------------------------------- simulation

TEST(SimulatedDifferentialBase, ConstantWheelSpeedsDriveTheExactCircle) {
  const DifferentialDriveKinematics k(0.3, 0.05);
  const Eigen::Vector3d start(0.1, 0.2, 0.4);
  SimulatedBases bases({k}, {start}, SimulationNoise::None());
  bases.CommandWheels(0, Eigen::Vector2d(3.0, 9.0));  // 0.3 m/s, 1 rad/s: a 0.3 m circle
  bases.Advance(2.0);
  // Centre 0.3 m to the left of the start; after 2 s the base is 2 rad round.
  const Eigen::Vector2d centre = start.head<2>() + 0.3 * Eigen::Vector2d(-std::sin(0.4), std::cos(0.4));
  const Eigen::Vector2d expected = centre + 0.3 * Eigen::Vector2d(std::sin(2.4), -std::cos(2.4));
  EXPECT_LT((bases.TruePose(0).head<2>() - expected).norm(), 1e-13);
  EXPECT_NEAR(bases.TruePose(0).z(), 2.4, 1e-12);  // 2000 plant steps of rounding
}

TEST(SimulatedDifferentialBase, NeverMovesSidewaysAndMixesWithOmniBases) {
  const DifferentialDriveKinematics diff(0.3, 0.05);
  const OmniWheelKinematics omni(DefaultWheels());
  SimulationNoise noise;  // slip, latency and sensing noise on
  noise.seed = 5;
  SimulatedBases bases({omni, diff}, {Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0)}, noise);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> w(-20, 20);
  double omni_lateral = 0;
  for (int tick = 0; tick < 200; ++tick) {
    bases.CommandWheels(0, Eigen::Vector3d{w(rng), w(rng), w(rng)});
    bases.CommandWheels(1, Eigen::Vector2d{w(rng), w(rng)});
    for (int i = 0; i < 10; ++i) {
      const Eigen::Vector3d d0 = bases.TruePose(1), o0 = bases.TruePose(0);
      bases.Advance(1e-3);
      EXPECT_LT(std::abs(LateralDisplacement(d0, bases.TruePose(1))), 1e-15);
      omni_lateral = std::max(omni_lateral, std::abs(LateralDisplacement(o0, bases.TruePose(0))));
    }
  }
  EXPECT_GT(omni_lateral, 1e-4);  // the omni base does slide sideways
  EXPECT_GT((bases.TruePose(1) - Eigen::Vector3d(1, 0, 0)).norm(), 0.01);  // and the differential one moved
  EXPECT_THROW(bases.CommandWheels(1, Eigen::Vector3d(1, 2, 3)), std::invalid_argument);
  EXPECT_THROW(bases.CommandWheels(0, Eigen::Vector2d(1, 2)), std::invalid_argument);
  EXPECT_THROW(bases.CommandWheels(2, Eigen::Vector2d(1, 2)), std::invalid_argument);
  EXPECT_THROW(SimulatedBases({diff}, {}, noise), std::invalid_argument);
}

// ---------------------------------------------------------------- tracking

// One differential base in closed loop: the set pose follows `reference`
// (pose and world velocity at t) for `seconds`.
struct Track {
  double max_error = 0;      // m, position, after `ignore_s`
  double final_position = 0; // m
  double final_heading = 0;  // rad
  double peak_wheel_speed = 0;
  double max_curvature_change = 0;  // |v/omega| after saturation vs before, relative
};
template <typename Reference>
Track RunTracker(const Eigen::Vector3d& start, Reference reference, double seconds, const TrackingGains& gains,
                 const SimulationNoise& noise, double ignore_s = 0) {
  const DifferentialDriveKinematics k(0.3, 0.05);
  DifferentialTracker tracker(k, gains);
  SimulatedBases bases({k}, {start}, noise);
  Track out;
  const double dt = 1.0 / gains.rate_hz;
  for (int tick = 0; tick < static_cast<int>(std::lround(seconds * gains.rate_hz)); ++tick) {
    const double t = tick * dt;
    Eigen::Vector3d set, velocity;
    reference(t, &set, &velocity);
    const Eigen::VectorXd wheels = tracker.Update(set, velocity, bases.MeasuredPose(0));
    out.peak_wheel_speed = std::max(out.peak_wheel_speed, wheels.cwiseAbs().maxCoeff());
    bases.CommandWheels(0, wheels);
    bases.Advance(dt);
    reference(t + dt, &set, &velocity);
    const double error = (bases.TruePose(0).head<2>() - set.head<2>()).norm();
    if (t + dt >= ignore_s) out.max_error = std::max(out.max_error, error);
    out.final_position = error;
    out.final_heading = std::abs(WrapAngle(bases.TruePose(0).z() - set.z()));
  }
  return out;
}

// A circle of radius 0.5 m at 0.2 m/s (0.4 rad/s, counter-clockwise) from the origin facing +x.
void Circle(double t, Eigen::Vector3d* set, Eigen::Vector3d* velocity) {
  *set = AlongArc(Eigen::Vector3d::Zero(), 0.2 * t, 0.4 * t);
  *velocity << 0.2 * std::cos(set->z()), 0.2 * std::sin(set->z()), 0.4;
}

TEST(DifferentialTracker, ConvergesOntoAMovingReferenceFromAnOffset) {
  // 5 cm behind, 4 cm to the side and 0.3 rad off.
  const Track r = RunTracker(Eigen::Vector3d(-0.05, -0.04, 0.3), Circle, 20.0, TrackingGains(),
                             SimulationNoise::None());
  EXPECT_LT(r.final_position, 1e-8);  // from 64 mm to rounding (5e-14 m) in 20 s
  EXPECT_LT(r.final_heading, 1e-8);
  // Backwards along the same circle (v_r < 0): the law works in reverse too.
  const Track back = RunTracker(
      Eigen::Vector3d(0.03, 0.04, -0.2),
      [](double t, Eigen::Vector3d* set, Eigen::Vector3d* velocity) {
        Circle(-t, set, velocity);
        *velocity = -*velocity;
      },
      20.0, TrackingGains(), SimulationNoise::None());
  EXPECT_LT(back.final_position, 1e-8);
  EXPECT_LT(back.final_heading, 1e-8);
}

TEST(DifferentialTracker, AtRestItCorrectsAlongTrackAndHeadingErrors) {
  const Eigen::Vector3d set(0.5, 0.2, 1.0);
  auto still = [&](double, Eigen::Vector3d* s, Eigen::Vector3d* v) {
    *s = set;
    v->setZero();
  };
  // 3 cm behind along the heading, 0.4 rad off.
  const Eigen::Vector3d start(0.5 - 0.03 * std::cos(1.0), 0.2 - 0.03 * std::sin(1.0), 0.6);
  const Track r = RunTracker(start, still, 10.0, TrackingGains(), SimulationNoise::None());
  EXPECT_LT(r.final_heading, 1e-8);  // 1e-14 rad
  // A sideways part of the error (it drove at an angle while turning) stays:
  // no smooth feedback removes it at rest; it is 5.8 mm here.
  EXPECT_LT(r.final_position, 0.01);
}

TEST(DifferentialTracker, FollowsPlannedArcsWithTheirVelocityFedForward) {
  // An S: a left quarter circle of radius 0.4 m, a straight 0.2 m, a right
  // quarter circle; each at constant speed, 4 s per segment, like a plan.
  std::vector<Eigen::Vector3d> poses = {Eigen::Vector3d::Zero()};
  poses.push_back(AlongArc(poses.back(), M_PI * 0.4 / 2, M_PI / 2));
  poses.push_back(AlongArc(poses.back(), 0.2, 0));
  poses.push_back(AlongArc(poses.back(), M_PI * 0.4 / 2, -M_PI / 2));
  auto plan = [&](double t, Eigen::Vector3d* set, Eigen::Vector3d* velocity) {
    const int i = std::min(static_cast<int>(t / 4.0), 2);
    const double a = std::min((t - 4.0 * i) / 4.0, 1.0);
    *set = InterpolateArc(poses[i], poses[i + 1], a);
    const Arc arc = ArcBetween(poses[i], poses[i + 1]);
    const bool moving = t < 12.0;
    *velocity << moving * arc.length / 4 * std::cos(set->z()), moving * arc.length / 4 * std::sin(set->z()),
        moving * arc.heading_change / 4;
  };
  TrackingGains gains;
  const Track exact = RunTracker(Eigen::Vector3d::Zero(), plan, 14.0, gains, SimulationNoise::None());
  // Without noise the fed-forward twist is exact on each arc (the arcs
  // switch on controller ticks here): the error stays at rounding (1e-14 m).
  EXPECT_LT(exact.max_error, 1e-9);
  // With the default noise (1 mm, 0.003 rad, latencies, 3 % slip): 3.6 mm.
  const Track noisy = RunTracker(Eigen::Vector3d::Zero(), plan, 14.0, gains, SimulationNoise());
  EXPECT_LT(noisy.max_error, 0.006);
  EXPECT_GT(noisy.max_error, 1e-4);  // the noise does act
  // Without the feed-forward the base lags by centimetres (39 mm).
  gains.velocity_feedforward = false;
  const Track lagging = RunTracker(Eigen::Vector3d::Zero(), plan, 14.0, gains, SimulationNoise::None());
  EXPECT_GT(lagging.max_error, 0.01);
}

TEST(DifferentialTracker, SaturationScalesBothWheelsAndKeepsTheCurvature) {
  TrackingGains gains;
  gains.max_wheel_speed = 5.0;  // 0.25 m/s at the rim
  const DifferentialDriveKinematics k(0.3, 0.05);
  DifferentialTracker tracker(k, gains);
  // 1 m ahead and 0.5 m to the left, facing 0.2 rad off: the law asks for
  // v = 4 * e_x and omega = 4 * sin(e_theta) + 0 (at rest), far beyond 5 rad/s.
  const Eigen::Vector3d set(1.0, 0.5, 0.2), measured(0, 0, 0);
  const Eigen::VectorXd wheels = tracker.Update(set, Eigen::Vector3d::Zero(), measured);
  EXPECT_TRUE(tracker.saturated());
  EXPECT_NEAR(wheels.cwiseAbs().maxCoeff(), 5.0, 1e-12);
  const double v = 4.0 * 1.0, omega = 4.0 * std::sin(0.2);  // e_x = 1 m in the base frame
  const Eigen::Vector2d unsaturated = k.WheelSpeeds(v, omega);
  EXPECT_NEAR(wheels[0] / wheels[1], unsaturated[0] / unsaturated[1], 1e-12);
  EXPECT_NEAR(tracker.twist().x() / tracker.twist().y(), v / omega, 1e-9);
  // Not saturated near the set pose.
  tracker.Update(set, Eigen::Vector3d::Zero(), set - Eigen::Vector3d(0.01, 0, 0));
  EXPECT_FALSE(tracker.saturated());
  // In closed loop from 2 m away: the limit holds all the way and it still arrives.
  auto still = [](double, Eigen::Vector3d* s, Eigen::Vector3d* vel) {
    *s = Eigen::Vector3d(2.0, 0, 0);
    vel->setZero();
  };
  const Track r = RunTracker(Eigen::Vector3d::Zero(), still, 15.0, gains, SimulationNoise::None());
  EXPECT_LE(r.peak_wheel_speed, 5.0 + 1e-12);
  EXPECT_LT(r.final_position, 1e-8);
}

TEST(DifferentialTracker, GainsAreValidated) {
  std::string why;
  TrackingGains gains;
  EXPECT_TRUE(gains.IsValid(&why)) << why;
  gains.differential.k_lateral = 0;
  EXPECT_FALSE(gains.IsValid(&why));
  EXPECT_NE(why.find("k_lateral"), std::string::npos) << why;
  EXPECT_NE(why.find("1/m^2"), std::string::npos) << why;
  gains = TrackingGains();
  gains.differential.k_along = kNaN;
  EXPECT_FALSE(gains.IsValid(&why));
  EXPECT_NE(why.find("k_along"), std::string::npos) << why;
  gains = TrackingGains();
  gains.differential.k_heading = kInf;
  EXPECT_FALSE(gains.IsValid(&why));
  EXPECT_NE(why.find("k_heading"), std::string::npos) << why;
}

// ---------------------------------------------------------------- replay

// One differential base carrying a post on an actuated vertical revolute
// (its motor holds the post's angle relative to the base): the post's tip,
// on the axis, is the end-effector (x, y), so the base must drive wherever
// it goes and may turn on the spot under it.
const char kCart[] = R"(name: cart
bodies:
  - {name: post, position: [0, 0, 0.3]}
mobile_bases:
  - {name: base0, type: differential, wheels: {track: 0.3, radius: 0.05}, pose: [0, 0, 0]}
joints:
  - {type: revolute, actuated: true, between: [base0, post], point: [0, 0, 0.1], axis: [0, 0, 1]}
end_effector: {body: post, point: [0, 0, 0.3], controlled: [x, y]}
)";

std::vector<Waypoint> Waypoints(const std::vector<std::array<double, 3>>& rows) {
  std::vector<Waypoint> out;
  for (const auto& [t, x, y] : rows) {
    Waypoint w;
    w.time = t;
    w.position = Eigen::Vector3d(x, y, 0.3);
    out.push_back(w);
  }
  return out;
}

// The largest distance [m] and heading difference [rad] between set and true base poses.
std::pair<double, double> BaseTrackingError(const ReplayResult& r, int base) {
  double position = 0, heading = 0;
  for (const ReplaySample& s : r.samples) {
    position = std::max(position, (s.set_controls.segment<2>(3 * base) - s.true_controls.segment<2>(3 * base)).norm());
    heading = std::max(heading, std::abs(WrapAngle(s.set_controls[3 * base + 2] - s.true_controls[3 * base + 2])));
  }
  return {position, heading};
}

TEST(DifferentialReplay, ACartFollowsItsPlannedArcs) {
  const Model m = LoadModelFromString(kCart, "cart.yaml");
  // Out 0.2 m along x, a bend to (0.3, 0.15), then back towards the start.
  const auto waypoints = Waypoints({{0, 0, 0}, {4, 0.2, 0}, {8, 0.3, 0.15}, {12, 0.1, 0.2}});
  ReplayOptions options;
  options.noise = SimulationNoise::None();
  const ReplayResult r = Replay(m, waypoints, options);
  ASSERT_TRUE(r.converged) << r.warning;
  EXPECT_TRUE(r.trustworthy());
  // The base turned (it had to face each leg) and drove.
  double turned = 0;
  for (const ReplaySample& s : r.samples) turned = std::max(turned, std::abs(s.true_controls[2]));
  EXPECT_GT(turned, 0.5);
  // Without noise: 2.7 um and 4e-5 rad from the set pose at worst, end-effector
  // RMSE 0.14 um in x and 0.56 um in y.
  const auto [position, heading] = BaseTrackingError(r, 0);
  EXPECT_LT(position, 1e-5);
  EXPECT_LT(heading, 1e-3);
  EXPECT_LT(r.rmse[0], 1e-5);
  EXPECT_LT(r.rmse[1], 1e-5);
  // With the default noise (seed 1): 1.25 mm at worst (0.14 rad during the
  // fast turns on the spot, 30 ms of latency at up to 6 rad/s); RMSE 0.26 mm
  // in x and 0.28 mm in y.
  options.noise = SimulationNoise();
  const ReplayResult noisy = Replay(m, waypoints, options);
  EXPECT_TRUE(noisy.trustworthy());
  const auto [noisy_position, noisy_heading] = BaseTrackingError(noisy, 0);
  EXPECT_LT(noisy_position, 0.003);
  EXPECT_LT(noisy_heading, 0.3);
  EXPECT_LT(noisy.rmse[0], 1e-3);
  EXPECT_LT(noisy.rmse[1], 1e-3);
  EXPECT_GT(noisy.rmse[0], 1e-5);  // the noise does act
}

// An omni base and a differential base under one bar (vertical revolutes at
// both ends); the bar's middle is the end-effector (x, y, yaw).
const char kMixed[] = R"(name: mixed
bodies:
  - {name: bar, position: [0, 0, 0.2]}
mobile_bases:
  - {name: omni0, type: omni, actuation: complete, pose: [-0.3, 0, 0]}
  - {name: diff1, type: differential, wheels: {track: 0.3, radius: 0.05}, pose: [0.3, 0, 1.2]}
joints:
  - {type: revolute, between: [omni0, bar], point: [-0.3, 0, 0.2], axis: [0, 0, 1]}
  - {type: revolute, between: [diff1, bar], point: [0.3, 0, 0.2], axis: [0, 0, 1]}
end_effector: {body: bar, point: [0, 0, 0.2], controlled: [x, y, yaw]}
)";

TEST(DifferentialReplay, AModelMixingOmniAndDifferentialBases) {
  const Model m = LoadModelFromString(kMixed, "mixed.yaml");
  ASSERT_FALSE(MakeBaseDrive(m.mobile_bases[0]).is_differential());
  ASSERT_TRUE(MakeBaseDrive(m.mobile_bases[1]).is_differential());
  EXPECT_EQ(MakeBaseDrive(m.mobile_bases[1]).differential()->track(), 0.3);
  EXPECT_EQ(MakeBaseDrive(m.mobile_bases[0]).num_wheels(), 3);
  // Sideways by 0.1 m (the differential base, facing 1.2 rad, turns first),
  // a turn of the bar by 0.3 rad (the differential base drives round an
  // arc), then a diagonal with a turn back.
  auto waypoints = Waypoints({{0, 0, 0}, {4, 0, 0.1}, {8, 0, 0.1}, {12, 0.1, 0.05}});
  waypoints[2].rpy.z() = 0.3;
  waypoints[3].rpy.z() = 0.2;
  ReplayOptions options;
  options.noise = SimulationNoise::None();
  const ReplayResult r = Replay(m, waypoints, options);
  ASSERT_TRUE(r.converged) << r.warning;
  EXPECT_TRUE(r.trustworthy()) << r.max_residual_energy;
  // While the bar turns (4 s to 8 s) the differential base drives round an
  // arc of radius 0.3 m (0.09 m and 0.3 rad in all), never sideways.
  Eigen::Vector3d at4 = Eigen::Vector3d::Zero(), at8 = Eigen::Vector3d::Zero();
  double max_lateral = 0;
  for (size_t i = 0; i < r.samples.size(); ++i) {
    const ReplaySample& s = r.samples[i];
    if (std::abs(s.time - 4.5) < 1e-9) at4 = s.true_controls.segment<3>(3);
    if (std::abs(s.time - 8.0) < 1e-9) at8 = s.true_controls.segment<3>(3);
    if (i > 0 && s.time > 4.5 && s.time <= 8.0) {
      max_lateral = std::max(max_lateral, std::abs(LateralDisplacement(r.samples[i - 1].set_controls.segment<3>(3),
                                                                       s.set_controls.segment<3>(3))));
    }
  }
  // From 4.5 s to 8 s: 0.079 m and 0.26 rad; the set pose's lateral
  // displacement between samples 7e-13 m (its arcs all lie on one circle).
  EXPECT_GT((at8 - at4).head<2>().norm(), 0.05);
  EXPECT_GT(std::abs(WrapAngle(at8.z() - at4.z())), 0.2);
  EXPECT_LT(max_lateral, 1e-9);
  // Without noise the differential base stays within 0.3 um and 3e-6 rad
  // of its set pose; the omni base (PI, linear set-points) within 0.23 mm.
  const auto [omni_position, omni_heading] = BaseTrackingError(r, 0);
  const auto [diff_position, diff_heading] = BaseTrackingError(r, 1);
  EXPECT_LT(diff_position, 1e-5);
  EXPECT_LT(diff_heading, 1e-4);
  EXPECT_LT(omni_position, 1e-3);
  EXPECT_LT(omni_heading, 1e-3);
  for (int c : {0, 1, 5}) EXPECT_LT(r.rmse[c], 1e-4) << c;  // 12 um, 9 um, 3.5e-5 rad
  // With the default noise: 1.2 mm (omni) and 1.4 mm (differential) at worst;
  // RMSE 0.19 mm in x and y, 6e-4 rad in yaw; the chain never torn.
  options.noise = SimulationNoise();
  const ReplayResult noisy = Replay(m, waypoints, options);
  EXPECT_TRUE(noisy.trustworthy()) << noisy.max_residual_energy;
  EXPECT_LT(BaseTrackingError(noisy, 0).first, 0.005);
  EXPECT_LT(BaseTrackingError(noisy, 1).first, 0.005);
  for (int c : {0, 1}) EXPECT_LT(noisy.rmse[c], 1e-3) << c;
  EXPECT_LT(noisy.rmse[5], 3e-3);
}

}  // namespace
}  // namespace ccma
