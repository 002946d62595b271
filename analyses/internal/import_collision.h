// Collision geometry for an imported robot (`ccma import
// --collision_radius=R`, docs/import.md#collision-geometry): robot files
// describe collision shapes as meshes, which ccma's clearance does not use,
// so import can give every body capsules of radius R along the segments
// between its joint points (and the end-effector point on its body): the
// shortest tree joining them, a sphere for a body with one point. Pairs of
// bodies whose capsules are closer than the margin at home touch by design
// (two rods meeting at a closure through a connector body) and are written
// to `collision.ignore`.
#ifndef CCMA_ANALYSES_INTERNAL_IMPORT_COLLISION_H_
#define CCMA_ANALYSES_INTERNAL_IMPORT_COLLISION_H_

#include <string>

#include "ccma/model.h"

namespace ccma {
namespace internal {

struct ImportCollisionCounts {
  int capsules = 0;       // capsules written
  int ignored_pairs = 0;  // body pairs closer than the margin at home
};

// Adds the capsules of radius `radius` [m] (> 0) to every body of `home`
// that is not a mobile base (whose cylinder it has already), enables
// clearance and ignores the pairs closer than the margin at home. Throws
// ModelError naming `source` when the pairs to ignore pass the model
// format's bound (ccma/limits.h).
ImportCollisionCounts AddImportCollision(double radius, const std::string& source, Model* home);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_ANALYSES_INTERNAL_IMPORT_COLLISION_H_
