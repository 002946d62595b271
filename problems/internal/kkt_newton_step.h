// One Newton step of the loaded equilibrium (problems/internal/loaded_newton.h)
// at an assembled point (problems/internal/loaded_kkt.h): the solve of
//   K [y; mu] = [force; -g]
// by the workspace's factorisation, refined against K without eps_A, and
// the tolerances the iterations that use it share.
// Units: m, rad, N, N*m.
#ifndef CCMA_PROBLEMS_INTERNAL_KKT_NEWTON_STEP_H_
#define CCMA_PROBLEMS_INTERNAL_KKT_NEWTON_STEP_H_

#include <Eigen/Core>

#include "problems/internal/kkt_factorization.h"
#include "problems/internal/loaded_kkt.h"

namespace ccma {

constexpr double kKktRowTolerance = 1e-13;  // a rigid row that holds [m or rad-like], as the dense path
// eps_H relative to the stiffest spring. It biases the step along a motion
// of curvature c by eps_H / c (squared after RemoveIdleBias), so it must lie
// far below the softest resisted motion, which geometry can put 1e-6 of the
// stiffest spring (a generated 3-agent CCMA: 2.8 N*m/rad under a 1e7 N/m
// spring; 1e-6 gave a linear rate of 0.6 there). Idle motions move by a
// rounding force over it: eps |F| L / (1e-12 k), 1e-4 of a deflection F / k.
constexpr double kKktIdleStiffness = 1e-12;
// eps_A against the rigid rows' O(1) entries, refined away.
constexpr double kKktRowRegularization = 1e-10;
constexpr double kKktMaxStep = 0.5;  // m or rad per Newton step

class KktNewtonStep {
 public:
  // The right-hand side [force; -g] of `system`, assembled with
  // eps_A = kKktRowRegularization.
  explicit KktNewtonStep(const LoadedKkt& system);

  // [y; mu] by `kkt` (which keeps its analysis from the previous steps):
  // factorises K by its LDL^T, or its LU when the LDL^T's refined solution
  // leaves more than 1e-12 of max(1, |rhs|, (|K| |z|)); false when both fail.
  bool Solve(KktFactorization* kkt, Eigen::VectorXd* z) const;
  // K^-1 rhs for another right-hand side, by the factorisation Solve made,
  // refined the same way; false when it does not reach that accuracy.
  bool SolveAgain(const KktFactorization& kkt, const Eigen::VectorXd& rhs, Eigen::VectorXd* z) const;

  // One step of refinement against eps_H = 0: z += K^-1 [eps_H y; 0].
  // eps_H biases a Newton step by eps_H / k (the iteration then gains only
  // that factor a step, 2e-5 on a 6-agent CCMA); one step squares it. Along
  // an idle motion (no spring, no rigid row) the step doubles instead, from
  // a rounding force over eps_H: harmless (1e-11 m), and a mechanism that
  // is not held is told by the step's length as before.
  void RemoveIdleBias(const KktFactorization& kkt, Eigen::VectorXd* z) const;

  const Eigen::VectorXd& rhs() const { return rhs_; }

  // max |force - A^T mu|: what the multipliers leave unbalanced.
  double Unbalanced(const Eigen::VectorXd& mu) const;

 private:
  bool SolveRefined(const KktFactorization& kkt, const Eigen::VectorXd& rhs, Eigen::VectorXd* z) const;
  double ComponentwiseScale(const Eigen::VectorXd& z) const;

  const LoadedKkt& system_;
  Eigen::VectorXd rhs_;
};

// A full step's LoadedKkt::Assemble at x (w weighs the rigid rows'
// curvature; zero when empty) or a chord step's AssembleResiduals (the
// reaction of mu_last), with the iterations' regularisations.
void AssembleStep(const Model& model, const ConstraintSet& set, bool chord, const LoadedPoint& x,
                  const Eigen::VectorXd& u, const ExternalWrench& wrench, const Eigen::VectorXd& w,
                  const Eigen::VectorXd& mu_last, LoadedKkt* system);

// [y; mu] at the point `system` was last evaluated at: a full step (after
// LoadedKkt::Assemble) factorises K there; a chord step (after
// AssembleResiduals with mu_last) solves with the last factorisation for
// the residuals [force - A^T mu_last; -g] and adds the multipliers' change
// to mu_last. The idle regulariser's bias removed. False when the solve fails.
bool SolveKktAt(const LoadedKkt& system, bool full, const Eigen::VectorXd& mu_last, KktFactorization* kkt,
                Eigen::VectorXd* z);

// max |force - A^T mu| at that point: a full step's own multipliers mu, or a
// chord step's last ones (the reaction AssembleResiduals took).
double UnbalancedAt(const LoadedKkt& system, bool chord, const Eigen::VectorXd& mu);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_KKT_NEWTON_STEP_H_
