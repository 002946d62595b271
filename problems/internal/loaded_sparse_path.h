// The loaded equilibrium's sparse path (problems/loaded_equilibrium.h):
// Newton's method on the sparse KKT system (problems/internal/
// loaded_newton.h) at the whole load, from the warm start when given and
// then from the rigid assembly; where both fail, in load steps from the
// rigid assembly, each started from the last equilibrium, whose multipliers
// weigh the preload's curvature in its first Newton matrix. A quarter of
// the loads first; a step that fails is quartered, one that succeeds
// doubled, down to kMinLoadStep of the loads.
//
// Load steps carry a soft mechanism whose first, linear Newton step
// overshoots: a motion its soft springs allow stretches its stiff ones to
// second order, which limits how far one Newton step reaches when the
// springs span many orders of magnitude (the chord steps of loaded_newton.h
// correct most of it).
// Units: m, rad, N, N*m.
#ifndef CCMA_PROBLEMS_INTERNAL_LOADED_SPARSE_PATH_H_
#define CCMA_PROBLEMS_INTERNAL_LOADED_SPARSE_PATH_H_

#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "ccma/loads.h"
#include "ccma/model.h"
#include "ccma/state.h"
#include "problems/internal/loaded_kkt.h"
#include "problems/loaded_equilibrium.h"

namespace ccma {

constexpr double kMinLoadStep = 1e-4;  // the smallest fraction of the loads a step may add

struct SparsePathResult {
  bool converged = false;
  double load_fraction = 0;  // of the loads, at x
  // Not converged: the load steps stalled (a step of kMinLoadStep failed:
  // past a limit load) rather than running out of iterations.
  bool stalled = false;
  int iterations = 0;        // KKT factorisations, all attempts
  double unbalanced = 0;     // at x's last Newton step [N or N*m]
  LoadedPoint x;             // the equilibrium at load_fraction (the rigid assembly at 0)
};

// At most options.max_iterations factorisations in all; `workspace` as
// LoadedOptions::workspace (not null).
SparsePathResult SolveLoadedSparsePath(const Model& model, const ConstraintSet& set, const State& rigid,
                                       const Eigen::VectorXd& u, const ExternalWrench& wrench,
                                       const LoadedOptions& options, LoadedWorkspace* workspace);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_LOADED_SPARSE_PATH_H_
