#include "problems/internal/convex_polygon.h"

#include <algorithm>
#include <cmath>

namespace ccma {
namespace internal {

Polygon BoxPolygon(double x_lo, double x_hi, double y_lo, double y_hi) {
  return {Eigen::Vector2d(x_lo, y_lo), Eigen::Vector2d(x_hi, y_lo), Eigen::Vector2d(x_hi, y_hi),
          Eigen::Vector2d(x_lo, y_hi)};
}

// One pass of Sutherland-Hodgman: walk the edges v_k -> v_{k+1}, keep the
// inside vertices and add the crossing point of every edge that enters or
// leaves. For a convex polygon the result is convex with at most one more
// vertex.
void ClipByHalfPlane(const Polygon& polygon, double a, double b, double c, Polygon* out) {
  out->clear();
  const std::size_t n = polygon.size();
  if (n == 0) return;
  auto excess = [&](const Eigen::Vector2d& v) { return a * v.x() + b * v.y() - c; };
  auto inside = [&](const Eigen::Vector2d& v) {
    return excess(v) <= kClipSlack * (std::abs(a * v.x()) + std::abs(b * v.y()) + std::abs(c));
  };
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d& p = polygon[k];
    const Eigen::Vector2d& q = polygon[(k + 1) % n];
    const bool p_in = inside(p), q_in = inside(q);
    if (p_in) out->push_back(p);
    if (p_in == q_in) continue;
    // An inside end on the line (within the slack) is the crossing itself,
    // kept as a vertex already or next: no duplicate.
    const double fp = excess(p), fq = excess(q);
    if ((p_in ? fp : fq) >= 0) continue;
    // The crossing, from the end nearer the line: t = f_p / (f_p - f_q) is
    // accurate relative to itself, so p + t (q - p) is accurate when t is
    // small (the clamp only guards against rounding).
    if (std::abs(fp) <= std::abs(fq)) {
      out->push_back(p + std::clamp(fp / (fp - fq), 0.0, 1.0) * (q - p));
    } else {
      out->push_back(q + std::clamp(fq / (fq - fp), 0.0, 1.0) * (p - q));
    }
  }
}

double SignedArea(const Polygon& polygon) {
  double twice = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d& p = polygon[k];
    const Eigen::Vector2d& q = polygon[(k + 1) % polygon.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return twice / 2;
}

void XRange(const Polygon& polygon, double* x_min, double* x_max) {
  *x_min = polygon.front().x();
  *x_max = polygon.front().x();
  for (const Eigen::Vector2d& v : polygon) {
    *x_min = std::min(*x_min, v.x());
    *x_max = std::max(*x_max, v.x());
  }
}

}  // namespace internal
}  // namespace ccma
