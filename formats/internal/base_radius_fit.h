// The default collision radius of the mobile bases that give none
// (model_format.md, "Collision geometry and obstacles"): 0.3 m where the
// bases stand far enough apart, and otherwise the largest radius that keeps
// every checked pair of bases a clear gap apart at home, so that a model
// whose bases stand close together (6 agents round one end-effector) does
// not start with its bases overlapping.
//
// Internal to the library.
#ifndef CCMA_FORMATS_INTERNAL_BASE_RADIUS_FIT_H_
#define CCMA_FORMATS_INTERNAL_BASE_RADIUS_FIT_H_

#include <string>
#include <utility>
#include <vector>

#include "ccma/model.h"

namespace ccma {
namespace internal {

struct BaseRadiusFit {
  double radius = 0;    // m: <= cap; <= 0 when no radius keeps the gap
  int a = -1, b = -1;   // the bases (indices into mobile_bases) that bound it, or -1 when cap does
  double distance = 0;  // m: their distance at home
};

// The largest radius r <= cap such that every two bases that are checked
// (not joined by a joint, not named together in `ignored`) stand at least
// `gap` apart at home, with radius given[k] for a base that gives its own
// (> 0) and r for the others (given[k] == 0). Pairs of bases that both give
// their own radius do not bound it. Sort and sweep along x: near-linear in
// the number of bases.
BaseRadiusFit FitDefaultBaseRadius(const Model& model, const std::vector<double>& given,
                                   const std::vector<std::pair<std::string, std::string>>& ignored,
                                   double gap, double cap);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_BASE_RADIUS_FIT_H_
