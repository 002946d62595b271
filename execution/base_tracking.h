// Driving the bases (paper Section IV): each omni base turns the difference
// between its set pose and its tracked pose into wheel speeds with a PI
// controller, each differential-drive base with a unicycle tracking law
// (DifferentialTracker); hardware plugs in through PoseSource (e.g. motion
// capture) and WheelCommandSink (e.g. serial/radio), and SimulatedBases
// stands in for both, for either kind of base.
// Poses are (x [m], y [m], theta [rad]) of the base frame in the world.
#ifndef CCMA_BASE_TRACKING_H_
#define CCMA_BASE_TRACKING_H_

#include <deque>
#include <random>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "execution/differential_drive.h"
#include "ccma/model.h"
#include "ccma/omni_wheels.h"

namespace ccma {

// The tracking law of a differential-drive base (DifferentialTracker): a
// variant of Kanayama et al. (1990), "A stable tracking control method for
// an autonomous mobile robot", with a heading gain that does not vanish at
// rest. With the errors e_x (along the heading) [m], e_y (sideways) [m] and
// e_theta [rad] of the set pose seen from the measured one, and the set
// pose's own twist (v_r [m/s], omega_r [rad/s]) fed forward:
//   v     = v_r cos(e_theta) + k_along e_x
//   omega = omega_r + k_lateral v_r e_y + k_theta sin(e_theta),
//   k_theta = max(k_heading, 2 sqrt(k_lateral) |v_r|).
// V = (e_x^2 + e_y^2) / 2 + (1 - cos e_theta) / k_lateral decreases as
// dV/dt = -k_along e_x^2 - (k_theta / k_lateral) sin^2 e_theta, forwards,
// backwards and at rest. Moving, the sideways error converges too (the
// e_y, e_theta loop linearised about a straight line, s^2 + k_theta s +
// k_lateral v_r^2, is critically damped or slower); at rest (v_r = 0) a
// sideways error cannot be corrected by any smooth feedback (Brockett): the
// base holds it until the plan moves it again.
struct DifferentialTrackingGains {
  double k_along = 4.0;       // 1/s: along-track error -> forward speed
  // 1/m^2: sideways error times speed -> turn rate; with k_heading = 4/s the
  // loop is critically damped from 0.05 m/s up (the speeds of the 4-DOF
  // models' bases), i.e. a sideways error decays within ~2.5 cm of travel.
  double k_lateral = 1600.0;
  double k_heading = 4.0;     // 1/s: heading error -> turn rate (its floor, see above)
};

struct TrackingGains {
  // Critically damped (ki = kp^2 / 4: a double closed-loop pole at -kp/2),
  // so a step settles without overshoot: 5 cm to 25 um in 5 s.
  double kp_position = 4.0;  // 1/s
  double ki_position = 4.0;  // 1/s^2
  double kp_heading = 4.0;   // 1/s
  double ki_heading = 4.0;   // 1/s^2
  double max_wheel_speed = 30.0;  // rad/s, saturation
  double rate_hz = 100.0;         // controller rate
  // Add the set-point's own velocity (known from the planned path) to the
  // PI output: the PI then only corrects errors, not the path itself.
  bool velocity_feedforward = true;
  // Differential-drive bases (their own law; max_wheel_speed, rate_hz and
  // velocity_feedforward apply to them too).
  DifferentialTrackingGains differential;

  // Every field in its documented range (Ceres' Solver::Options::IsValid
  // style): gains finite, kp > 0 and ki >= 0 [1/s, 1/s^2]; max_wheel_speed
  // finite and > 0 [rad/s]; rate_hz in [kMinControllerHz, kMaxControllerHz];
  // differential gains finite and > 0 [1/s, 1/m^2, 1/s].
  // Otherwise false, with `why` (if not null) naming the field and its unit.
  bool IsValid(std::string* why) const;
  static constexpr double kMinControllerHz = 1.0;
  static constexpr double kMaxControllerHz = 10000.0;
};

// PI on the pose error expressed in the base frame. Saturation scales all
// wheel speeds together (the twist keeps its direction); anti-windup stops
// integrating while saturated.
class BaseTracker {
 public:
  BaseTracker(OmniWheelKinematics kinematics, const TrackingGains& gains);
  // One controller tick (dt = 1 / rate_hz): wheel speeds [rad/s] from the set
  // pose, its world velocity (x_dot, y_dot, theta_dot) and the measured pose.
  Eigen::VectorXd Update(const Eigen::Vector3d& set, const Eigen::Vector3d& set_velocity,
                         const Eigen::Vector3d& measured);
  void Reset() { integral_.setZero(); }
  bool saturated() const { return saturated_; }
  const OmniWheelKinematics& kinematics() const { return kinematics_; }

 private:
  OmniWheelKinematics kinematics_;
  TrackingGains gains_;
  Eigen::Vector3d integral_ = Eigen::Vector3d::Zero();
  bool saturated_ = false;
};

// The tracking law of a differential-drive base (DifferentialTrackingGains):
// no integrator (wheel slip leaves an along-track lag of slip * v_r /
// k_along). Saturation scales both wheel speeds together (the commanded
// curvature v / omega is kept).
class DifferentialTracker {
 public:
  DifferentialTracker(DifferentialDriveKinematics kinematics, const TrackingGains& gains);
  // One controller tick: (left, right) wheel speeds [rad/s] from the set
  // pose, its world velocity (x_dot, y_dot, theta_dot) and the measured pose.
  // The reference twist fed forward is v_r = the set velocity along the set
  // heading, omega_r = theta_dot (zero without velocity_feedforward).
  Eigen::VectorXd Update(const Eigen::Vector3d& set, const Eigen::Vector3d& set_velocity,
                         const Eigen::Vector3d& measured);
  // The same with the reference twist given directly: v_r [m/s], omega_r [rad/s].
  Eigen::VectorXd UpdateWithTwist(const Eigen::Vector3d& set, double v_r, double omega_r,
                                  const Eigen::Vector3d& measured);
  bool saturated() const { return saturated_; }
  // The body twist (v [m/s], omega [rad/s]) of the last command, after saturation.
  const Eigen::Vector2d& twist() const { return twist_; }
  const DifferentialDriveKinematics& kinematics() const { return kinematics_; }

