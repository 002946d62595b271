#include "ccma/base_tracking.h"

#include <algorithm>
#include <cmath>

#include "ccma/rotation.h"

namespace ccma {

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

SimulationNoise SimulationNoise::None() {
  SimulationNoise n;
  n.position_sigma = n.heading_sigma = 0;
  n.mocap_latency = n.command_latency = 0;
  n.slip = n.slip_sigma = 0;
  n.mocap_hz = 1e9;  // every request sees the current pose
  return n;
}

SimulatedBases::SimulatedBases(std::vector<OmniWheelKinematics> kinematics,
                               std::vector<Eigen::Vector3d> poses, const SimulationNoise& noise)
    : kinematics_(std::move(kinematics)),
      poses_(std::move(poses)),
      pending_(poses_.size()),
      measured_(poses_),
      noise_(noise),
      rng_(noise.seed) {
  for (const auto& k : kinematics_) applied_.push_back(Eigen::VectorXd::Zero(k.num_wheels()));
  history_.emplace_back(0.0, poses_);
}

void SimulatedBases::CommandWheels(int base, const Eigen::VectorXd& wheel_speeds) {
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
      measured_[k] = it->second[k] + Eigen::Vector3d(noise_.position_sigma * n(rng_),
                                                     noise_.position_sigma * n(rng_),
                                                     noise_.heading_sigma * n(rng_));
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
      const Eigen::Vector3d xi = kinematics_[k].Twist(applied_[k]);
      const double theta = poses_[k].z(), dtheta = xi.z() * step;
      Eigen::Vector2d v = xi.head<2>() * step;
      if (std::abs(dtheta) > 1e-12) {
        const double s = std::sin(dtheta) / dtheta, c = (1 - std::cos(dtheta)) / dtheta;
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
