// Collision geometry of a model (model_format.md, "Collision geometry and
// obstacles"): the shapes that control keeps apart, as the model file gives
// them. Mobile bases are vertical cylinders from the floor (z = 0) to
// base_height; links are capsules fixed in bodies; obstacles are fixed in
// the world. The distances between them live in collision/ (clearance.h).
//
// Units: metres, radians.
#ifndef CCMA_COLLISION_GEOMETRY_H_
#define CCMA_COLLISION_GEOMETRY_H_

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace ccma {

// A capsule (a segment swept by a sphere) fixed in a body.
struct CollisionCapsule {
  int body = -1;                              // index into Model::bodies
  Eigen::Vector3d a_B = Eigen::Vector3d::Zero();  // segment ends in the body frame [m]
  Eigen::Vector3d b_B = Eigen::Vector3d::Zero();
  double radius = 0;                          // m, > 0
  int line = 0;                               // source line (for messages)
};

enum class ObstacleShape { kCylinder, kBox };

// An obstacle fixed in the world: a vertical prism over [z_min, z_max].
// Cylinder: footprint a disc of `radius` about (center.x, center.y), from
// the floor to its height. Box: footprint a rectangle of size.x by size.y
// turned by `yaw` about z, over center.z -/+ size.z / 2.
struct Obstacle {
  std::string name;
  ObstacleShape shape = ObstacleShape::kCylinder;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // m (cylinder: z unused)
  double radius = 0;                                 // cylinder [m]
  Eigen::Vector3d size = Eigen::Vector3d::Zero();    // box [m]
  double yaw = 0;                                    // box [rad]
  double z_min = 0, z_max = 0;                       // m
  std::string source;                                // file that declared it
  int line = 0;
};

// The margin a model gets when it gives none [m].
constexpr double kDefaultMargin = 0.02;

struct CollisionGeometry {
  // Whether clearance is computed and kept: the model has a `collision:` or
  // an `obstacles:` key, or obstacles were added (--obstacles).
  bool enabled = false;
  double margin = kDefaultMargin;  // m: control keeps every clearance >= margin
  // m: the radius of the cylinder of a base without its own `radius:`;
  // collision.base_radius, or 0.3 m where that leaves every two bases twice
  // the margin apart at home, else the largest radius that does
  // (formats/internal/base_radius_fit.h).
  double base_radius = 0.3;
  double base_height = 0.2;   // m: every base's cylinder spans [0, base_height]
  std::vector<double> base_radii;  // per mobile base [m]: its own `radius:` or base_radius
  std::vector<CollisionCapsule> links;
  std::vector<Obstacle> obstacles;
  // Pairs of names (bodies, bases, obstacles) never checked.
  std::vector<std::pair<std::string, std::string>> ignore;
  // Why no default base radius fits (bases closer at home than twice the
  // margin), as a "file: key: what" message, or "": clearance cannot be
  // turned on (--obstacles) without collision.base_radius then.
  std::string base_radius_unfit;
};

}  // namespace ccma

#endif  // CCMA_COLLISION_GEOMETRY_H_
