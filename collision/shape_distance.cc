// Closed forms for the clearance of two shapes (shapes.h). Every pair the
// model format allows has one, exact to rounding, so the step constraint's
// Newton iterations converge to 1e-10 m (a general GJK, e.g. FCL's, stops
// near 1e-6 m): tests compare them with FCL (tests/clearance_test.cc).
//  - prism-prism (a disc against a disc or a rectangle): the Minkowski
//    difference is again a vertical prism, so the distance combines the
//    footprints' planar distance and the gap between the height intervals;
//  - capsule-prism: the signed distance to a convex set is convex along the
//    capsule's segment: its minimum by golden-section search, minus the
//    capsule's radius;
//  - capsule-capsule: closest points of two segments (Ericson, Real-Time
//    Collision Detection, 5.1.9), minus both radii.
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "collision/shapes.h"

namespace ccma {
namespace {

// A signed distance and its unit gradient.
struct Signed2 {
  double d;
  Eigen::Vector2d g;
};
struct Signed3 {
  double d;
  Eigen::Vector3d g;
};

// Signed distance of the planar point q to a prism's footprint.
Signed2 FootprintDistance(const PlacedShape& s, const Eigen::Vector2d& q) {
  const Eigen::Vector2d rel = q - s.center;
  if (s.footprint == Footprint::kDisc) {
    const double norm = rel.norm();
    return {norm - s.radius, norm > 0 ? Eigen::Vector2d(rel / norm) : Eigen::Vector2d::UnitX()};
  }
  // Into the rectangle's axes, the box SDF, and back.
  const Eigen::Vector2d local(s.cos_yaw * rel.x() + s.sin_yaw * rel.y(), -s.sin_yaw * rel.x() + s.cos_yaw * rel.y());
  const Eigen::Vector2d excess = local.cwiseAbs() - s.half_size;
  Eigen::Vector2d g_local;
  double d;
  if (excess.maxCoeff() > 0) {
    const Eigen::Vector2d outside = excess.cwiseMax(0.0);
    d = outside.norm();
    g_local = outside / d;
  } else {
    const int axis = excess.x() > excess.y() ? 0 : 1;
    d = excess[axis];
    g_local = Eigen::Vector2d::Unit(axis);
  }
  g_local = g_local.cwiseProduct(Eigen::Vector2d(local.x() < 0 ? -1 : 1, local.y() < 0 ? -1 : 1));
  return {d, Eigen::Vector2d(s.cos_yaw * g_local.x() - s.sin_yaw * g_local.y(),
                             s.sin_yaw * g_local.x() + s.cos_yaw * g_local.y())};
}

// Combines a planar and a vertical signed distance of an extrusion.
Signed3 Extrude(const Signed2& xy, double z, double gz) {
  if (xy.d > 0 && z > 0) {
    const double d = std::hypot(xy.d, z);
    return {d, Eigen::Vector3d(xy.d * xy.g.x() / d, xy.d * xy.g.y() / d, z * gz / d)};
  }
  if (xy.d > z) return {xy.d, Eigen::Vector3d(xy.g.x(), xy.g.y(), 0)};
  return {z, Eigen::Vector3d(0, 0, gz)};
}

// Signed distance of the point q to the prism, gradient outward.
Signed3 PrismDistance(const PlacedShape& s, const Eigen::Vector3d& q) {
  const double below = s.z_min - q.z(), above = q.z() - s.z_max;
  return Extrude(FootprintDistance(s, q.head<2>()), std::max(below, above), below > above ? -1.0 : 1.0);
}

// Disc prism `a` against prism `b`; gradient: how d grows as a moves.
ShapeDistance DiscPrism(const PlacedShape& a, const PlacedShape& b) {
  Signed2 xy = FootprintDistance(b, a.center);
  xy.d -= a.radius;
  const double below = b.z_min - a.z_max, above = a.z_min - b.z_max;  // a below b, a above b
  const Signed3 s = Extrude(xy, std::max(below, above), below > above ? -1.0 : 1.0);
  ShapeDistance out;
  out.distance = s.d;
  out.n = -s.g;
  const double z = std::clamp(0.5 * (b.z_min + b.z_max), a.z_min, a.z_max);
  out.p_a = Eigen::Vector3d(a.center.x(), a.center.y(), z) - a.radius * Eigen::Vector3d(s.g.x(), s.g.y(), 0);
  out.p_b = out.p_a + s.d * out.n;
  return out;
}

// Capsule `c` against prism `p`; n from the prism toward the capsule.
ShapeDistance PrismCapsule(const PlacedShape& p, const PlacedShape& c) {
  const Eigen::Vector3d axis = c.b_W - c.a_W;
  auto f = [&](double t) { return PrismDistance(p, c.a_W + t * axis).d; };
  // Golden-section search for the minimum of a convex function on [0, 1].
  const double inv_phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 0, hi = 1, x1 = hi - inv_phi, x2 = lo + inv_phi, f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 80 && hi - lo > 1e-15; ++it) {
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - inv_phi * (hi - lo), f1 = f(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + inv_phi * (hi - lo), f2 = f(x2);
    }
  }
  double t = f1 <= f2 ? x1 : x2, best = std::min(f1, f2);
  for (double end : {0.0, 1.0}) {
    if (f(end) < best) best = f(end), t = end;
  }
  const Eigen::Vector3d q = c.a_W + t * axis;
  const Signed3 s = PrismDistance(p, q);
  ShapeDistance out;
  out.distance = s.d - c.radius;
  out.n = s.g;
  out.p_b = q - c.radius * s.g;
  out.p_a = q - s.d * s.g;
  return out;
}

// Closest points of segments p1-q1 and p2-q2: parameters s and t.
void ClosestSegmentParameters(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                              const Eigen::Vector3d& q2, double* s, double* t) {
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double tiny = 1e-300;
  if (a <= tiny && e <= tiny) {
    *s = *t = 0;
    return;
  }
  if (a <= tiny) {
    *s = 0, *t = std::clamp(f / e, 0.0, 1.0);
    return;
  }
  const double c = d1.dot(r);
  if (e <= tiny) {
    *t = 0, *s = std::clamp(-c / a, 0.0, 1.0);
    return;
  }
  const double b = d1.dot(d2), denom = a * e - b * b;
  *s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  *t = (b * *s + f) / e;
  if (*t < 0) {
    *t = 0, *s = std::clamp(-c / a, 0.0, 1.0);
  } else if (*t > 1) {
    *t = 1, *s = std::clamp((b - c) / a, 0.0, 1.0);
  }
}

ShapeDistance CapsuleCapsule(const PlacedShape& a, const PlacedShape& b) {
  double s = 0, t = 0;
  ClosestSegmentParameters(a.a_W, a.b_W, b.a_W, b.b_W, &s, &t);
  const Eigen::Vector3d pa = a.a_W + s * (a.b_W - a.a_W), pb = b.a_W + t * (b.b_W - b.a_W);
  const Eigen::Vector3d gap = pb - pa;
  const double norm = gap.norm();
  ShapeDistance out;
  if (norm > 0) {
    out.n = gap / norm;
  } else {  // crossing axes: across both
    const Eigen::Vector3d across = (a.b_W - a.a_W).cross(b.b_W - b.a_W);
    out.n = across.norm() > 0 ? Eigen::Vector3d(across.normalized()) : Eigen::Vector3d::UnitZ();
  }
  out.distance = norm - a.radius - b.radius;
  out.p_a = pa + a.radius * out.n;
  out.p_b = pb - b.radius * out.n;
  return out;
}

ShapeDistance Swapped(ShapeDistance d) {
  std::swap(d.p_a, d.p_b);
  d.n = -d.n;
  return d;
}

}  // namespace

