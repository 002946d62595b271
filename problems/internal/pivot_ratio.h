// The pivot ratio of dG/ds and its exact gradient along the solution curve
// (issue 12, singularity-aware control: the second conditioning figure).
//
// rho(s, u) = min_i D_ii / max_i |D_ii| of the LDL^T factorisation of
// H = dG/ds = d2E/ds2 in the solver's fixed (AMD) order
// (HessianSolver::pivot_ratio, reported as `rcond`). It falls toward 0 where
// the assembly itself degenerates (a loop that can flex without changing E,
// two joints aligned so that a body's pose is determined only to second
// order), where ds/du and every gradient built from it blow up; it can stay
// well away from 0 at the edge of the workspace, which sigma_min(dX/du)
// (singularity.h) watches instead.
//
// rho is a smooth function of H wherever the extreme pivots are simple (the
// pivots themselves are smooth in H for a fixed order), so along the solution
// curve s_hat(u)
//   d rho / du_l = d/dt rho(H(s_hat(u + t e_l), u + t e_l)) at t = 0,
// taken as in singularity.h: a central difference along the curve's tangent
// line (s (+) t S e_l, u + t e_l), S = ds/du, whose second-order departure
// from the curve is symmetric and cancels, then Richardson extrapolation
// (h, h/2) to remove the h^2 term. No forward problem is re-solved; each
// component costs four factorisations of H. Where the smallest (or largest)
// pivot changes index, rho has a kink and this is the one-sided slope of the
// pivot chosen at u.
#ifndef CCMA_PROBLEMS_INTERNAL_PIVOT_RATIO_H_
#define CCMA_PROBLEMS_INTERNAL_PIVOT_RATIO_H_

#include <vector>

#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "ccma/state.h"
#include "problems/internal/sensitivity.h"

namespace ccma {

struct PivotRatioResult {
  double rho = 0;            // min pivot / max |pivot| of dG/ds [1]; negative: indefinite
  bool valid = false;        // dG/ds factorised at (s, u) (and on the tangent line, if asked)
  Eigen::VectorXd gradient;  // d rho / du over the effective controls (k) [1 / (m or rad)], if asked
  // Every pivot's ratio D_ii / max |D| (n, in the solver's order; rho is the
  // smallest) and, if asked, their derivatives (n x k): a barrier on rho
  // alone sees only the pivot that is smallest now, while another may be
  // falling faster (ControlOptions::Secondary puts one term on each ratio
  // below its threshold).
  Eigen::VectorXd ratios;
  Eigen::MatrixXd ratio_gradients;
};

// rho and, if `with_gradient`, d rho/du at a solved state (s, u) (G = 0: the
// difference above follows the solution curve only there). `solver` (not
// null) and `workspace` are scratch. `h` is the tangent-line step [m or rad],
// in [1e-8, 1e-2].
PivotRatioResult PivotRatioOfdGds(const ConstraintSet& constraints, const State& s, const Eigen::VectorXd& u,
                                  const std::vector<int>& effective, bool with_gradient, double h,
                                  HessianSolver* solver, EnergyDerivatives* workspace);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_PIVOT_RATIO_H_
