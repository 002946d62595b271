#include "analyses/internal/motion_limits.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ccma::internal {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kPushSides = 32;
// A motion's part of an effort below this (relative to the effort and its
// limit) is rounding: a motion that feels no inertia at a row.
constexpr double kNoise = 1e-12;

// The limited part of v: one entry, or the norm of two.
double Norm(const MotionLimit& limit, const Eigen::VectorXd& v) {
  if (limit.controls.size() == 1) return std::abs(v[limit.controls[0]]);
  return std::hypot(v[limit.controls[0]], v[limit.controls[1]]);
}

Eigen::Vector2d Pair(const MotionLimit& limit, const Eigen::VectorXd& v) {
  return Eigen::Vector2d(v[limit.controls[0]], v[limit.controls[1]]);
}

// Largest w >= 0 with |c + d w| <= P (|c| < P): the push's stretch k = 1/sqrt(w).
double PushStretch(const Eigen::Vector2d& c, const Eigen::Vector2d& d, double P) {
  if (!(c.norm() < P)) return kInf;
  const double A = d.squaredNorm(), B = c.dot(d), C = c.squaredNorm() - P * P;
  if (std::sqrt(A) <= kNoise * (c.norm() + P)) return 0;  // rounding, not inertia
  const double w = (-B + std::sqrt(B * B - A * C)) / A;  // > 0 since C < 0
  return 1 / std::sqrt(w);
}

}  // namespace

const char* KindName(MotionLimit::Kind kind) {
  switch (kind) {
    case MotionLimit::Kind::kEffort: return "effort";
    case MotionLimit::Kind::kPush: return "push";
    case MotionLimit::Kind::kVelocity: return "velocity";
  }
  return "effort";
}

std::vector<MotionLimit> MotionLimits(const Model& model) {
  std::vector<MotionLimit> out;
  for (int k = 0; k < model.num_bases(); ++k) {
    const MobileBase& base = model.mobile_bases[static_cast<size_t>(k)];
    const int first = model.base_control(k);
    if (base.push_limit > 0) out.push_back({MotionLimit::Kind::kPush, base.name, {first, first + 1}, 0, base.push_limit});
    const std::vector<double>& v = base.velocity_limit;
    for (size_t i = 0; i < v.size(); ++i) {
      std::vector<int> controls = i == 0 ? std::vector<int>{first, first + 1} : std::vector<int>{first + 1 + static_cast<int>(i)};
      out.push_back({MotionLimit::Kind::kVelocity, base.name, controls, 0, v[i]});
    }
  }
  for (const Joint& joint : model.joints) {
    if (!joint.actuated) continue;
    if (joint.effort.given) {
      out.push_back({MotionLimit::Kind::kEffort, joint.name, {joint.control}, joint.effort.lower, joint.effort.upper});
    }
    if (joint.velocity_limit > 0) out.push_back({MotionLimit::Kind::kVelocity, joint.name, {joint.control}, 0, joint.velocity_limit});
  }
  return out;
}

double Utilisation(const MotionLimit& limit, const Eigen::VectorXd& e, const Eigen::VectorXd& du) {
  switch (limit.kind) {
    case MotionLimit::Kind::kEffort: {
      const double v = e[limit.controls[0]];
      if (v >= 0) return limit.upper > 0 ? v / limit.upper : (v > 0 || limit.upper < 0 ? kInf : 0.0);
      return limit.lower < 0 ? v / limit.lower : kInf;
    }
    case MotionLimit::Kind::kPush: return Norm(limit, e) / limit.upper;
    case MotionLimit::Kind::kVelocity: return Norm(limit, du) / limit.upper;
  }
  return 0;
}

double RequiredStretch(const MotionLimit& limit, const Eigen::VectorXd& c, const Eigen::VectorXd& d,
                       const Eigen::VectorXd& du) {
  switch (limit.kind) {
    case MotionLimit::Kind::kVelocity: return Norm(limit, du) / limit.upper;
    case MotionLimit::Kind::kPush: return PushStretch(Pair(limit, c), Pair(limit, d), limit.upper);
    case MotionLimit::Kind::kEffort: {
      const double c0 = c[limit.controls[0]], d0 = d[limit.controls[0]];
      if (!(c0 >= limit.lower && c0 <= limit.upper)) return kInf;
      if (std::abs(d0) <= kNoise * (std::abs(c0) + std::abs(limit.lower) + std::abs(limit.upper))) return 0;
      const double room = d0 > 0 ? limit.upper - c0 : c0 - limit.lower;
      return room > 0 ? std::sqrt(std::abs(d0) / room) : kInf;
    }
  }
  return 0;
}

void AddStageConstraints(const MotionLimit& limit, int id, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                         const Eigen::VectorXd& c, const Eigen::VectorXd& u_s, double margin, double room,
                         ToppStage* stage) {
  switch (limit.kind) {
    case MotionLimit::Kind::kEffort: {
      const int j = limit.controls[0];
      const double width = limit.upper - limit.lower;
      const double hi = limit.upper - margin * width, lo = limit.lower + margin * width;
      stage->constraints.push_back({a[j], b[j], room * (hi - c[j]), id});
      stage->constraints.push_back({-a[j], -b[j], room * (c[j] - lo), id});
      return;
    }
    case MotionLimit::Kind::kPush: {
      // The inscribed polygon's sides sit at P cos(pi / n) from the centre.
      const double reach = limit.upper * (1 - margin) * std::cos(M_PI / kPushSides);
      const Eigen::Vector2d pa = Pair(limit, a), pb = Pair(limit, b), pc = Pair(limit, c);
      for (int k = 0; k < kPushSides; ++k) {
        const Eigen::Vector2d n(std::cos(2 * M_PI * k / kPushSides), std::sin(2 * M_PI * k / kPushSides));
        stage->constraints.push_back({n.dot(pa), n.dot(pb), room * (reach - n.dot(pc)), id});
      }
      return;
    }
    case MotionLimit::Kind::kVelocity: {
      const double rate = Norm(limit, u_s);  // |u'| per unit s'
      if (rate == 0) return;
      const double bound = limit.upper * (1 - margin) / rate;
      const double x_max = room * bound * bound;
      if (x_max < stage->x_max) {
        stage->x_max = x_max;
        stage->x_max_id = id;
      }
      return;
    }
  }
}

}  // namespace ccma::internal