void UpdateBoundingBox(PlacedShape* s) {
  if (s->kind == ShapeKind::kCapsule) {
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(s->radius);
    s->box_min = s->a_W.cwiseMin(s->b_W) - r;
    s->box_max = s->a_W.cwiseMax(s->b_W) + r;
    return;
  }
  Eigen::Vector2d half = Eigen::Vector2d::Constant(s->radius);
  if (s->footprint == Footprint::kRectangle) {
    const double c = std::abs(s->cos_yaw), n = std::abs(s->sin_yaw);
    half = Eigen::Vector2d(c * s->half_size.x() + n * s->half_size.y(), n * s->half_size.x() + c * s->half_size.y());
  }
  s->box_min << s->center - half, s->z_min;
  s->box_max << s->center + half, s->z_max;
}

ShapeDistance Distance(const PlacedShape& a, const PlacedShape& b) {
  const bool a_prism = a.kind == ShapeKind::kPrism, b_prism = b.kind == ShapeKind::kPrism;
  if (!a_prism && !b_prism) return CapsuleCapsule(a, b);
  if (a_prism && !b_prism) return PrismCapsule(a, b);
  if (!a_prism && b_prism) return Swapped(PrismCapsule(b, a));
  // Two prisms: at least one is a disc (obstacles are never checked against each other).
  if (a.footprint == Footprint::kDisc) return DiscPrism(a, b);
  return Swapped(DiscPrism(b, a));
}

}  // namespace ccma
