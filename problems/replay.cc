#include "problems/replay.h"

#include <algorithm>
#include <cmath>

#include "ccma/rotation.h"
#include "problems/trajectory.h"

namespace ccma {
namespace {

Eigen::Matrix<double, 6, 1> Pose6(const EndEffectorPose& p) {
  Eigen::Matrix<double, 6, 1> x;
  x << p.position, p.rpy;
  return x;
}

}  // namespace

ReplayResult Replay(const Model& model, const std::vector<Waypoint>& waypoints,
                    const ReplayOptions& options) {
  ReplayResult result;
  // 1. The plan: control solution per path step, with its time.
  ControlProblem control(model, options.control);
  std::vector<double> times = {waypoints.front().time};
  std::vector<Eigen::VectorXd> plan_u = {control.controls()};
  std::vector<Eigen::Matrix<double, 6, 1>> plan_ee = {Pose6(control.forward().end_effector())};
  const TrajectoryResult plan = FollowWaypoints(control, waypoints, [&](const TrajectoryStep& s) {
    if (s.time <= times.back()) return;  // the zero-length first leg
    times.push_back(s.time);
    plan_u.push_back(s.controls);
    plan_ee.push_back(Pose6(s.reached));
  });
  result.converged = plan.converged;
  result.warning = plan.warning;

  // Set-point at time t: linear between plan steps; its velocity: the slope.
  auto segment = [&](double t) {
    const size_t i = std::upper_bound(times.begin(), times.end(), t) - times.begin();
    return std::min(std::max<size_t>(i, 1), times.size() - 1);
  };
  auto interpolate = [&](const auto& values, double t) {
    if (times.size() == 1 || t <= times.front()) return values.front();
    if (t >= times.back()) return values.back();
    const size_t i = segment(t);
    const double a = (t - times[i - 1]) / (times[i] - times[i - 1]);
    return decltype(values.front())((1 - a) * values[i - 1] + a * values[i]);
  };
  auto velocity = [&](double t) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(model.num_controls());
    if (times.size() < 2 || t < times.front() || t >= times.back()) return v;
    const size_t i = segment(t);
    return Eigen::VectorXd((plan_u[i] - plan_u[i - 1]) / (times[i] - times[i - 1]));
  };

  // 2. The bases, their trackers and the chain that follows them.
  std::vector<OmniWheelKinematics> kinematics;
  std::vector<BaseTracker> trackers;
  std::vector<Eigen::Vector3d> start;
  for (int k = 0; k < model.num_bases(); ++k) {
    kinematics.emplace_back(model.mobile_bases[k].wheels);
    trackers.emplace_back(kinematics.back(), options.gains);
    start.push_back(plan_u.front().segment<3>(3 * k));
  }
  SimulatedBases bases(kinematics, start, options.noise);
  ForwardProblem chain(model, options.control.forward);

  const double t0 = times.front(), t_end = times.back() + options.settle_s;
  const double dt = 1.0 / options.gains.rate_hz;
  double next_output = t0;
  const int ticks = static_cast<int>(std::ceil((t_end - t0) / dt));
  for (int tick = 0; tick <= ticks; ++tick) {
    const double t = t0 + tick * dt;
    if (t + 1e-9 >= next_output) {
      ReplaySample sample;
      sample.time = t;
      sample.commanded = interpolate(plan_ee, t);
      sample.set_controls = interpolate(plan_u, t);
      sample.true_controls.resize(model.num_controls());
      for (int k = 0; k < model.num_bases(); ++k) sample.true_controls.segment<3>(3 * k) = bases.TruePose(k);
      sample.residual_energy = chain.Solve(sample.true_controls).residual_energy;
      sample.tracked = Pose6(chain.end_effector());
      result.samples.push_back(sample);
      next_output += 1.0 / options.output_hz;
    }
    const Eigen::VectorXd set = interpolate(plan_u, t);
    const Eigen::VectorXd set_velocity = velocity(t);
    for (int k = 0; k < model.num_bases(); ++k) {
      const Eigen::VectorXd wheels = trackers[k].Update(set.segment<3>(3 * k), set_velocity.segment<3>(3 * k),
                                                        bases.MeasuredPose(k));
      bases.CommandWheels(k, wheels);
    }
    bases.Advance(dt);
  }

  // 3. RMSE of tracked against commanded, per component (angles wrapped).
  for (int c = 0; c < 6; ++c) {
    double sum = 0;
    for (const auto& s : result.samples) {
      const double d = c < 3 ? s.tracked[c] - s.commanded[c] : WrapAngle(s.tracked[c] - s.commanded[c]);
      sum += d * d;
    }
    result.rmse[c] = result.samples.empty() ? 0 : std::sqrt(sum / result.samples.size());
  }
  result.duration_s = t_end - t0;
  return result;
}

}  // namespace ccma
