#include "collision/clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Geometry>

namespace ccma {
namespace {

bool Near(const PlacedShape& p, const PlacedShape& q, double threshold) {
  for (int k = 0; k < 3; ++k) {
    if (p.box_min[k] > q.box_max[k] + threshold || q.box_min[k] > p.box_max[k] + threshold) return false;
  }
  return true;
}

// The gradient row of one shape's body: sign -1 for the first shape of a
// pair, +1 for the second (ShapeDistance: d moves by n . (dp_b - dp_a)).
Eigen::Matrix<double, 1, 6> Row(const CollisionModel& model, const State& s, int shape, const Eigen::Vector3d& p,
                                const Eigen::Vector3d& n, double sign) {
  Eigen::Matrix<double, 1, 6> g = Eigen::Matrix<double, 1, 6>::Zero();
  const int body = model.BodyOf(shape);
  if (body == kWorld) return g;
  if (model.IsBase(shape)) {
    g[3] = sign * n.x();
    g[4] = sign * n.y();
    return g;
  }
  g.head<3>() = sign * (p - s.p_WB(body)).cross(n).transpose();
  g.tail<3>() = sign * n.transpose();
  return g;
}

}  // namespace

void NearPairs(const CollisionModel& model, const std::vector<PlacedShape>& shapes, double threshold,
               std::vector<std::pair<int, int>>* pairs, std::vector<int>* order) {
  const int n = static_cast<int>(shapes.size());
  order->resize(static_cast<size_t>(n));
  std::iota(order->begin(), order->end(), 0);
  std::sort(order->begin(), order->end(), [&](int i, int j) { return shapes[i].box_min.x() < shapes[j].box_min.x(); });
  const size_t first = pairs->size();
  for (int k = 0; k < n; ++k) {
    const PlacedShape& p = shapes[(*order)[k]];
    for (int m = k + 1; m < n && shapes[(*order)[m]].box_min.x() <= p.box_max.x() + threshold; ++m) {
      const int i = (*order)[k], j = (*order)[m];
      if (Near(p, shapes[j], threshold) && model.Checked(i, j)) pairs->emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  std::sort(pairs->begin() + static_cast<long>(first), pairs->end());
}

std::vector<PairClearance> NearClearances(const CollisionModel& model, const std::vector<PlacedShape>& shapes,
                                          double threshold) {
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> order;
  NearPairs(model, shapes, threshold, &pairs, &order);
  std::vector<PairClearance> out;
  out.reserve(pairs.size());
  for (const auto& [a, b] : pairs) out.push_back({a, b, Distance(shapes[a], shapes[b])});
  return out;
}

ClearanceSummary MinimumClearance(const CollisionModel& model, const State& s) {
  ClearanceSummary out;
  if (!model.enabled() || model.num_shapes() < 2) return out;
  std::vector<PlacedShape> shapes;
  model.PlaceShapes(s, &shapes);
  Eigen::Vector3d lo = shapes[0].box_min, hi = shapes[0].box_max;
  for (const PlacedShape& p : shapes) lo = lo.cwiseMin(p.box_min), hi = hi.cwiseMax(p.box_max);
  const double extent = (hi - lo).norm();
  // Grow the broad phase's reach until it finds a pair (every pair within
  // the scene's extent at the end): near-linear for a crowded scene.
  for (double threshold = std::max(0.25, 2 * model.margin());; threshold *= 4) {
    const bool last = threshold > extent;
    const std::vector<PairClearance> near = NearClearances(model, shapes, last ? extent + 1.0 : threshold);
    for (const PairClearance& p : near) {
      if (!out.any || p.distance.distance < out.min) {
        out.any = true;
        out.min = p.distance.distance;
        out.a = model.Name(p.a);
        out.b = model.Name(p.b);
      }
    }
    // A pair found within `threshold` is the minimum only if it is within it.
    if ((out.any && out.min <= threshold) || last) break;
    out.any = false;
  }
  return out;
}

void ClearanceGradient(const CollisionModel& model, const State& s, const PairClearance& pair,
                       Eigen::Matrix<double, 1, 6>* g_a, Eigen::Matrix<double, 1, 6>* g_b) {
  *g_a = Row(model, s, pair.a, pair.distance.p_a, pair.distance.n, -1.0);
  *g_b = Row(model, s, pair.b, pair.distance.p_b, pair.distance.n, +1.0);
}

}  // namespace ccma
