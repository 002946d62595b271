// What `ccma design --objective=...` improves once every target is reached
// with margin (design.h; issue 27 item 5, the paper's future work):
//   payload   the largest payload within the effort and push limits
//             (payload.h), at the worst target [kg], raised;
//   peak_push the largest horizontal push |e_xy| of any base at any target
//             (a path's waypoints) [N], lowered;
//   ee_std    the largest end-effector position standard deviation
//             sqrt(trace Sigma_p) from the bases' pose noise (precision.h)
//             at any target [m], lowered;
//   stiffness the largest eigenvalue of the translational 3 x 3 block of
//             the end-effector's compliance (analyses/compliance.h,
//             `ccma statics`' most_compliant) at any target [m/N], lowered:
//             the softest direction made stiffer (a compliant model only);
//   deflection the largest end-effector displacement |deflection[0:3]|
//             under gravity on the masses and payload, controls held (the
//             linear deflection of `ccma statics`) at any target [m],
//             lowered (a compliant model only).
//
// Gradient in the design p at one target. The target's controls follow the
// design so that its controlled end-effector components stay put:
//   du/dp = -(de/du)^+ de/dp,   ds/dp|total = ds/dp + ds/du du/dp,
// (de/du, de/dp from the implicit sensitivities; the minimum-norm du where
// the controls are redundant). Along that tangent, per parameter k:
//  * payload, peak_push: the value is a weighted effort sum w . e whose
//    derivative is that of the adjoint Lagrangian
//    L = -w^T J_u^T lambda + mu^T (J_s^T lambda + Q) - zeta^T J_s eta at
//    fixed adjoints (problems/internal/equilibrium.h; zeta = 0 unless the
//    mechanism is statically indeterminate, when the minimum-norm efforts
//    statics reports are the ones used), no derivative of the least-squares
//    solve;
//  * stiffness, deflection: the adjoint Lagrangian of the compliant
//    system at fixed primal and adjoint vectors
//    (analyses/internal/compliance_objective.h): no factorisation along the
//    tangent;
//  * ee_std: sqrt(trace Sigma_p) itself, a function of (s, u, p).
// The remaining derivative, of the analytic Jacobians along the tangent
// (second-order terms), is a central difference along it (step 1e-5
// relative), error O(1e-10). tests/design_objective_test.cc checks the
// gradient against objectives re-solved on perturbed designs.
#ifndef CCMA_ANALYSES_DESIGN_OBJECTIVE_H_
#define CCMA_ANALYSES_DESIGN_OBJECTIVE_H_

#include <string>

#include <Eigen/Core>

#include "analyses/design.h"
#include "analyses/precision.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// "reach", "payload", "peak_push", "ee_std", "stiffness", "deflection";
// false for anything else.
bool ParseDesignObjective(const std::string& name, DesignObjective* out);
const char* DesignObjectiveName(DesignObjective objective);
const char* DesignObjectiveUnit(DesignObjective objective);  // "", "kg", "N", "m", "m/N"
inline bool IsMaximised(DesignObjective objective) { return objective == DesignObjective::kPayload; }
// Whether the objective is a compliance (only a model with stiffness keys has one).
inline bool NeedsSprings(DesignObjective objective) {
  return objective == DesignObjective::kStiffness || objective == DesignObjective::kDeflection;
}

ObjectiveAtTarget EvaluateObjective(DesignObjective objective, const Model& model, const State& s,
                                    const Eigen::VectorXd& u, const BasePoseNoise& noise);

// d value / dp (params.size()) at a target solved at (s, u) on
// ApplyParameters(model, params, p) (see above). False, with `why`, when the
// value is not defined there or dG/ds is singular.
bool ObjectiveGradient(DesignObjective objective, const Model& model, const DesignParameters& params,
                       const Eigen::VectorXd& p, const State& s, const Eigen::VectorXd& u,
                       const BasePoseNoise& noise, Eigen::VectorXd* gradient, std::string* why);

}  // namespace ccma

#endif  // CCMA_ANALYSES_DESIGN_OBJECTIVE_H_
