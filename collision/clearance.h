// Clearance of a model's shapes at a state (collision_model.h): the checked
// pairs that come close (a broad phase: sort and sweep of the bounding
// boxes along x, near-linear in the number of shapes), their distances
// (shapes.h), the smallest of all, and each pair's gradient over the state.
#ifndef CCMA_COLLISION_CLEARANCE_H_
#define CCMA_COLLISION_CLEARANCE_H_

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "ccma/state.h"
#include "collision/collision_model.h"
#include "collision/shapes.h"

namespace ccma {

struct PairClearance {
  int a = -1, b = -1;  // shape indices, a < b
  ShapeDistance distance;
};

// Appends to `pairs` every checked pair whose bounding boxes are at most
// `threshold` [m] apart on every axis (a superset of the pairs whose
// clearance is at most threshold), a < b, sorted. `order` is scratch.
void NearPairs(const CollisionModel& model, const std::vector<PlacedShape>& shapes, double threshold,
               std::vector<std::pair<int, int>>* pairs, std::vector<int>* order);

// The clearance of every checked pair that NearPairs() finds within
// `threshold` (so every pair with clearance <= threshold is among them).
std::vector<PairClearance> NearClearances(const CollisionModel& model, const std::vector<PlacedShape>& shapes,
                                          double threshold);

// The smallest clearance over all checked pairs at s.
struct ClearanceSummary {
  bool any = false;          // false: no pair is checked
  double min = 0;            // m (negative: overlap depth)
  std::string a, b;          // names of the two bodies, bases or obstacles
};
ClearanceSummary MinimumClearance(const CollisionModel& model, const State& s);

// d clearance / ds of one pair at s: the 1 x 6 rows (dphi, dp; state.h)
// of the bodies of shapes a and b (zero for an obstacle). The witness
// points move rigidly with their bodies; a base's cylinder moves with its
// body's x and y only.
void ClearanceGradient(const CollisionModel& model, const State& s, const PairClearance& pair,
                       Eigen::Matrix<double, 1, 6>* g_a, Eigen::Matrix<double, 1, 6>* g_b);

}  // namespace ccma

#endif  // CCMA_COLLISION_CLEARANCE_H_
