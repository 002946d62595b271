// The document of `ccma control` (docs/cli.md) and of Python's move_to()
// results: the control result, where it left the mechanism, the compensation
// of a loaded end-effector, and whether the controls are reproduced from home.
#ifndef CCMA_DOCUMENTS_CONTROL_DOCUMENT_H_
#define CCMA_DOCUMENTS_CONTROL_DOCUMENT_H_

#include <optional>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "ccma/ccma.h"
#include "documents/document.h"

namespace ccma::documents {

// ControlResult plus where it left the mechanism and what the document
// prints besides (the method, the secondary objective's settings).
struct ControlSolution : ControlResult {
  Eigen::Matrix<double, 6, 1> target;  // x y z [m], roll pitch yaw [rad]
  Eigen::VectorXd controls;
  EndEffectorPose end_effector;  // the loaded one with a compensation
  // The model controlled (it outlives the solution: the CLI's, or the
  // problem a Python result keeps alive).
  const Model* model = nullptr;
  State state;                   // the rigid assembly at `controls`
  std::string method;            // "lm" or "bfgs"
  ControlOptions::Secondary secondary;
  // A compensated move (`control --compensate`, move_to(compensate=True)):
  // how the loaded end-effector was put on the target.
  std::optional<CompensatedResult> compensation;
  EndEffectorPose rigid_end_effector;  // the rigid assembly's end-effector
  // The "from_home" check (FromHome), made when first asked for: an assembly
  // from home, as long as a simulate.
  mutable std::optional<nlohmann::json> from_home;
  mutable std::string from_home_warning;
};

// The solution `control` holds after a move to `target` that returned
// `result`, or (with `compensation`) after MoveToCompensated: its result,
// converged and error are then the loaded end-effector's, and its warning
// is added to the result's ("--compensate: ...").
ControlSolution MakeControlSolution(const ControlProblem& control, const ControlResult& result,
                                    const PoseTarget& target, std::optional<CompensatedResult> compensation);

// The document's "from_home" {reproducible, end_effector_distance_m,
// end_effector_rotation_rad, max_state_difference, idle_bodies}
// (analyses/configuration_difference.h CheckFromHome), computed once.
const nlohmann::json& FromHome(const ControlSolution& s);
// The document's "warning": the result's, then the from-home check's.
std::string ControlWarning(const ControlSolution& s);
// The document's "conditioning".
nlohmann::json ConditioningJson(const ControlResult& r);

// Document::warnings: the clearance's when below the margin, then the warning.
Document ControlDocument(const ControlSolution& s);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_CONTROL_DOCUMENT_H_
