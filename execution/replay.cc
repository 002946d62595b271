#include "execution/replay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "execution/differential_drive.h"
#include "ccma/limits.h"
#include "ccma/rotation.h"
#include "problems/trajectory.h"

namespace ccma {
namespace {

Eigen::Matrix<double, 6, 1> Pose6(const EndEffectorPose& p) {
  Eigen::Matrix<double, 6, 1> x;
  x << p.position, p.rpy;
  return x;
}

std::string Format(const char* format, double a, double b = 0, double c = 0) {
  char text[320];
  std::snprintf(text, sizeof(text), format, a, b, c);
  return text;
}

bool Fail(const std::string& message, std::string* why) {
  if (why != nullptr) *why = message;
  return false;
}

// The plan: control solution per path step, with its time. The first entry
// is the start (the first waypoint's time, the starting controls).
struct Plan {
  std::vector<double> times;
  std::vector<Eigen::VectorXd> controls;
  std::vector<Eigen::Matrix<double, 6, 1>> end_effector;
  std::vector<bool> differential;  // per base: moves along arcs between steps
  std::vector<Eigen::Index> first;  // per base: the index into u of its x

  // Index i of the segment [times[i-1], times[i]] holding t (times.size() > 1).
  size_t Segment(double t) const {
    const size_t i = std::upper_bound(times.begin(), times.end(), t) - times.begin();
    return std::min(std::max<size_t>(i, 1), times.size() - 1);
  }
  // Linear between plan steps, held before the first and after the last.
  template <typename T>
  T Interpolate(const std::vector<T>& values, double t) const {
    if (times.size() == 1 || t <= times.front()) return values.front();
    if (t >= times.back()) return values.back();
    const size_t i = Segment(t);
    const double a = (t - times[i - 1]) / (times[i] - times[i - 1]);
    return T((1 - a) * values[i - 1] + a * values[i]);
  }
  // The set-point controls at t: linear between plan steps, except the
  // poses of differential bases, which move along the step's arc
  // (InterpolateArc) at constant speed and turn rate.
  Eigen::VectorXd SetControls(double t) const {
    Eigen::VectorXd u = Interpolate(controls, t);
    if (times.size() == 1 || t <= times.front() || t >= times.back()) return u;
    const size_t i = Segment(t);
    const double a = (t - times[i - 1]) / (times[i] - times[i - 1]);
    for (size_t k = 0; k < differential.size(); ++k) {
      if (!differential[k]) continue;
      const Eigen::Index c = first[k];
      u.segment<3>(c) = InterpolateArc(controls[i - 1].segment<3>(c), controls[i].segment<3>(c), a);
    }
    return u;
  }
  // The set-points' velocity: the slope of the current segment.
  Eigen::VectorXd Velocity(double t) const {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(controls.front().size());
    if (times.size() < 2 || t < times.front() || t >= times.back()) return v;
    const size_t i = Segment(t);
    return (controls[i] - controls[i - 1]) / (times[i] - times[i - 1]);
  }

  // Differential bases: the arc of every step (arcs[k][i]: from step i - 1
  // to step i) and the distance driven and heading turned [m, rad] from the
  // start to each step (progress[k][i]). Call once the steps are all in.
  void FindArcs() {
    arcs.assign(differential.size(), {});
    progress.assign(differential.size(), {});
    for (size_t k = 0; k < differential.size(); ++k) {
      if (!differential[k]) continue;
      const Eigen::Index c = first[k];
      arcs[k].resize(times.size());
      progress[k].assign(times.size(), Eigen::Vector2d::Zero());
      for (size_t i = 1; i < times.size(); ++i) {
        arcs[k][i] = ArcBetween(controls[i - 1].segment<3>(c), controls[i].segment<3>(c));
        progress[k][i] = progress[k][i - 1] + Eigen::Vector2d(arcs[k][i].length, arcs[k][i].heading_change);
      }
    }
  }
  // Distance driven and heading turned by base k's set pose from the start to t.
  Eigen::Vector2d Progress(size_t k, double t) const {
    if (times.size() == 1 || t <= times.front()) return Eigen::Vector2d::Zero();
    if (t >= times.back()) return progress[k].back();
    const size_t i = Segment(t);
    const double a = (t - times[i - 1]) / (times[i] - times[i - 1]);
    return progress[k][i - 1] + a * Eigen::Vector2d(arcs[k][i].length, arcs[k][i].heading_change);
  }
  // The twist (v_r [m/s], omega_r [rad/s]) of base k's set pose averaged over
  // the controller tick [t, t + dt]: exact on an arc, and a step's arc is
  // fed forward for the share of the tick it lasts (no lag at step
  // boundaries between ticks, such as the start and end of a fast turn on
  // the spot).
  Eigen::Vector2d Twist(size_t k, double t, double dt) const {
    return (Progress(k, t + dt) - Progress(k, t)) / dt;
  }
  std::vector<std::vector<Arc>> arcs;
  std::vector<std::vector<Eigen::Vector2d>> progress;
};

// One base's controller: the PI of an omni base or the unicycle tracker of a
// differential one.
class BaseController {
 public:
  BaseController(const BaseDrive& drive, const TrackingGains& gains) {
    if (const DifferentialDriveKinematics* d = drive.differential()) {
      differential_.emplace(*d, gains);
    } else {
      omni_.emplace(*drive.omni(), gains);
    }
  }
  bool differential() const { return differential_.has_value(); }
  // Omni: the set pose's world velocity is fed forward. Differential: the
  // reference twist (v_r, omega_r) along its arc.
  Eigen::VectorXd Update(const Eigen::Vector3d& set, const Eigen::Vector3d& set_velocity,
                         const Eigen::Vector2d& set_twist, const Eigen::Vector3d& measured) {
    return omni_ ? omni_->Update(set, set_velocity, measured)
                 : differential_->UpdateWithTwist(set, set_twist.x(), set_twist.y(), measured);
  }

