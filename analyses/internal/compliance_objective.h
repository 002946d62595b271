// The compliance design objectives (analyses/design_objective.h, `ccma
// design --objective=stiffness|deflection`) and their adjoints.
//
// The linear compliance at (s, u) (analyses/compliance.h,
// problems/internal/compliant_equilibrium.h): y = P f minimises
// 1/2 y^T H y - f^T y on A y = 0 (H = S^T diag(k) S, f = [Q; 0]), the
// end-effector's motion is G y, and C = G P G^T.
//   stiffness  lambda = nu^T C nu, the largest eigenvalue of C's
//              translational block with its unit eigenvector nu (padded to 6);
//   deflection J = |E G y|, E the translational rows.
// Each is the value at its optimum of a Lagrangian whose derivative in
// (s, u, p), at FIXED primal and adjoint vectors, is the objective's
// (the envelope theorem; Hellmann-Feynman for the eigenvalue):
//   stiffness   L = 2 nu^T G w - w^T H w - 2 mu^T A w,
//               w = P G^T nu, A^T mu = G^T nu - H w;
//   deflection  L = e^T G y - z^T (H y + A^T lambda - f) - zeta^T A y,
//               e = E^T E G y / J, A^T lambda = f - H y,
//               z = P G^T e, A^T zeta = G^T e - H z.
// The multipliers exist exactly: the right-hand sides are orthogonal to the
// idle motions (H and, the end-effector being held, G vanish there). So the
// gradient needs A, S, k, G and Q at nearby states only, no factorisation
// (CompliantEquilibrium with factorize = false).
// Units: m/N (stiffness), m (deflection).
#ifndef CCMA_ANALYSES_INTERNAL_COMPLIANCE_OBJECTIVE_H_
#define CCMA_ANALYSES_INTERNAL_COMPLIANCE_OBJECTIVE_H_

#include <string>

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// The fixed vectors of one objective's Lagrangian at a target.
struct ComplianceAdjoint {
  bool stiffness = true;    // else deflection
  Eigen::Matrix<double, 6, 1> weight = Eigen::Matrix<double, 6, 1>::Zero();  // nu, or e
  Eigen::VectorXd primal;   // w, or y
  Eigen::VectorXd primal_multipliers;   // mu, or lambda
  Eigen::VectorXd adjoint;  // -, or z
  Eigen::VectorXd adjoint_multipliers;  // -, or zeta
};

struct ComplianceValue {
  bool defined = false;
  double value = 0;
  std::string why;  // when !defined
};

// The objective at (s, u) and, when `adjoint` is given, its Lagrangian's
// fixed vectors there. Not defined for a rigid model or an end-effector
// that is not held. Throws std::invalid_argument like CompliantEquilibrium.
ComplianceValue ComplianceObjectiveAt(bool stiffness, const Model& model, const State& s, const Eigen::VectorXd& u,
                                      ComplianceAdjoint* adjoint = nullptr);

// The Lagrangian at (s, u) on `model` with the vectors held fixed.
double ComplianceLagrangian(const ComplianceAdjoint& adjoint, const Model& model, const State& s,
                            const Eigen::VectorXd& u);

}  // namespace ccma

#endif  // CCMA_ANALYSES_INTERNAL_COMPLIANCE_OBJECTIVE_H_
