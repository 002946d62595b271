// The collision shapes of a model and which pairs of them are checked
// (model_format.md, "Collision geometry and obstacles"), built once from a
// Model and then constant, like the Model itself; PlaceShapes() puts them at
// a state into a caller's vector (no allocation once it has the size).
//
// Shapes, in this order: one vertical cylinder per mobile base (a legged
// base with a `footprint`: a box from the floor to its body), the link
// capsules, the obstacles. A pair is checked unless both are obstacles, both
// belong to one body, their bodies share a joint, or `collision.ignore`
// names them.
#ifndef CCMA_COLLISION_COLLISION_MODEL_H_
#define CCMA_COLLISION_COLLISION_MODEL_H_

#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"
#include "collision/shapes.h"

namespace ccma {

class CollisionModel {
 public:
  explicit CollisionModel(const Model& model);

  // Whether the model asks for clearance (collision.enabled).
  bool enabled() const { return enabled_; }
  double margin() const { return margin_; }
  int num_shapes() const { return static_cast<int>(owners_.size()); }

  // Every shape at state s (bases from their body's x, y; capsules with
  // their body's pose; obstacles fixed), bounding boxes included.
  void PlaceShapes(const State& s, std::vector<PlacedShape>* shapes) const;

  // Whether the pair (i, j) of shape indices is checked.
  bool Checked(int i, int j) const;
  // The body a shape moves with, or kWorld for an obstacle.
  int BodyOf(int shape) const { return bodies_[static_cast<size_t>(shape)]; }
  // Whether the shape is a base's cylinder (it moves with its body's x, y only).
  bool IsBase(int shape) const { return shape < num_bases_; }
  // The name of the body, base or obstacle a shape belongs to.
  const std::string& Name(int shape) const { return names_[static_cast<size_t>(owners_[static_cast<size_t>(shape)])]; }
  // The largest distance [m] of a point of any shape from its body's origin
  // at home (bounds how far a rotation moves a shape).
  double reach() const { return reach_; }

 private:
  bool enabled_ = false;
  double margin_ = 0;
  int num_bases_ = 0;
  double reach_ = 0;
  std::vector<PlacedShape> local_;  // capsules in their body frame, obstacles and base sizes as placed
  std::vector<int> bodies_;         // per shape: body or kWorld
  std::vector<int> owners_;         // per shape: body index, or num_bodies + obstacle index
  std::vector<std::string> names_;  // per owner
  std::unordered_set<std::uint64_t> skipped_;  // owner pairs never checked
  std::unordered_set<int> boxes_;  // base shapes that are boxes up to their body (BaseCollisionShape)
};

}  // namespace ccma

#endif  // CCMA_COLLISION_COLLISION_MODEL_H_
