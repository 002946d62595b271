#include "analyses/payload.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "ccma/internal/format.h"
#include "ccma/loads.h"
#include "problems/internal/compliant_equilibrium.h"
#include "problems/internal/equilibrium.h"

namespace ccma {
namespace {

// One limit's bound on m and its weights (dm = a . de_own + b . de_kg).
struct Bound {
  double m = std::numeric_limits<double>::infinity();
  Eigen::VectorXd a, b;
};

// lower <= e0 + m e1 <= upper at control c.
Bound JointBound(const EffortLimits& limits, int c, const Eigen::VectorXd& e0, const Eigen::VectorXd& e1) {
  Bound out;
  const double slope = e1[c];
  if (std::abs(slope) <= 1e-12 * (1 + std::abs(e0[c]))) return out;  // the payload does not load it
  const double bound = slope > 0 ? limits.upper : limits.lower;
  out.m = (bound - e0[c]) / slope;
  out.a = Eigen::VectorXd::Zero(e0.size());
  out.b = Eigen::VectorXd::Zero(e0.size());
  out.a[c] = -1 / slope;       // dm/de0_c
  out.b[c] = -out.m / slope;   // dm/de1_c
  return out;
}

// |v(m)| <= L with v = e0_xy + m e1_xy at controls (c, c + 1): the larger
// root of |v|^2 = L^2; dm = -(v . de0 + m v . de1) / (v . e1).
Bound PushBound(double limit, int c, const Eigen::VectorXd& e0, const Eigen::VectorXd& e1) {
  Bound out;
  const Eigen::Vector2d v0 = e0.segment<2>(c), v1 = e1.segment<2>(c);
  const double a = v1.squaredNorm(), b = 2 * v0.dot(v1), q = v0.squaredNorm() - limit * limit;
  if (a <= 1e-24 * (1 + v0.squaredNorm())) return out;
  const double disc = b * b - 4 * a * q;
  if (disc < 0) {  // within the limit at no payload at all
    out.m = -std::numeric_limits<double>::infinity();
    return out;
  }
  out.m = (-b + std::sqrt(disc)) / (2 * a);
  const Eigen::Vector2d v = v0 + out.m * v1;
  const double slope = v.dot(v1);
  out.a = Eigen::VectorXd::Zero(e0.size());
  out.b = Eigen::VectorXd::Zero(e0.size());
  out.a.segment<2>(c) = -v / slope;
  out.b.segment<2>(c) = -out.m * v / slope;
  return out;
}

// The first limit broken with no payload (efforts e0), as a note; "" when none.
// A limit counts as broken beyond a relative 1e-9, the solve's own noise.
std::string BrokenUnloaded(const Model& model, const Eigen::VectorXd& e0, std::string* name) {
  for (int k = 0; k < model.num_bases(); ++k) {
    const MobileBase& base = model.mobile_bases[static_cast<size_t>(k)];
    const double push = e0.segment<2>(model.base_control(k)).norm();
    if (base.push_limit > 0 && push > base.push_limit * (1 + 1e-9)) {
      *name = base.name;
      return "the mechanism breaks the push limit of " + Quote(base.name) + " with no payload (" + FormatG(push) +
             " N against " + FormatG(base.push_limit) + " N): no payload is within the limits";
    }
  }
  for (const Joint& joint : model.joints) {
    if (!joint.actuated || !joint.effort.given) continue;
    const double e = e0[joint.control], tolerance = 1e-9 * (1 + std::abs(e));
    if (e > joint.effort.upper + tolerance || e < joint.effort.lower - tolerance) {
      const char* unit = joint.type == JointType::kRevolute ? " N*m" : " N";
      *name = joint.name;
      return "the mechanism breaks the effort limits of " + Quote(joint.name) + " with no payload (" + FormatG(e) +
             unit + " outside [" + FormatG(joint.effort.lower) + ", " + FormatG(joint.effort.upper) + "]" + unit +
             "): no payload is within the limits";
    }
  }
  return "";
}

}  // namespace

double ReportedMass(const PayloadCapacity& capacity) {
  return capacity.broken_unloaded.empty() ? std::max(0.0, capacity.mass) : 0.0;
}

bool Reportable(const PayloadCapacity& capacity) {
  return !capacity.broken_unloaded.empty() || (capacity.defined && !capacity.unbounded);
}

Model WithoutPayload(const Model& model) {
  Model out = model;
  out.end_effector.payload.mass = 0;
  return out;
}

Model PayloadPerKilogram(const Model& model) {
  Model out = model;
  for (Body& body : out.bodies) body.inertia.mass = 0;
  if (!(model.end_effector.payload.mass > 0)) out.end_effector.payload.com_B = model.end_effector.p_B;
  out.end_effector.payload.mass = 1;
  return out;
}

PayloadCapacity ComputePayloadCapacity(const Model& model, const State& s, const Eigen::VectorXd& u) {
  PayloadCapacity out;
  const ConstraintSet set(model);
  const Equilibrium eq(set, s, u);
  const Eigen::VectorXd Q0 = GeneralizedLoads(WithoutPayload(model), s), Q1 = GeneralizedLoads(PayloadPerKilogram(model), s);
  const Eigen::VectorXd l0 = eq.Multipliers(Q0), l1 = eq.Multipliers(Q1);
  double residual = std::max((eq.J_s().transpose() * l0 + Q0).lpNorm<Eigen::Infinity>(),
                             (eq.J_s().transpose() * l1 + Q1).lpNorm<Eigen::Infinity>());
  Eigen::VectorXd e0 = eq.Efforts(l0), e1 = eq.Efforts(l1);
  if (model.compliant()) {
    // The compliant mechanism's efforts, as `ccma statics` reports them
    // (unique where the rigid ones are not; linear in the loads too).
    const CompliantEquilibrium system(model, set, s, u);
    double r0 = 0, r1 = 0;
    e0 = system.Efforts(Q0, &r0);
    e1 = system.Efforts(Q1, &r1);
    residual = std::max(r0, r1);
  }
  std::vector<std::pair<std::string, Bound>> bounds;
  for (int k = 0; k < model.num_bases(); ++k) {
    const MobileBase& base = model.mobile_bases[static_cast<size_t>(k)];
    if (base.push_limit > 0) bounds.emplace_back(base.name, PushBound(base.push_limit, model.base_control(k), e0, e1));
  }
  for (const Joint& joint : model.joints) {
    if (joint.actuated && joint.effort.given) bounds.emplace_back(joint.name, JointBound(joint.effort, joint.control, e0, e1));
  }
  if (bounds.empty()) {
    out.why = "the model gives no effort_limits and no push_limit";
    return out;
  }
  if (residual > 1e-8 * (1 + Q0.lpNorm<Eigen::Infinity>() + Q1.lpNorm<Eigen::Infinity>())) {
    out.why = "the joints cannot hold the loads here (unbalanced)";
    return out;
  }
  const auto* best = &bounds.front();
  for (const auto& b : bounds) {
    if (b.second.m < best->second.m) best = &b;
  }
  if (best->second.m == -std::numeric_limits<double>::infinity()) {
    out.why = "the push limit of " + Quote(best->first) + " is exceeded at every payload";
    out.broken_unloaded = best->first;
    out.note = out.why;
    return out;
  }
  out.note = BrokenUnloaded(model, e0, &out.broken_unloaded);
  out.unbounded = std::isinf(best->second.m);
  out.mass = out.unbounded ? 0.0 : best->second.m;
  out.limiting = best->first;
  out.weight_own = best->second.a.size() ? best->second.a : Eigen::VectorXd::Zero(e0.size());
  out.weight_kg = best->second.b.size() ? best->second.b : Eigen::VectorXd::Zero(e0.size());
  out.determinate = eq.AdjointOf(out.weight_own, Q0).unique && eq.AdjointOf(out.weight_kg, Q1).unique;
  out.defined = true;
  return out;
}

}  // namespace ccma
