// Driving the bases (paper Section IV): each omni base turns the difference
// between its set pose and its tracked pose into wheel speeds with a PI
// controller; hardware plugs in through PoseSource (e.g. motion capture) and
// WheelCommandSink (e.g. serial/radio), and SimulatedBases stands in for both.
// Poses are (x [m], y [m], theta [rad]) of the base frame in the world.
#ifndef CCMA_BASE_TRACKING_H_
#define CCMA_BASE_TRACKING_H_

#include <deque>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/omni_wheels.h"

namespace ccma {

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

  // Every field in its documented range (Ceres' Solver::Options::IsValid
  // style): gains finite, kp > 0 and ki >= 0 [1/s, 1/s^2]; max_wheel_speed
  // finite and > 0 [rad/s]; rate_hz in [kMinControllerHz, kMaxControllerHz].
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

// Bases that move by their wheels: commands take effect after the command
// latency, less the slip; poses are integrated exactly over each plant step;
// measurements are delayed, noisy and sampled at the motion-capture rate.
class SimulatedBases final : public PoseSource, public WheelCommandSink {
 public:
  SimulatedBases(std::vector<OmniWheelKinematics> kinematics, std::vector<Eigen::Vector3d> poses,
                 const SimulationNoise& noise);
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
  std::vector<OmniWheelKinematics> kinematics_;
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
