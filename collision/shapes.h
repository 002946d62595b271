// Collision shapes placed in the world at one state (collision_model.h
// places them). Two kinds:
//  - a vertical prism over [z_min, z_max] whose footprint is a disc or a
//    rectangle turned about z: a mobile base's cylinder (from the floor), an
//    obstacle's cylinder or box;
//  - a capsule: the segment a_W-b_W swept by a sphere of `radius`, a link.
// Units: metres, radians; W = world, z up, floor z = 0.
#ifndef CCMA_COLLISION_SHAPES_H_
#define CCMA_COLLISION_SHAPES_H_

#include <Eigen/Core>

namespace ccma {

enum class ShapeKind { kPrism, kCapsule };
enum class Footprint { kDisc, kRectangle };

struct PlacedShape {
  ShapeKind kind = ShapeKind::kPrism;
  // Prism.
  Footprint footprint = Footprint::kDisc;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // footprint centre [m]
  double radius = 0;                                 // disc [m]; capsule too
  Eigen::Vector2d half_size = Eigen::Vector2d::Zero();  // rectangle, in its own axes [m]
  double cos_yaw = 1, sin_yaw = 0;                      // rectangle axes in W
  double z_min = 0, z_max = 0;
  // Capsule.
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero(), b_W = Eigen::Vector3d::Zero();
  // Axis-aligned box around the shape (broad phase).
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero(), box_max = Eigen::Vector3d::Zero();
};

// The clearance of two shapes and how it changes: d moves by
// n . (dp_b - dp_a) when the witness point p_a of the first shape moves by
// dp_a and p_b of the second by dp_b (rigidly with their shapes). d < 0: the
// depth by which they overlap.
struct ShapeDistance {
  double distance = 0;  // m
  Eigen::Vector3d p_a = Eigen::Vector3d::Zero();  // witness on the first [m, W]
  Eigen::Vector3d p_b = Eigen::Vector3d::Zero();  // witness on the second
  Eigen::Vector3d n = Eigen::Vector3d::UnitX();   // unit, from a toward b
};

// Sets shape->box_min/box_max from its geometry.
void UpdateBoundingBox(PlacedShape* shape);

// The clearance of two placed shapes (closed forms, shape_distance.cc).
ShapeDistance Distance(const PlacedShape& a, const PlacedShape& b);

}  // namespace ccma

#endif  // CCMA_COLLISION_SHAPES_H_
