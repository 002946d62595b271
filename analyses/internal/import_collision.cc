#include "analyses/internal/import_collision.h"

#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "ccma/limits.h"
#include "collision/clearance.h"
#include "collision/collision_model.h"
#include "formats/model_loader.h"

namespace ccma {
namespace internal {
namespace {

// Points closer than this [m] are one point (a joint and the closure that
// meets it at the same place).
constexpr double kSamePoint = 1e-9;

// The distinct joint points of every body (body frame), the end-effector
// point included, in joint order.
std::vector<std::vector<Eigen::Vector3d>> BodyPoints(const Model& model) {
  std::vector<std::vector<Eigen::Vector3d>> points(static_cast<std::size_t>(model.num_bodies()));
  const auto add = [&](int body, const Eigen::Vector3d& p_B) {
    if (body == kWorld) return;
    std::vector<Eigen::Vector3d>& list = points[static_cast<std::size_t>(body)];
    for (const Eigen::Vector3d& q : list) {
      if ((q - p_B).norm() < kSamePoint) return;
    }
    list.push_back(p_B);
  };
  for (const Joint& joint : model.joints) {
    add(joint.body_a, joint.p_A);
    add(joint.body_b, joint.p_B);
  }
  add(model.end_effector.body, model.end_effector.p_B);
  return points;
}

// The shortest tree joining `points` (Prim): one capsule per edge, or one
// sphere when there is a single point.
void AddTreeCapsules(int body, const std::vector<Eigen::Vector3d>& points, double radius,
                     std::vector<CollisionCapsule>* capsules) {
  const std::size_t n = points.size();
  if (n == 1) {
    capsules->push_back({body, points[0], points[0], radius, 0});
    return;
  }
  std::vector<bool> in(n, false);
  std::vector<double> best(n, std::numeric_limits<double>::infinity());
  std::vector<std::size_t> from(n, 0);
  best[0] = 0;
  for (std::size_t added = 0; added < n; ++added) {
    std::size_t next = n;
    for (std::size_t i = 0; i < n; ++i) {
      if (!in[i] && (next == n || best[i] < best[next])) next = i;
    }
    in[next] = true;
    if (added > 0) capsules->push_back({body, points[from[next]], points[next], radius, 0});
    for (std::size_t i = 0; i < n; ++i) {
      const double d = (points[i] - points[next]).norm();
      if (!in[i] && d < best[i]) best[i] = d, from[i] = next;
    }
  }
}

}  // namespace

ImportCollisionCounts AddImportCollision(double radius, const std::string& source, Model* home) {
  CollisionGeometry& geometry = home->collision;
  geometry.enabled = true;
  const std::vector<std::vector<Eigen::Vector3d>> points = BodyPoints(*home);
  ImportCollisionCounts counts;
  for (int b = 0; b < home->num_bodies(); ++b) {
    if (home->bodies[b].is_mobile_base() || points[static_cast<std::size_t>(b)].empty()) continue;
    AddTreeCapsules(b, points[static_cast<std::size_t>(b)], radius, &geometry.links);
  }
  counts.capsules = static_cast<int>(geometry.links.size());
  if (counts.capsules > kMaxCollisionLinks) {
    throw ModelError(source + ": --collision_radius: " + std::to_string(counts.capsules) +
                     " capsules, more than a model file holds (" + std::to_string(kMaxCollisionLinks) + ")");
  }
  const CollisionModel shapes_model(*home);
  std::vector<PlacedShape> shapes;
  shapes_model.PlaceShapes(State::Home(*home), &shapes);
  std::set<std::pair<std::string, std::string>> ignored;
  for (const PairClearance& pair : NearClearances(shapes_model, shapes, geometry.margin)) {
    if (pair.distance.distance >= geometry.margin) continue;
    ignored.emplace(shapes_model.Name(pair.a), shapes_model.Name(pair.b));
  }
  if (static_cast<int>(ignored.size()) > kMaxIgnoredPairs) {
    throw ModelError(source + ": --collision_radius: " + std::to_string(ignored.size()) +
                     " body pairs touch at home, more than a model file can ignore (" +
                     std::to_string(kMaxIgnoredPairs) + "): give a smaller radius");
  }
  geometry.ignore.assign(ignored.begin(), ignored.end());
  counts.ignored_pairs = static_cast<int>(ignored.size());
  return counts;
}

}  // namespace internal
}  // namespace ccma
