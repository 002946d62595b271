#include "collision/collision_model.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace ccma {
namespace {

std::uint64_t Key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

PlacedShape ObstacleShapeOf(const Obstacle& o) {
  PlacedShape s;
  s.kind = ShapeKind::kPrism;
  s.center = o.center.head<2>();
  s.z_min = o.z_min;
  s.z_max = o.z_max;
  if (o.shape == ObstacleShape::kCylinder) {
    s.footprint = Footprint::kDisc;
    s.radius = o.radius;
  } else {
    s.footprint = Footprint::kRectangle;
    s.half_size = 0.5 * o.size.head<2>();
    s.cos_yaw = std::cos(o.yaw);
    s.sin_yaw = std::sin(o.yaw);
  }
  UpdateBoundingBox(&s);
  return s;
}

}  // namespace

CollisionModel::CollisionModel(const Model& model) {
  const CollisionGeometry& g = model.collision;
  enabled_ = g.enabled;
  margin_ = g.margin;
  if (!enabled_) return;
  num_bases_ = model.num_bases();
  for (const Body& body : model.bodies) names_.push_back(body.name);
  for (const Obstacle& o : g.obstacles) names_.push_back(o.name);
  for (int k = 0; k < model.num_bases(); ++k) {
    PlacedShape s;
    s.radius = g.base_radii.empty() ? g.base_radius : g.base_radii[static_cast<size_t>(k)];
    s.z_max = g.base_height;
    const MobileBase& base = model.mobile_bases[static_cast<size_t>(k)];
    const BaseCollisionShape shape = KindOf(base).CollisionShape(base);
    if (shape.rectangle) {
      // A box along its heading from the floor to its body (PlaceShapes
      // follows the body's height and heading).
      s.footprint = Footprint::kRectangle;
      s.half_size = shape.half_size;
      s.radius = shape.half_size.norm();
      s.z_max = model.bodies[static_cast<size_t>(base.body)].p_WB_home.z();
      boxes_.insert(static_cast<int>(local_.size()));
    }
    local_.push_back(s);
    bodies_.push_back(model.mobile_bases[k].body);
    owners_.push_back(model.mobile_bases[k].body);
    reach_ = std::max(reach_, s.radius);
  }
  for (const CollisionCapsule& c : g.links) {
    PlacedShape s;
    s.kind = ShapeKind::kCapsule;
    s.a_W = c.a_B;  // body frame until placed
    s.b_W = c.b_B;
    s.radius = c.radius;
    local_.push_back(s);
    bodies_.push_back(c.body);
    owners_.push_back(c.body);
    reach_ = std::max(reach_, std::max(c.a_B.norm(), c.b_B.norm()) + c.radius);
  }
  for (size_t o = 0; o < g.obstacles.size(); ++o) {
    local_.push_back(ObstacleShapeOf(g.obstacles[o]));
    bodies_.push_back(kWorld);
    owners_.push_back(model.num_bodies() + static_cast<int>(o));
  }
  for (const Joint& joint : model.joints) {
    if (joint.body_a != kWorld && joint.body_b != kWorld) skipped_.insert(Key(joint.body_a, joint.body_b));
  }
  std::unordered_map<std::string, int> owner_of;
  for (size_t i = 0; i < names_.size(); ++i) owner_of[names_[i]] = static_cast<int>(i);
  for (const auto& pair : g.ignore) {
    const auto a = owner_of.find(pair.first), b = owner_of.find(pair.second);
    if (a != owner_of.end() && b != owner_of.end()) skipped_.insert(Key(a->second, b->second));
  }
}

void CollisionModel::PlaceShapes(const State& s, std::vector<PlacedShape>* shapes) const {
  shapes->resize(local_.size());
  for (size_t i = 0; i < local_.size(); ++i) {
    PlacedShape& out = (*shapes)[i];
    out = local_[i];
    const int body = bodies_[i];
    if (body == kWorld) continue;  // obstacles: placed once, box included
    if (IsBase(static_cast<int>(i))) {
      out.center = s.p_WB(body).head<2>();
      if (boxes_.count(static_cast<int>(i)) != 0) {
        const Eigen::Vector3d heading_W = s.R_WB(body).col(0);
        const double norm = heading_W.head<2>().norm();
        out.cos_yaw = norm > 0 ? heading_W.x() / norm : 1.0;
        out.sin_yaw = norm > 0 ? heading_W.y() / norm : 0.0;
        out.z_max = s.p_WB(body).z();
      }
    } else {
      const Eigen::Matrix3d R_WB = s.R_WB(body);
      const Eigen::Vector3d p_WB = s.p_WB(body);
      out.a_W = R_WB * local_[i].a_W + p_WB;
      out.b_W = R_WB * local_[i].b_W + p_WB;
    }
    UpdateBoundingBox(&out);
  }
}

bool CollisionModel::Checked(int i, int j) const {
  if (i == j) return false;
  const int bi = bodies_[static_cast<size_t>(i)], bj = bodies_[static_cast<size_t>(j)];
  if (bi == kWorld && bj == kWorld) return false;
  const int oi = owners_[static_cast<size_t>(i)], oj = owners_[static_cast<size_t>(j)];
  if (oi == oj) return false;
  return skipped_.count(Key(oi, oj)) == 0;
}

}  // namespace ccma
