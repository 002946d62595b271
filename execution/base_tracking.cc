#include "execution/base_tracking.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "ccma/limits.h"
#include "ccma/rotation.h"

namespace ccma {
namespace {

// True if value lies in the interval from lo to hi (closed unless lo_open /
// hi_open; never for NaN); else false with a message naming the field, its
// meaning, the interval with its unit, and the value (%g).
bool InRange(double value, double lo, double hi, const char* field, const char* unit, std::string* why,
             bool lo_open = false, bool hi_open = false) {
  const bool above = lo_open ? value > lo : value >= lo;
  const bool below = hi_open ? value < hi : value <= hi;
  if (above && below) return true;
  if (why != nullptr) {
    char text[320];
    std::snprintf(text, sizeof(text), "%s must lie in %c%g, %g%c %s; got %g", field, lo_open ? '(' : '[', lo, hi,
                  hi_open ? ')' : ']', unit, value);
    *why = text;
  }
  return false;
}

}  // namespace

bool TrackingGains::IsValid(std::string* why) const {
  constexpr double kMaxGain = 1e12;  // finite; larger gains only saturate
  return InRange(kp_position, 0, kMaxGain, "TrackingGains::kp_position (PI proportional gain)", "1/s", why, true) &&
         InRange(ki_position, 0, kMaxGain, "TrackingGains::ki_position (PI integral gain)", "1/s^2", why) &&
         InRange(kp_heading, 0, kMaxGain, "TrackingGains::kp_heading (PI proportional gain)", "1/s", why, true) &&
         InRange(ki_heading, 0, kMaxGain, "TrackingGains::ki_heading (PI integral gain)", "1/s^2", why) &&
         InRange(max_wheel_speed, 0, kMaxGain, "TrackingGains::max_wheel_speed (wheel-speed saturation)",
                 "rad/s", why, true) &&
         InRange(rate_hz, kMinControllerHz, kMaxControllerHz, "TrackingGains::rate_hz (controller rate)", "Hz", why) &&
         InRange(differential.k_along, 0, kMaxGain,
                 "TrackingGains::differential.k_along (differential base: along-track gain)", "1/s", why, true) &&
         InRange(differential.k_lateral, 0, kMaxGain,
                 "TrackingGains::differential.k_lateral (differential base: sideways gain)", "1/m^2", why, true) &&
         InRange(differential.k_heading, 0, kMaxGain,
                 "TrackingGains::differential.k_heading (differential base: heading gain)", "1/s", why, true);
}

bool SimulationNoise::IsValid(std::string* why) const {
  return InRange(position_sigma, 0, kMaxMagnitude, "SimulationNoise::position_sigma (motion-capture noise on x, y)",
                 "m", why) &&
         InRange(heading_sigma, 0, kMaxMagnitude, "SimulationNoise::heading_sigma (motion-capture noise on theta)",
                 "rad", why) &&
         InRange(mocap_latency, 0, kMaxLatency, "SimulationNoise::mocap_latency (motion-capture latency)", "s", why) &&
         InRange(mocap_hz, 1, kMaxMocapHz, "SimulationNoise::mocap_hz (motion-capture rate)", "Hz", why) &&
         InRange(command_latency, 0, kMaxLatency, "SimulationNoise::command_latency (radio latency)", "s", why) &&
         InRange(slip, 0, 1, "SimulationNoise::slip (mean fraction of wheel speed lost)", "(fraction)", why,
                 false, true) &&
         InRange(slip_sigma, 0, 1, "SimulationNoise::slip_sigma (spread of the slip)", "(fraction)", why) &&
         InRange(plant_hz, 1, kMaxPlantHz, "SimulationNoise::plant_hz (integration rate of the base motion)", "Hz",
                 why);
}

BaseTracker::BaseTracker(OmniWheelKinematics kinematics, const TrackingGains& gains)
    : kinematics_(std::move(kinematics)), gains_(gains) {}

Eigen::VectorXd BaseTracker::Update(const Eigen::Vector3d& set, const Eigen::Vector3d& set_velocity,
                                    const Eigen::Vector3d& measured) {
  const double dt = 1.0 / gains_.rate_hz;
  const Eigen::Matrix2d R_WB = Eigen::Rotation2Dd(measured.z()).toRotationMatrix();
  Eigen::Vector3d error;  // in the base frame
  error.head<2>() = R_WB.transpose() * (set.head<2>() - measured.head<2>());
  error.z() = WrapAngle(set.z() - measured.z());
  Eigen::Vector3d feedforward = Eigen::Vector3d::Zero();
  if (gains_.velocity_feedforward) {
    feedforward.head<2>() = R_WB.transpose() * set_velocity.head<2>();
    feedforward.z() = set_velocity.z();
  }
  const Eigen::Vector3d kp(gains_.kp_position, gains_.kp_position, gains_.kp_heading);
  const Eigen::Vector3d ki(gains_.ki_position, gains_.ki_position, gains_.ki_heading);
  const Eigen::Vector3d candidate_integral = integral_ + error * dt;
  Eigen::Vector3d twist = feedforward + kp.cwiseProduct(error) + ki.cwiseProduct(candidate_integral);
  Eigen::VectorXd wheels = kinematics_.WheelSpeeds(twist);
  const double peak = wheels.cwiseAbs().maxCoeff();
  saturated_ = peak > gains_.max_wheel_speed;
  if (saturated_) {
    wheels *= gains_.max_wheel_speed / peak;  // same direction, slower
  } else {
    integral_ = candidate_integral;  // anti-windup: integrate only when not saturated
  }
  return wheels;
}

DifferentialTracker::DifferentialTracker(DifferentialDriveKinematics kinematics, const TrackingGains& gains)
    : kinematics_(kinematics), gains_(gains) {}

Eigen::VectorXd DifferentialTracker::Update(const Eigen::Vector3d& set, const Eigen::Vector3d& set_velocity,
                                            const Eigen::Vector3d& measured) {
  const double v_r = std::cos(set.z()) * set_velocity.x() + std::sin(set.z()) * set_velocity.y();
  return UpdateWithTwist(set, v_r, set_velocity.z(), measured);
}

Eigen::VectorXd DifferentialTracker::UpdateWithTwist(const Eigen::Vector3d& set, double v_r, double omega_r,
                                                     const Eigen::Vector3d& measured) {
  const DifferentialTrackingGains& k = gains_.differential;
  if (!gains_.velocity_feedforward) v_r = omega_r = 0;
  // The set pose seen from the measured one (Kanayama's error, base frame).
  const double c = std::cos(measured.z()), s = std::sin(measured.z());
  const double dx = set.x() - measured.x(), dy = set.y() - measured.y();
  const double e_x = c * dx + s * dy, e_y = -s * dx + c * dy;
  const double e_theta = WrapAngle(set.z() - measured.z());
  const double k_theta = std::max(k.k_heading, 2 * std::sqrt(k.k_lateral) * std::abs(v_r));
  double v = v_r * std::cos(e_theta) + k.k_along * e_x;
  double omega = omega_r + k.k_lateral * v_r * e_y + k_theta * std::sin(e_theta);
  Eigen::Vector2d wheels = kinematics_.WheelSpeeds(v, omega);
  const double peak = wheels.cwiseAbs().maxCoeff();
  saturated_ = peak > gains_.max_wheel_speed;
  if (saturated_) {
    wheels *= gains_.max_wheel_speed / peak;  // both wheels together: the curvature is kept
  }
  twist_ = kinematics_.Twist(wheels.x(), wheels.y());
  return wheels;
}

int BaseDrive::num_wheels() const {
  if (is_differential()) return 2;
  return omni()->num_wheels();
}

Eigen::Vector3d BaseDrive::Twist(const Eigen::VectorXd& wheel_speeds) const {
  if (const auto* d = differential()) {
    const Eigen::Vector2d t = d->Twist(wheel_speeds[0], wheel_speeds[1]);
    return Eigen::Vector3d(t.x(), 0, t.y());
  }
  return omni()->Twist(wheel_speeds);
}

BaseDrive MakeBaseDrive(const MobileBase& base) {
  if (base.type == BaseType::kDifferential) {
    return DifferentialDriveKinematics(base.differential.track, base.differential.radius);
  }
  return OmniWheelKinematics(base.wheels);
}

SimulationNoise SimulationNoise::None() {
  SimulationNoise n;
  n.position_sigma = n.heading_sigma = 0;
  n.mocap_latency = n.command_latency = 0;
  n.slip = n.slip_sigma = 0;
  n.mocap_hz = 1e9;  // every request sees the current pose
  return n;
}

SimulatedBases::SimulatedBases(std::vector<BaseDrive> drives, std::vector<Eigen::Vector3d> poses,
                               const SimulationNoise& noise)
    : drives_(std::move(drives)),
      poses_(std::move(poses)),
      pending_(poses_.size()),
      measured_(poses_),
      noise_(noise),
      rng_(noise.seed) {
  if (drives_.size() != poses_.size()) {
    throw std::invalid_argument("SimulatedBases: " + std::to_string(drives_.size()) + " drives but " +
                                std::to_string(poses_.size()) + " poses");
  }
  for (const auto& d : drives_) applied_.push_back(Eigen::VectorXd::Zero(d.num_wheels()));
  history_.emplace_back(0.0, poses_);
}

void SimulatedBases::CommandWheels(int base, const Eigen::VectorXd& wheel_speeds) {
  if (base < 0 || base >= static_cast<int>(drives_.size())) {
    throw std::invalid_argument("SimulatedBases::CommandWheels: no base " + std::to_string(base));
  }
  if (wheel_speeds.size() != drives_[base].num_wheels()) {
    throw std::invalid_argument("SimulatedBases::CommandWheels: base " + std::to_string(base) + " has " +
                                std::to_string(drives_[base].num_wheels()) + " wheels, got " +
                                std::to_string(wheel_speeds.size()) + " speeds");
  }
  std::normal_distribution<double> n;
  Eigen::VectorXd actual = wheel_speeds;
  for (int i = 0; i < actual.size(); ++i) {
    actual[i] *= 1.0 - std::clamp(noise_.slip + noise_.slip_sigma * n(rng_), 0.0, 1.0);
  }
  pending_[base].push_back({time_ + noise_.command_latency, actual});
}

Eigen::Vector3d SimulatedBases::MeasuredPose(int base) {
  if (time_ + 1e-12 >= next_sample_time_) {
    // A new motion-capture frame: the poses of mocap_latency ago, plus noise.
    const double wanted = time_ - noise_.mocap_latency;
    auto it = history_.begin();
    while (std::next(it) != history_.end() && std::next(it)->first <= wanted + 1e-12) ++it;
    std::normal_distribution<double> n;
    for (size_t k = 0; k < poses_.size(); ++k) {
      measured_[k] = it->second[k] + Eigen::Vector3d{noise_.position_sigma * n(rng_),
                                                     noise_.position_sigma * n(rng_),
                                                     noise_.heading_sigma * n(rng_)};
    }
    next_sample_time_ = time_ + 1.0 / noise_.mocap_hz;
  }
  return measured_[base];
}

void SimulatedBases::Advance(double dt) {
  const double h = 1.0 / noise_.plant_hz;
  const double end = time_ + dt;
  while (time_ < end - 1e-12) {
    const double step = std::min(h, end - time_);
    for (size_t k = 0; k < poses_.size(); ++k) {
      while (!pending_[k].empty() && pending_[k].front().apply_time <= time_ + 1e-12) {
        applied_[k] = pending_[k].front().wheel_speeds;
        pending_[k].pop_front();
      }
      // Constant body twist over the step: exact motion on SE(2).
      const Eigen::Vector3d xi = drives_[k].Twist(applied_[k]);
      const double theta = poses_[k].z(), dtheta = xi.z() * step;
      Eigen::Vector2d v = xi.head<2>() * step;
      if (std::abs(dtheta) > 1e-12) {
        // (1 - cos) / dtheta without the cancellation of 1 - cos at small angles.
        const double half = std::sin(dtheta / 2);
        const double s = std::sin(dtheta) / dtheta, c = 2 * half * half / dtheta;
        v = Eigen::Vector2d(s * v.x() - c * v.y(), c * v.x() + s * v.y());
      }
      poses_[k].head<2>() += Eigen::Rotation2Dd(theta).toRotationMatrix() * v;
      poses_[k].z() = theta + dtheta;
    }
    time_ += step;
    history_.emplace_back(time_, poses_);
    while (history_.size() > 2 && history_[1].first < time_ - noise_.mocap_latency - 1.0) history_.pop_front();
  }
}

}  // namespace ccma