 private:
  std::optional<BaseTracker> omni_;
  std::optional<DifferentialTracker> differential_;
};

Plan MakePlan(const Model& model, const std::vector<Waypoint>& waypoints, const ReplayOptions& options,
              ReplayResult* result) {
  ControlProblem control(model, options.control);
  Plan plan;
  plan.times = {waypoints.front().time};
  plan.controls = {control.controls()};
  plan.end_effector = {Pose6(control.forward().end_effector())};
  for (int k = 0; k < model.num_bases(); ++k) {
    plan.differential.push_back(model.mobile_bases[static_cast<size_t>(k)].type == BaseType::kDifferential);
    plan.first.push_back(model.base_control(k));
  }
  const TrajectoryResult trajectory = FollowWaypoints(control, waypoints, [&](const TrajectoryStep& s) {
    if (!s.result.reached && std::isnan(result->failed_step_time)) result->failed_step_time = s.time;
    if (s.time <= plan.times.back()) return;  // the zero-length first leg
    plan.times.push_back(s.time);
    plan.controls.push_back(s.controls);
    plan.end_effector.push_back(Pose6(s.reached));
  });
  result->converged = trajectory.converged;
  result->warning = trajectory.warning;
  if (!result->converged && std::isnan(result->failed_step_time)) result->failed_step_time = plan.times.back();
  plan.FindArcs();
  return plan;
}

// Sums of squared errors per component (angles wrapped), for RMSEs taken
// over every controller tick rather than over the output samples.
struct ErrorSums {
  std::array<double, 6> tracked{}, gait{}, tracking{};  // tracked-commanded, tracked-without gait, without-commanded
  long count = 0;

  void Add(const ReplaySample& s) {
    for (int c = 0; c < 6; ++c) {
      const auto d = [c](const Eigen::Matrix<double, 6, 1>& x, const Eigen::Matrix<double, 6, 1>& y) {
        const double e = c < 3 ? x[c] - y[c] : WrapAngle(x[c] - y[c]);
        return e * e;
      };
      tracked[c] += d(s.tracked, s.commanded);
      gait[c] += d(s.tracked, s.tracked_without_gait);
      tracking[c] += d(s.tracked_without_gait, s.commanded);
    }
    ++count;
  }
};

// The chain at the bases' true poses: a sample at time t (with legged
// bases also the chain without the gait, solved first).
class ChainAtBases {
 public:
  ChainAtBases(const Model& model, const ReplayOptions& options)
      : model_(model), options_(options), chain_(model, options.control.forward),
        without_gait_(model, options.control.forward), gait_(HasLeggedBases(model)) {}
  bool gait() const { return gait_; }

  ReplaySample At(double t, const Plan& plan, const SimulatedBases& bases) {
    ReplaySample sample;
    sample.time = t;
    sample.commanded = plan.Interpolate(plan.end_effector, t);
    sample.set_controls = plan.SetControls(t);
    // Actuated joints' motors (after the bases' controls) hold their set-points.
    sample.true_controls = sample.set_controls;
    for (int k = 0; k < model_.num_bases(); ++k) sample.true_controls.segment<3>(plan.first[k]) = bases.TruePose(k);
    if (gait_) {
      without_gait_.Solve(sample.true_controls);
      sample.tracked_without_gait = Pose6(without_gait_.end_effector());
      ApplyGait(model_, options_.gait, t, plan.Velocity(t), &sample.true_controls);
    }
    sample.residual_energy = chain_.Solve(sample.true_controls).residual_energy;
    sample.assembled = sample.residual_energy <= options_.control.forward.assembly_tolerance;
    sample.torn = !(sample.residual_energy <= options_.torn_residual_energy);
    sample.tracked = Pose6(chain_.end_effector());
    return sample;
  }

