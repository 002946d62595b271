#include "analyses/dynamics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "ccma/base_kind.h"
#include "ccma/end_effector.h"
#include "ccma/inertial_loads.h"
#include "analyses/internal/motion_limits.h"
#include "ccma/internal/constraint_set.h"
#include "problems/forward_problem.h"
#include "problems/internal/control_motion.h"
#include "problems/internal/hessian_solver.h"
#include "problems/natural_spline.h"

namespace ccma {

InverseDynamics::InverseDynamics(const Model& model)
    : model_(model),
      set_(std::make_unique<ConstraintSet>(model)),
      symbolic_(std::make_unique<const HessianSolver>(*set_)),
      efforts_(model) {}
InverseDynamics::~InverseDynamics() = default;

DynamicsPoint InverseDynamics::At(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& du,
                                  const Eigen::VectorXd& ddu, const ExternalWrench& wrench) const {
  DynamicsPoint out;
  const ControlMotion motion(*set_, *symbolic_, s, u);
  out.velocity = motion.Velocity(du);
  out.acceleration = motion.Acceleration(du, ddu, out.velocity);
  out.rate_inconsistency = motion.Inconsistency(out.velocity, du);
  // Gravity, payload and wrench first, then the inertia: at rest Q_in is
  // exactly zero and the sum is statics' Q bit for bit.
  Eigen::VectorXd Q = GeneralizedLoads(model_, s, wrench);
  Q += InertialLoads(model_, s, out.velocity, out.acceleration);
  out.efforts = efforts_.AtLoads(s, u, Q, motion.factorization());
  out.kinetic = KineticEnergy(model_, s, out.velocity);
  out.potential = PotentialEnergy(model_, s);
  out.power = out.efforts.control_efforts.dot(du);
  return out;
}

namespace {

std::string Where(const ControlPath& path, size_t row) {
  const int line = row < path.lines.size() ? path.lines[row] : 0;
  return path.source + (line > 0 ? ":" + std::to_string(line) : "");
}

}  // namespace

// Base headings (theta, heading) unwrapped along the rows, so that the
// spline does not turn a base the long way round where the file wrapped an
// angle to (-pi, pi].
std::vector<Eigen::VectorXd> UnwrappedControls(const Model& model, std::vector<Eigen::VectorXd> controls) {
  for (int k = 0; k < model.num_bases(); ++k) {
    const std::vector<BaseControl> names = KindOf(model.mobile_bases[static_cast<size_t>(k)]).controls();
    for (size_t c = 0; c < names.size(); ++c) {
      const std::string name = names[c].name;
      if (name != "theta" && name != "heading") continue;
      const int i = model.base_control(k) + static_cast<int>(c);
      for (size_t r = 1; r < controls.size(); ++r) {
        const double step = controls[r][i] - controls[r - 1][i];
        controls[r][i] = controls[r - 1][i] + std::remainder(step, 2 * M_PI);
      }
    }
  }
  return controls;
}

// The assembled end-effector against the file's reached point.
void CheckReachedPoint(const Model& model, const State& s, const ControlPath& path, size_t row) {
  if (row >= path.reached.size() || !path.reached[row]) return;
  const Eigen::Vector3d p = ComputeEndEffectorPose(model, s).position;
  const double gap = (p - *path.reached[row]).norm();
  if (gap > 1e-6) {
    throw std::invalid_argument(Where(path, row) + ": columns x_m, y_m, z_m: the model's end-effector assembles " +
                                std::to_string(gap) + " m away from the row's (a trajectory of another model?)");
  }
}

namespace {

// Each control's name and kind, in control order, and its effort limit.
std::vector<ActuatorSummary> Actuators(const Model& model) {
  std::vector<ActuatorSummary> out;
  for (int k = 0; k < model.num_bases(); ++k) {
    const MobileBase& base = model.mobile_bases[static_cast<size_t>(k)];
    const std::vector<BaseControl>& names = KindOf(base).controls();
    for (size_t c = 0; c < names.size(); ++c) {
      ActuatorSummary a;
      a.name = base.name;
      a.kind = std::string("base_") + names[c].name;
      if (base.push_limit > 0 && c < 2) a.limit = std::make_pair(-base.push_limit, base.push_limit);
      out.push_back(a);
    }
  }
  for (const Joint& joint : model.joints) {
    if (!joint.actuated) continue;
    ActuatorSummary a;
    a.name = joint.name;
    a.kind = "joint";
    if (joint.effort.given) a.limit = std::make_pair(joint.effort.lower, joint.effort.upper);
    out.push_back(a);
  }
  return out;
}

// Peaks, rms and limits over the assembled rows; the report's totals.
void Summarise(const Model& model, DynamicsReport* report) {
  DynamicsReport& out = *report;
  out.actuators = Actuators(model);
  std::vector<double> integral(out.actuators.size(), 0.0);
  const DynamicsRow* previous = nullptr;
  bool any = false;  // an assembled row seen
  for (const DynamicsRow& row : out.rows) {
    if (!row.assembled) {
      previous = nullptr;
      continue;
    }
    for (size_t i = 0; i < out.actuators.size(); ++i) {
      ActuatorSummary& a = out.actuators[i];
      const double rate = row.rates[static_cast<Eigen::Index>(i)];
      if (std::abs(rate) > std::abs(a.peak_rate)) a.peak_rate = rate;
      const double e = row.efforts[static_cast<Eigen::Index>(i)];
      if (std::abs(e) > std::abs(a.peak_effort)) {
        a.peak_effort = e;
        a.peak_time = row.time;
      }
      if (previous != nullptr) {
        const double e0 = previous->efforts[static_cast<Eigen::Index>(i)];
        integral[i] += 0.5 * (e0 * e0 + e * e) * (row.time - previous->time);
      }
    }
    if (previous != nullptr) out.energy += 0.5 * (previous->power + row.power) * (row.time - previous->time);
    out.max_power = any ? std::max(out.max_power, row.power) : row.power;
    any = true;
    previous = &row;
  }
  for (size_t i = 0; i < out.actuators.size(); ++i) {
    out.actuators[i].rms_effort = out.duration > 0 ? std::sqrt(integral[i] / out.duration) : 0.0;
  }
}

// The actuators beyond their limits at one row (StaticsReport::limiting)
// into the summaries and the report.
void MarkLimits(const std::vector<std::string>& limiting, DynamicsReport* report) {
  for (const std::string& name : limiting) {
    for (ActuatorSummary& a : report->actuators) {
      if (a.name == name && a.limit) a.within_limits = false;
    }
    if (std::find(report->limiting.begin(), report->limiting.end(), name) == report->limiting.end()) {
      report->limiting.push_back(name);
    }
  }
}

// The rates against every velocity_limit (internal/motion_limits.h), at
// the assembled rows: each control's rate_limit, and the controls and
// names beyond one (1e-9 relative: a retimed path sits on its limits).
void JudgeRates(const Model& model, DynamicsReport* report) {
  for (const internal::MotionLimit& limit : internal::MotionLimits(model)) {
    if (limit.kind != internal::MotionLimit::Kind::kVelocity) continue;
    for (const int c : limit.controls) report->actuators[static_cast<size_t>(c)].rate_limit = limit.upper;
    bool beyond = false;
    for (DynamicsRow& row : report->rows) {
      if (!row.assembled || internal::Utilisation(limit, row.efforts, row.rates) <= 1 + 1e-9) continue;
      row.within_limits = false;
      beyond = true;
    }
    if (!beyond) continue;
    for (const int c : limit.controls) report->actuators[static_cast<size_t>(c)].within_limits = false;
    if (std::find(report->limiting.begin(), report->limiting.end(), limit.name) == report->limiting.end()) {
      report->limiting.push_back(limit.name);
    }
  }
}

}  // namespace

DynamicsReport ComputeDynamics(const Model& model, const ControlPath& path, const ExternalWrench& wrench) {
  const NaturalCubicSpline spline(path.times, UnwrappedControls(model, path.controls));
  const InverseDynamics dynamics(model);
  ForwardProblem forward(model);
  DynamicsReport out;
  out.duration = path.times.back() - path.times.front();
  std::vector<std::vector<std::string>> limiting;  // per assembled row
  for (size_t r = 0; r < path.times.size(); ++r) {
    DynamicsRow row;
    row.time = path.times[r];
    const ForwardResult assembly = forward.Assemble(path.controls[r]);
    row.assembled = assembly.assembled;
    row.residual_energy = assembly.residual_energy;
    row.rates = spline.KnotRate(static_cast<int>(r));
    if (row.assembled) {
      CheckReachedPoint(model, forward.state(), path, r);
      const DynamicsPoint p = dynamics.At(forward.state(), forward.controls(), row.rates,
                                          spline.KnotAcceleration(static_cast<int>(r)), wrench);
      row.efforts = p.efforts.control_efforts;
      row.kinetic = p.kinetic;
      row.potential = p.potential;
      row.power = p.power;
      row.within_limits = p.efforts.within_limits;
      out.max_rate_inconsistency = std::max(out.max_rate_inconsistency, p.rate_inconsistency);
      limiting.push_back(p.efforts.limiting);
    } else {
      ++out.not_assembled_rows;
      out.assembled = false;
    }
    out.rows.push_back(std::move(row));
  }
  Summarise(model, &out);
  for (const std::vector<std::string>& names : limiting) MarkLimits(names, &out);
  JudgeRates(model, &out);
  out.within_limits = out.limiting.empty();
  return out;
}

}  // namespace ccma
