// The smallest singular value of dX/du and its exact gradient (issue 12,
// singularity-aware control).
//
// A(u) = de/du = de/ds(s_hat(u)) S(s_hat(u), u), S = ds/du = -H^-1 B
// (H = dG/ds, B = dG/du over the effective controls), is the end-effector
// Jacobian over the controlled components (ne x k). Its smallest singular
// value sigma (the min(ne, k)-th, with unit singular vectors v (ne), w (k))
// falls to 0 where the mechanism loses an end-effector direction (a leg at
// full extension, links aligned). Where sigma is simple,
//   d sigma / du_l = v^T (dA/du_l) w = d/dt [v^T A(s_hat(u + t e_l), u + t e_l) w] at t = 0,
// a second-order sensitivity of the assembly. A(s, u) = -de/ds(s) H(s,u)^-1
// B(s,u) w is a smooth function of (s, u) everywhere (H is the exact Hessian
// of E, also off the solution manifold), so its derivative along the solution
// curve is taken as a central difference of these analytic Jacobians along
// the curve's tangent line (s (+) t S e_l, u + t e_l):
//   g_l = [v^T A(s (+) h S e_l, u + h e_l) w - v^T A(s (+) -h S e_l, u - h e_l) w] / (2h).
// The tangent line leaves the curve by t^2 s_ll / 2 on both sides, the same
// offset, which cancels in the difference: g_l = d sigma/du_l + O(h^2).
// Richardson extrapolation, (4 g_l(h/2) - g_l(h)) / 3, removes the h^2 term:
// error O(h^4 max |d5 (v^T A w)/dt5|) + ~1e-16 |A| / h (with h = 1e-4 the
// tests find agreement with central differences of re-solved forward
// problems to better than 1e-6 relative on four bundled models). No forward
// problem is re-solved: each g_l costs four factorisations of H and four
// solves. Where sigma is repeated (`gap` ~ 0; e.g. 4dof_reduced, whose
// three identical legs make its two smallest singular values equal
// everywhere) sigma is not differentiable and this is the derivative of
// v^T A w for one singular pair only: the control loop then keeps a
// null-space step only if it decreased the objective.
#ifndef CCMA_PROBLEMS_INTERNAL_SINGULARITY_H_
#define CCMA_PROBLEMS_INTERNAL_SINGULARITY_H_

#include <vector>

#include <Eigen/Core>

#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/state.h"
#include "problems/internal/end_effector_error.h"
#include "problems/internal/sensitivity.h"

namespace ccma {

struct SmallestSingularValueResult {
  double sigma = 0;          // m or rad per control unit; 0 if it could not be formed
  bool valid = false;        // dG/ds factorised (sigma and gradient meaningful)
  double gap = 0;            // sigma_{min(ne,k)-1} - sigma: the gradient needs it > 0
  Eigen::VectorXd gradient;  // d sigma / du over the effective controls (k), if asked
};

// sigma and, if `with_gradient`, d sigma/du at a solved state (s, u) (G = 0:
// the formula above is the derivative along the solution curve only there).
// `solver` (not null) and `workspace` are scratch (reused across calls). `h` is the
// tangent-line step [m or rad], in [1e-8, 1e-2].
SmallestSingularValueResult SmallestSingularValueOfdXdu(const ConstraintSet& constraints, const EndEffectorError& error,
                                                        const PoseTarget& target, const State& s,
                                                        const Eigen::VectorXd& u, const std::vector<int>& effective,
                                                        bool with_gradient, double h, HessianSolver* solver,
                                                        EnergyDerivatives* workspace);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_SINGULARITY_H_
