// Payload capacity (issue 27): the largest payload mass the mechanism can
// hold at one configuration with every effort within its limits
// (`effort_limits` of actuated joints, `push_limit` of bases;
// model_format.md, "Masses and loads").
//
// Efforts are linear in the loads: e(m) = e_own + m e_kg, e_own from the
// bodies' own masses (payload removed), e_kg per kilogram of payload (at the
// payload's `com`, else at the end-effector point). Each limit bounds m:
//   joint:  lower <= e_own_j + m e_kg_j <= upper          (one linear bound)
//   base:   |e_own_xy + m e_kg_xy| <= push_limit           (a quadratic's root)
// and the capacity is the smallest such bound. A statically indeterminate
// mechanism's efforts are those of the minimum-norm reactions (statics.h). Its derivative is linear in
// the efforts' derivatives: d m = w_own . d e_own + w_kg . d e_kg, with the
// weights below (the implicit function of the limiting bound), which the
// design objective (design_objective.h) turns into a gradient through the
// adjoint of the statics solve. Units: kg, N, N*m.
#ifndef CCMA_ANALYSES_PAYLOAD_H_
#define CCMA_ANALYSES_PAYLOAD_H_

#include <string>

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

struct PayloadCapacity {
  bool defined = false;    // some limit is given and the loads are balanced
  bool determinate = true; // the limiting efforts are unique (else: of the minimum-norm reactions, as statics reports)
  double mass = 0;         // kg; negative when the mechanism's own weight already exceeds a limit
                           // (the design objective follows it below 0; reports use ReportedMass)
  bool unbounded = false;  // no limited effort grows with the payload (mass is then 0 and meaningless)
  std::string limiting;    // the actuator (joint or base) whose limit sets `mass`
  Eigen::VectorXd weight_own, weight_kg;  // num_controls each (see above)
  std::string why;         // when !defined
  // The first limit the mechanism breaks with no payload at all ("" when none):
  // its own weight (and the wrench) already exceed it, so no payload is safe.
  std::string broken_unloaded;
  std::string note;        // a sentence naming that limit and by how much, for reports
};

// What a report prints as the capacity [kg]: `mass`, or 0 when the unloaded
// mechanism already breaks a limit (never negative).
double ReportedMass(const PayloadCapacity& capacity);

// Whether a report prints the capacity: defined and bounded, or 0 because
// the unloaded mechanism already breaks a limit.
bool Reportable(const PayloadCapacity& capacity);

// The model with its payload removed, and with only a 1 kg payload (every
// other mass zero) at the payload's com or the end-effector point.
Model WithoutPayload(const Model& model);
Model PayloadPerKilogram(const Model& model);

// At an assembled (s, u). Throws std::invalid_argument like ComputeStatics
// for a model too large for the dense solve.
PayloadCapacity ComputePayloadCapacity(const Model& model, const State& s, const Eigen::VectorXd& u);

}  // namespace ccma

#endif  // CCMA_ANALYSES_PAYLOAD_H_