 private:
  const Model& model_;
  const ReplayOptions& options_;
  ForwardProblem chain_, without_gait_;
  bool gait_;
};

// Runs the bases and the chain along the plan; appends the samples. With
// legged bases the chain is solved at every controller tick, not only at the
// output samples, and `sums` collects the errors of every tick: a gait
// sampled only at the output rate aliases (at 20 Hz, a 10 Hz gait is
// sampled at the same phase every time and shows no bob).
void Simulate(const Model& model, const Plan& plan, const ReplayOptions& options, ReplayResult* result,
              ErrorSums* sums) {
  std::vector<BaseDrive> drives;
  std::vector<BaseController> controllers;
  std::vector<Eigen::Vector3d> start;
  for (int k = 0; k < model.num_bases(); ++k) {
    drives.push_back(MakeBaseDrive(model.mobile_bases[k]));
    controllers.emplace_back(drives.back(), options.gains);
    start.push_back(plan.controls.front().segment<3>(plan.first[k]));
  }
  SimulatedBases bases(drives, start, options.noise);
  ChainAtBases chain(model, options);
  result->gait = chain.gait();
  result->torn_residual_energy = options.torn_residual_energy;

  const double t0 = plan.times.front();
  result->duration_s = plan.times.back() + options.settle_s - t0;  // <= the checked duration
  const double dt = 1.0 / options.gains.rate_hz;
  // Checked by IsValidReplay: at most kMaxReplayTicks, so the conversion is exact.
  const long ticks = static_cast<long>(std::ceil(result->duration_s * options.gains.rate_hz));
  double next_output = t0;
  // The chain's solves: every tick with a gait, else every output sample.
  const long solves = chain.gait() ? ticks + 1 : static_cast<long>(std::floor(result->duration_s * options.output_hz)) + 1;
  long solved = 0;
  for (long tick = 0; tick <= ticks; ++tick) {
    const double t = t0 + static_cast<double>(tick) * dt;
    const bool output = t + 1e-9 >= next_output;
    if (output || chain.gait()) {
      const ReplaySample sample = chain.At(t, plan, bases);
      if (options.on_solve) options.on_solve(++solved, std::max(solves, solved));
      if (chain.gait()) sums->Add(sample);
      if (output) {
        result->samples.push_back(sample);
        next_output += 1.0 / options.output_hz;
      }
    }
    const Eigen::VectorXd set = plan.SetControls(t);
    const Eigen::VectorXd set_velocity = plan.Velocity(t);
    for (int k = 0; k < model.num_bases(); ++k) {
      const Eigen::Vector2d twist = controllers[k].differential() ? plan.Twist(k, t, dt) : Eigen::Vector2d::Zero();
      const Eigen::VectorXd wheels = controllers[k].Update(set.segment<3>(plan.first[k]), set_velocity.segment<3>(plan.first[k]),
                                                           twist, bases.MeasuredPose(k));
      bases.CommandWheels(k, wheels);
    }
    bases.Advance(dt);
  }
}

// Torn samples, the worst E, and the RMSE of tracked against commanded per
// component (angles wrapped): over the output samples, or with legged bases
// over every controller tick (`sums`), as the gait's shares are.
void Summarize(const ErrorSums& sums, ReplayResult* result) {
  for (const ReplaySample& s : result->samples) {
    result->max_residual_energy = std::max(result->max_residual_energy, s.residual_energy);
    if (std::isnan(s.residual_energy)) result->max_residual_energy = s.residual_energy;
    if (!s.torn) continue;
    if (result->torn_samples++ == 0) result->first_torn_time = s.time;
    result->torn = true;
  }
  ErrorSums over_samples;
  for (const ReplaySample& s : result->samples) over_samples.Add(s);
  const ErrorSums& e = result->gait ? sums : over_samples;
  const auto rms = [&e](double sum) { return e.count == 0 ? 0 : std::sqrt(sum / static_cast<double>(e.count)); };
  for (int c = 0; c < 6; ++c) {
    result->rmse[c] = rms(e.tracked[c]);
    if (!result->gait) continue;
    result->gait_rmse[c] = rms(e.gait[c]);
    result->tracking_rmse[c] = rms(e.tracking[c]);
  }
}

}  // namespace

bool ReplayOptions::IsValid(std::string* why) const {
  if (!gains.IsValid(why) || !noise.IsValid(why) || !gait.IsValid(why)) return false;
  if (!(output_hz >= kMinOutputHz && output_hz <= kMaxOutputHz)) {
    return Fail(Format("ReplayOptions::output_hz (output sample rate) must lie in [%g, %g] Hz; got %g", kMinOutputHz,
                       kMaxOutputHz, output_hz),
                why);
  }
  if (!(settle_s >= 0 && settle_s <= kMaxTime)) {
    return Fail(Format("ReplayOptions::settle_s (time kept running after the last waypoint) must lie in [0, %g] s; "
                       "got %g",
                       kMaxTime, settle_s),
                why);
  }
  if (!(torn_residual_energy > 0 && torn_residual_energy <= 1)) {
    return Fail(Format("ReplayOptions::torn_residual_energy (chain residual energy of a torn sample) must lie in "
                       "(0, 1] m^2; got %g",
                       torn_residual_energy),
                why);
  }
  return true;
}

bool IsValidReplay(const std::vector<Waypoint>& waypoints, const ReplayOptions& options, std::string* why) {
  if (!options.IsValid(why)) return false;
  if (waypoints.empty()) return Fail("no waypoints", why);
  for (size_t i = 0; i < waypoints.size(); ++i) {
    const double t = waypoints[i].time;
    if (!(t >= -kMaxTime && t <= kMaxTime)) {
      return Fail("waypoint " + std::to_string(i) +
                      Format(": time %g s must lie in [%g, %g] s", t, -kMaxTime, kMaxTime),
                  why);
    }
    if (i > 0 && t < waypoints[i - 1].time) {
      return Fail("waypoint " + std::to_string(i) + Format(": time %g s is before the previous one (%g s)", t,
                                                                   waypoints[i - 1].time),
                  why);
    }
  }
  // All in double (at most 2e6 + 1e6 s here, times rates of at most 1e4 Hz):
  // no conversion happens before the comparisons.
  const double duration = waypoints.back().time - waypoints.front().time + options.settle_s;
  const double ticks = std::ceil(duration * options.gains.rate_hz);
  const double plant_steps = std::ceil(duration * std::max(options.noise.plant_hz, options.gains.rate_hz));
  const double samples = std::floor(duration * options.output_hz) + 1;
  const std::string span = Format("waypoints spanning %g s plus %g s of settling", duration - options.settle_s,
                                  options.settle_s);
  if (!(ticks <= static_cast<double>(kMaxReplayTicks))) {
    return Fail(span + Format(" at a controller rate of %g Hz make %g controller ticks; at most %g are allowed",
                              options.gains.rate_hz, ticks, static_cast<double>(kMaxReplayTicks)),
                why);
  }
  if (!(plant_steps <= static_cast<double>(kMaxReplayTicks))) {
    return Fail(span + Format(" at a plant rate of %g Hz make %g plant steps; at most %g are allowed",
                              std::max(options.noise.plant_hz, options.gains.rate_hz), plant_steps,
                              static_cast<double>(kMaxReplayTicks)),
                why);
  }
  if (!(samples <= static_cast<double>(kMaxReplaySamples))) {
    return Fail(span + Format(" at an output rate of %g Hz make %g samples; at most %g are allowed", options.output_hz,
                              samples, static_cast<double>(kMaxReplaySamples)),
                why);
  }
  return true;
}

bool IsValidReplay(const Model& model, const std::vector<Waypoint>& waypoints, const ReplayOptions& options,
                   std::string* why) {
  if (!IsValidReplay(waypoints, options, why)) return false;
  if (!HasLeggedBases(model)) return true;
  const double rate = options.gains.rate_hz;
  const double per_period = ReplayOptions::kMinTicksPerGaitPeriod;
  if (!(options.gait.hz * per_period <= rate)) {
    return Fail(Format("a gait of %g Hz (gait_hz) needs a controller rate (controller_hz) of at least %g Hz: the gait "
                       "is evaluated at every controller tick, at least 4 a gait period (fewer cannot show its bob); "
                       "it is %g Hz",
                       options.gait.hz, per_period * options.gait.hz, rate),
                why);
  }
  // Two chain solves a tick: bounded as the output samples are.
  const double duration = waypoints.back().time - waypoints.front().time + options.settle_s;
  const double ticks = std::ceil(duration * rate) + 1;
  if (!(ticks <= static_cast<double>(kMaxReplaySamples))) {
    return Fail(Format("with legged bases the chain is solved at every controller tick: %g s at %g Hz make %g ticks;",
                       duration, rate, ticks) +
                    Format(" at most %g are allowed", static_cast<double>(kMaxReplaySamples)),
                why);
  }
  return true;
}

ReplayResult Replay(const Model& model, const std::vector<Waypoint>& waypoints,
                    const ReplayOptions& options) {
  std::string why;
  if (!IsValidReplay(model, waypoints, options, &why)) throw std::invalid_argument(why);
  ReplayResult result;
  const Plan plan = MakePlan(model, waypoints, options, &result);
  ErrorSums sums;
  Simulate(model, plan, options, &result, &sums);
  Summarize(sums, &result);
  return result;
}

}  // namespace ccma
