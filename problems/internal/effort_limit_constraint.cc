#include "problems/internal/effort_limit_constraint.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "ccma/internal/format.h"
#include "ccma/loads.h"
#include "problems/internal/equilibrium.h"

namespace ccma {
namespace {

// Central-difference step along a motion, relative to its largest entry.
constexpr double kMotionStep = 1e-6;

}  // namespace

bool HasEffortLimits(const Model& model) {
  bool limits = false, mass = model.end_effector.payload.mass > 0;
  for (const MobileBase& base : model.mobile_bases) limits = limits || base.push_limit > 0;
  for (const Joint& joint : model.joints) limits = limits || (joint.actuated && joint.effort.given);
  for (const Body& body : model.bodies) mass = mass || body.inertia.mass > 0;
  return limits && mass;
}

EffortLimitConstraint::EffortLimitConstraint(const Model& model, std::vector<int> effective)
    : model_(model), set_(model), effective_(std::move(effective)) {
  for (int k = 0; k < model.num_bases(); ++k) {
    const MobileBase& base = model.mobile_bases[static_cast<size_t>(k)];
    if (base.push_limit > 0) items_.push_back({base.name, true, 3 * k, 0.0, base.push_limit, " N"});
  }
  for (const Joint& joint : model.joints) {
    if (joint.actuated && joint.effort.given) {
      items_.push_back({joint.name, false, joint.control, joint.effort.lower, joint.effort.upper,
                        joint.type == JointType::kRevolute ? " N*m" : " N"});
    }
  }
}

EffortLimitConstraint::Reading EffortLimitConstraint::Read(const Item& item, const Eigen::VectorXd& e) const {
  Reading r;
  r.w = Eigen::VectorXd::Zero(e.size());
  if (item.push) {
    const Eigen::Vector2d v = e.segment<2>(item.control);
    r.value = v.norm();
    r.bound = item.upper;
    if (r.value > 0) r.w.segment<2>(item.control) = v / r.value;
  } else {
    r.value = e[item.control];
    r.bound = std::abs(r.value - item.lower) < std::abs(r.value - item.upper) ? item.lower : item.upper;
    r.w[item.control] = 1;
  }
  r.scale = std::max({1.0, std::abs(item.lower), std::abs(item.upper)});
  return r;
}

Eigen::VectorXd EffortLimitConstraint::Efforts(const Eigen::VectorXd& u, const State& s) const {
  const Equilibrium eq(set_, s, u);
  return eq.Efforts(eq.Multipliers(GeneralizedLoads(model_, s)));
}

double EffortLimitConstraint::AlongChange(const Eigen::VectorXd& u, const State& s, const Reading& reading,
                                          const Eigen::VectorXd& d) const {
  const Equilibrium eq(set_, s, u);
  const Equilibrium::Adjoint adjoint = eq.AdjointOf(reading.w, GeneralizedLoads(model_, s));
  Eigen::VectorXd du = Eigen::VectorXd::Zero(u.size());
  for (size_t i = 0; i < effective_.size(); ++i) du[effective_[i]] = d[static_cast<Eigen::Index>(i)];
  const Eigen::VectorXd ds = eq.StateMotion(du);
  const double size = std::max(ds.lpNorm<Eigen::Infinity>(), du.lpNorm<Eigen::Infinity>());
  const double h = kMotionStep / std::max(1.0, size);
  State plus = s, minus = s;
  plus.Plus(h * ds);
  minus.Plus(-h * ds);
  return (EffortLagrangian(set_, model_, plus, u + h * du, reading.w, adjoint) -
          EffortLagrangian(set_, model_, minus, u - h * du, reading.w, adjoint)) /
         (2 * h);
}

Eigen::RowVectorXd EffortLimitConstraint::Gradient(const Eigen::VectorXd& u, const State& s,
                                                   const Reading& reading) const {
  Eigen::RowVectorXd g(static_cast<Eigen::Index>(effective_.size()));
  for (Eigen::Index i = 0; i < g.size(); ++i) {
    g[i] = AlongChange(u, s, reading, Eigen::VectorXd::Unit(g.size(), i));
  }
  return g;
}

double EffortLimitConstraint::MaxViolation(const Eigen::VectorXd& u, const State& s) const {
  const Eigen::VectorXd e = Efforts(u, s);
  double worst = 0;
  for (const Item& item : items_) {
    const Reading r = Read(item, e);
    worst = std::max({worst, (r.value - item.upper) / r.scale, (item.push ? 0.0 : item.lower - r.value) / r.scale});
  }
  return worst;
}

void EffortLimitConstraint::AppendRows(const Eigen::VectorXd& u, const State& s, const SensitivityView& /*ds_du*/,
                                       const std::vector<int>& active, int first_row, LinearConstraints* rows) const {
  const Eigen::VectorXd e = Efforts(u, s);
  int row = first_row;
  for (int i : active) {
    const Reading r = Read(items_[static_cast<size_t>(i)], e);
    rows->A.row(row) = Gradient(u, s, r) / r.scale;
    rows->b[row] = (r.bound - r.value) / r.scale;
    ++row;
  }
}

std::vector<int> EffortLimitConstraint::WouldCross(const Eigen::VectorXd& u, const State& s,
                                                   const SensitivityView& /*ds_du*/, const Eigen::VectorXd& d,
                                                   double tolerance) const {
  const Eigen::VectorXd e = Efforts(u, s);
  std::vector<int> out;
  for (int i = 0; i < num_items(); ++i) {
    const Item& item = items_[static_cast<size_t>(i)];
    const Reading r = Read(item, e);
    const double next = r.value + AlongChange(u, s, r, d);
    if (next > item.upper + tolerance * r.scale || (!item.push && next < item.lower - tolerance * r.scale)) {
      out.push_back(i);
    }
  }
  return out;
}

std::vector<int> EffortLimitConstraint::AtOrBeyond(const Eigen::VectorXd& u, const State& s, double tolerance) const {
  const Eigen::VectorXd e = Efforts(u, s);
  std::vector<int> out;
  for (int i = 0; i < num_items(); ++i) {
    const Item& item = items_[static_cast<size_t>(i)];
    const Reading r = Read(item, e);
    if (r.value >= item.upper - tolerance * r.scale || (!item.push && r.value <= item.lower + tolerance * r.scale)) {
      out.push_back(i);
    }
  }
  return out;
}

void EffortLimitConstraint::AppendInequalities(const Eigen::VectorXd& u, const State& s, const SensitivityView& /*ds_du*/,
                                               double watch, std::vector<InequalityRow>* rows) const {
  const Eigen::VectorXd e = Efforts(u, s);
  for (int i : AtOrBeyond(u, s, watch)) {
    const Item& item = items_[static_cast<size_t>(i)];
    const Reading r = Read(item, e);
    const Eigen::RowVectorXd a = Gradient(u, s, r) / r.scale;
    if (r.value >= item.upper - watch * r.scale) rows->push_back({-a, (r.value - item.upper) / r.scale});
    if (!item.push && r.value <= item.lower + watch * r.scale) rows->push_back({a, (item.lower - r.value) / r.scale});
  }
}

std::string EffortLimitConstraint::Report(const Eigen::VectorXd& u, const State& s, const std::vector<int>& active,
                                          ControlStepResult* result) const {
  const Eigen::VectorXd e = Efforts(u, s);
  double worst = 0;
  for (const Item& item : items_) {
    const Reading r = Read(item, e);
    worst = std::max({worst, r.value - item.upper, item.push ? 0.0 : item.lower - r.value});
  }
  result->max_effort_violation = worst;
  if (AtOrBeyond(u, s, 1e-8).empty()) return "";
  std::string text;
  for (int i : active) {
    const Item& item = items_[static_cast<size_t>(i)];
    const Reading r = Read(item, e);
    const bool upper = r.bound == item.upper;
    text += std::string(text.empty() ? "" : ", ") + (item.push ? "push of '" : "effort of '") + item.name +
            (item.push ? "' at its limit " : upper ? "' at its upper limit " : "' at its lower limit ") +
            FormatG(r.bound) + item.unit;
  }
  return text;
}

}  // namespace ccma
