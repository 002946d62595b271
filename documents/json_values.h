// The values of the commands' documents (docs/cli.md): vectors, poses, bodies, joints,
// clearance, compliance and the loaded equilibrium as JSON, shared by every
// document (documents/*_document.h), the CLI's and Python's alike.
#ifndef CCMA_DOCUMENTS_JSON_VALUES_H_
#define CCMA_DOCUMENTS_JSON_VALUES_H_

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ccma/ccma.h"

namespace ccma::documents {

nlohmann::json ToJson(const Eigen::VectorXd& v);
// {"position": [..], "rotation": [[..],[..],[..]], "rpy": [..]}
nlohmann::json ToJson(const EndEffectorPose& pose);
// [{"name", "position", "rpy", "quaternion"}] for every body: the body
// frame's world position [m], R_WB as rpy [rad] and as the unit quaternion
// [w, x, y, z] (exact, for `simulate --from`).
nlohmann::json BodiesToJson(const Model& model, const State& s);

// [{"name", "type", "q", "actuated", "limits"?}] for every revolute and
// prismatic joint in file order (q in rad or m; limits only when given).
nlohmann::json JointsToJson(const Model& model, const State& s);
// The names of the joints outside their limits (tolerance 1e-9).
nlohmann::json LimitsViolatedToJson(const Model& model, const State& s);

// {"min": d [m], "pair": [a, b], "margin": m [m], "below_margin": bool}: the
// smallest clearance at s (collision/clearance.h); null when the model has
// no collision geometry or no pair of shapes is checked.
nlohmann::json ClearanceToJson(const Model& model, const State& s);
// Adds ClearanceToJson as out["clearance"] when not null, and when it is
// below the margin a warning to `warnings` (null: none kept): "clearance 0.01
// m between 'a' and 'b' is below the margin 0.05 m".
void AddClearance(const Model& model, const State& s, nlohmann::json* out, std::vector<std::string>* warnings);

// The compliance keys of `ccma statics` (cli.md, "Compliance in `ccma
// statics`") into `out` when the report is a compliant mechanism's:
// compliant_reactions, deflection, ee_compliance, ee_stiffness (null with
// ee_stiffness_note when singular), most_compliant. Nothing otherwise.
void AddComplianceJson(const StaticsReport& report, nlohmann::json* out);

// The loaded equilibrium of `ccma simulate --loaded` and `ccma control
// --compensate` (cli.md, "Compliance in ..."): end_effector, bodies and
// joints of the deflected configuration, deflection {end_effector [m, rad],
// max_body_m, held} against the rigid assembly, and loaded {converged,
// iterations, unbalanced_load [N or N*m], yields [per control, m or rad]}.
void AddLoadedJson(const Model& model, const LoadedEquilibrium& loaded, nlohmann::json* out);

// The keys `ccma control --compensate` adds or replaces: the loaded
// configuration (AddLoadedJson), converged and error of the loaded
// end-effector, limits_violated there, and compensation {converged, rounds,
// miss, aim, rigid_end_effector} (`rigid`: the rigid assembly's end-effector).
void AddCompensationJson(const Model& model, const EndEffectorPose& rigid, const CompensatedResult& c,
                         nlohmann::json* out);

// The "secondary" object of `ccma control` and `ccma trajectory`: the null
// space steps, the secondary objective's settings and its value Phi (left
// out where it is not finite: dG/ds could not be factorised).
nlohmann::json SecondaryJson(const ControlOptions::Secondary& secondary, int null_space_steps, double objective);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_JSON_VALUES_H_