 private:
  DifferentialDriveKinematics kinematics_;
  TrackingGains gains_;
  Eigen::Vector2d twist_ = Eigen::Vector2d::Zero();
  bool saturated_ = false;
};

// The drive of one base: its wheels, omni or differential. Converts wheel
// speeds to the body twist (v_x [m/s], v_y [m/s], omega [rad/s]) in the base
// frame (v_y = 0 for a differential base).
class BaseDrive {
 public:
  BaseDrive(OmniWheelKinematics omni) : drive_(std::move(omni)) {}  // NOLINT: implicit on purpose
  BaseDrive(DifferentialDriveKinematics differential) : drive_(differential) {}  // NOLINT
  bool is_differential() const { return std::holds_alternative<DifferentialDriveKinematics>(drive_); }
  int num_wheels() const;
  Eigen::Vector3d Twist(const Eigen::VectorXd& wheel_speeds) const;
  const OmniWheelKinematics* omni() const { return std::get_if<OmniWheelKinematics>(&drive_); }
  const DifferentialDriveKinematics* differential() const {
    return std::get_if<DifferentialDriveKinematics>(&drive_);
  }

 private:
  std::variant<OmniWheelKinematics, DifferentialDriveKinematics> drive_;
};

// A model base's drive: its omni wheels (MobileBase::wheels) or its
// differential pair (MobileBase::differential). Throws std::invalid_argument
// for wheels that cannot drive.
BaseDrive MakeBaseDrive(const MobileBase& base);

// Where tracked base poses come from (motion capture on hardware).
class PoseSource {
 public:
  virtual ~PoseSource() = default;
  virtual Eigen::Vector3d MeasuredPose(int base) = 0;
};

// Where wheel commands go (serial/radio on hardware).
class WheelCommandSink {
 public:
  virtual ~WheelCommandSink() = default;
  virtual void CommandWheels(int base, const Eigen::VectorXd& wheel_speeds) = 0;
};

// The imperfections of a simulated set-up; all randomness from `seed`.
struct SimulationNoise {
  double position_sigma = 0.001;  // m, motion-capture noise on x and y
  double heading_sigma = 0.003;   // rad, on theta
  double mocap_latency = 0.010;   // s
  double mocap_hz = 120.0;        // sample-and-hold rate of motion capture
  double command_latency = 0.020; // s, radio link
  double slip = 0.03;             // mean fraction of wheel speed lost
  double slip_sigma = 0.02;       // its spread, per wheel and command
  double plant_hz = 1000.0;       // integration rate of the base motion
  unsigned seed = 1;
  // Perfect sensing and actuation (plant rate unchanged).
  static SimulationNoise None();

  // Every field in its documented range: sigmas finite in [0, kMaxMagnitude]
  // (m, rad); latencies in [0, kMaxLatency] s; mocap_hz in [1, 1e9] Hz (None()
  // uses 1e9: every request sees the current pose); plant_hz in [1, 10000] Hz;
  // slip in [0, 1) and slip_sigma in [0, 1]. Otherwise false, with `why` (if
  // not null) naming the field and its unit.
  bool IsValid(std::string* why) const;
  static constexpr double kMaxLatency = 10.0;      // s
  static constexpr double kMaxMocapHz = 1e9;       // Hz
  static constexpr double kMaxPlantHz = 10000.0;   // Hz
};

// Bases that move by their wheels (omni or differential, mixed freely):
// commands take effect after the command latency, less the slip (drawn per
// wheel and command: on a differential base unequal slip turns it); poses
// are integrated exactly over each plant step (constant body twist: an arc
// on SE(2), with no sideways motion for a differential base); measurements
// are delayed, noisy and sampled at the motion-capture rate.
class SimulatedBases final : public PoseSource, public WheelCommandSink {
 public:
  // Throws std::invalid_argument unless drives and poses have the same size.
  SimulatedBases(std::vector<BaseDrive> drives, std::vector<Eigen::Vector3d> poses, const SimulationNoise& noise);
  // Throws std::invalid_argument for a base index out of range or a command
  // with a number of speeds other than the base's wheels (2 for a
  // differential base: left, right).
  void CommandWheels(int base, const Eigen::VectorXd& wheel_speeds) override;
  Eigen::Vector3d MeasuredPose(int base) override;
  // Advances the simulation by dt seconds.
  void Advance(double dt);
  const Eigen::Vector3d& TruePose(int base) const { return poses_[base]; }
  double time() const { return time_; }

 private:
  struct Command {
    double apply_time;
    Eigen::VectorXd wheel_speeds;  // after slip
  };
  std::vector<BaseDrive> drives_;
  std::vector<Eigen::Vector3d> poses_;
  std::vector<std::deque<Command>> pending_;
  std::vector<Eigen::VectorXd> applied_;
  std::deque<std::pair<double, std::vector<Eigen::Vector3d>>> history_;  // for mocap latency
  std::vector<Eigen::Vector3d> measured_;
  double next_sample_time_ = 0;
  SimulationNoise noise_;
  std::mt19937 rng_;
  double time_ = 0;
};

}  // namespace ccma

#endif  // CCMA_BASE_TRACKING_H_
