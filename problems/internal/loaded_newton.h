// The loaded equilibrium's Newton iteration on its sparse KKT system
// (problems/loaded_equilibrium.h): the fast path, tried first.
//
// At a point x = (s, delta) (the rigid rows need not hold there), with the
// rigid rows' residual g and Jacobian A, the springs' stretch e, and
// force = Q(s) - S^T k e, one step solves
//   [H + eps_H I   A^T ] [y ]   [force]
//   [A          -eps_A I] [mu] = [-g   ]
// with H = S^T diag(k) S + sum_i w_i Hess(C_i) - dQ/ds (the springs, the
// preload's geometric stiffness with the previous step's multipliers w, and
// the loads turning with the bodies), assembled block by block into a
// pattern fixed per model (problems/internal/loaded_kkt.h), by one sparse LDL^T (KktFactorization:
// its analysis kept in the LoadedWorkspace, an LU where the LDL^T fails),
// then refines the solution against eps_A = 0. eps_H gives the idle
// motions (no spring, no rigid row: a leg spinning about its axis) a
// stiffness far above any rounding force, so they stay put; eps_A keeps
// redundant rigid rows (a wheeled base's planar and motor rows both lock its
// tilt) factorisable, and the refinement removes its bias on g. Neither
// moves the fixed point: y = 0 exactly where the rigid rows hold and the
// loads and springs balance along every motion they allow.
// Converged when |g| is below its tolerance and |force - A^T mu| or the
// Newton step is below its own (problems/internal/loaded_tolerances.h); the
// dense path (load steps, minimum-norm restoration) takes over otherwise.
// Units: m, rad, N, N*m.
#ifndef CCMA_PROBLEMS_INTERNAL_LOADED_NEWTON_H_
#define CCMA_PROBLEMS_INTERNAL_LOADED_NEWTON_H_

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "ccma/loads.h"
#include "ccma/model.h"
#include "ccma/state.h"
#include "problems/internal/kkt_factorization.h"
#include "problems/internal/loaded_kkt.h"
#include "problems/internal/loaded_tolerances.h"
#include "problems/loaded_equilibrium.h"

namespace ccma {

// The controls the motors' rows see: as commanded plus their yields.
Eigen::VectorXd CommandedControls(const Eigen::VectorXd& u, const std::vector<int>& compliant,
                                  const Eigen::VectorXd& delta);

// The rigid rows' residual g (in the order of CompliantEquilibrium's A) and
// the springs' stretch e (in the order of its S: the controls' yields, then
// each compliant joint's spring deviations), at x with effective controls
// u_eff.
void LoadedResiduals(const Model& model, const ConstraintSet& set, const LoadedPoint& x, const Eigen::VectorXd& u_eff,
                     Eigen::VectorXd* g, Eigen::VectorXd* e);

// The public LoadedOptions::workspace (problems/loaded_equilibrium.h).
class LoadedWorkspace {
 public:
  // The KKT matrix's layout and pattern for the model last solved (built
  // again for another), and its factorisation.
  std::unique_ptr<LoadedKkt> system;
  KktFactorization kkt;

  // `system` for `model` with `set` (built when it is another's; the
  // multipliers then dropped).
  LoadedKkt& SystemFor(const Model& model, const ConstraintSet& set);
  // The last equilibrium's rigid-row multipliers, in the constraint set's
  // row order (w) and in CompliantEquilibrium's A order (mu): the next
  // solve's first Newton matrix weighs the rows' curvature by them.
  Eigen::VectorXd w, mu;

  // Keeps mu (A order) and w = system->SetOrder(mu): an equilibrium's.
  void KeepMultipliers(const Eigen::VectorXd& equilibrium_mu) {
    mu = equilibrium_mu;
    w = system->SetOrder(mu);
  }
};

struct LoadedNewtonResult {
  bool converged = false;
  int iterations = 0;     // KKT factorisations
  double unbalanced = 0;  // max |force - A^T mu| at the last point [N or N*m]
};

// out's state, yields, deflection and largest body displacement: x against
// the rigid assembly `rigid` (compliant: the model's compliant controls).
void DescribeLoadedPoint(const Model& model, const State& rigid, const LoadedPoint& x, const std::vector<int>& compliant,
                         LoadedEquilibrium* out);

// Newton's method at the full loads from *x; on convergence *x is the
// equilibrium (rigid rows within 1e-13), else *x is unchanged.
// `tolerances` from LoadedTolerancesFor;
// `workspace` keeps the factorisation's analysis between calls.
LoadedNewtonResult SolveLoadedNewton(const Model& model, const ConstraintSet& set, const Eigen::VectorXd& u,
                                     const ExternalWrench& wrench, const LoadedTolerances& tolerances, int max_iterations,
                                     LoadedWorkspace* workspace, LoadedPoint* x);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_LOADED_NEWTON_H_
