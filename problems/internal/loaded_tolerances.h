// When the loaded equilibrium's Newton iterations (problems/internal/
// loaded_newton.h, the dense path in problems/loaded_equilibrium.cc and
// problems/internal/compensated_newton.h) have converged.
//
// A point is an equilibrium when the rigid rows hold (kKktRowTolerance) and
// either the unbalanced generalized force is below `force` [N or N*m], or
// the Newton step taken there is below `step` [m or rad]. The second test is
// needed because the force test alone cannot always be met: a spring of
// stiffness k stretched at a position of size L carries a rounding error of
// about eps k L in its force (1e-9 N for k = 1e7 N/m, L = 0.6 m), above the
// force tolerance of a small load (2e-10 N at 1 N). The Newton step there is
// the distance to the exact equilibrium [m or rad]; once it is within a
// rounding's reach of the model's size, no further step can improve it.
// Units: m, rad, N, N*m.
#ifndef CCMA_PROBLEMS_INTERNAL_LOADED_TOLERANCES_H_
#define CCMA_PROBLEMS_INTERNAL_LOADED_TOLERANCES_H_

#include <Eigen/Core>

#include "ccma/loads.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// A Newton step below this per metre of the model's size (1 + the farthest
// body origin from the world's, at the rigid assembly) is converged: about
// 500 roundings of that size.
constexpr double kLoadedStepTolerance = 1e-13;

struct LoadedTolerances {
  double force = 0;  // [N or N*m]
  double step = 0;   // [m or rad]

  // Whether a point whose rigid rows hold is converged with `unbalanced`
  // left and a Newton step of max-norm `step_size` there.
  bool Converged(double unbalanced, double step_size) const { return unbalanced <= force || step_size <= step; }
};

// force = force_tolerance (1 + the largest generalized load at `rigid`);
// step = kLoadedStepTolerance (1 + the largest |p_WB| at `rigid`).
LoadedTolerances LoadedTolerancesFor(const Model& model, const State& rigid, const ExternalWrench& wrench,
                                     double force_tolerance);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_LOADED_TOLERANCES_H_
