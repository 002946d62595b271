// Design parameters and their sensitivities (issue 12 item 3): geometry a
// user names (joint points, link lengths), how the model changes with it, and
// the design loop behind `ccma design` that moves the geometry until every
// target pose is reachable.
//
// A parameter p_k is one of
//  * a world coordinate [m] of a joint's home point (model_format.md: the
//    point both bodies of the joint share at home; a base attachment point is
//    the point of a joint whose `between` names a mobile base), or
//  * a link length L [m]: the distance from an anchor joint A to a joint B on
//    a body they share; B's home point moves along the line from A through
//    B's original point, P_B = P_A + L d (d the original unit direction).
// Either way the joint's world home point P_W is affine in p and the
// body-frame copies p_A = R_WA^T (P_W - p_WA), p_B = R_WB^T (P_W - p_WB) the
// constraints read are affine in P_W (Model keeps the bodies' home poses).
//
// Sensitivities at a forward solution s_hat(u, p), G(s_hat, u, p) = dE/ds = 0:
//   ds/dp = -(dG/ds)^-1 dG/dp,   dX_EE/dp = dX_EE/ds ds/dp   (u fixed).
// Every joint residual is affine in the joint's points (a point enters as
// R p + t), so C is affine in p, J_s = dC/ds is affine in p and
// G = J_s^T C is quadratic in p: the central difference of G over the
// perturbed models (p +- h e_k) is exact up to rounding, for any h, also when
// E > 0 (an unreached target) where dG/dp = J_s^T dC/dp + (dJ_s/dp)^T C.
// No new cost-function code is needed and nothing is approximated.
#ifndef CCMA_PROBLEMS_DESIGN_H_
#define CCMA_PROBLEMS_DESIGN_H_

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analyses/precision.h"
#include "ccma/end_effector.h"
#include "ccma/model.h"
#include "ccma/state.h"
#include "problems/control_problem.h"

namespace ccma {

class ConstraintSet;
class WorkEstimate;

enum class DesignParameterKind { kJointCoordinate, kLinkLength };

struct DesignParameter {
  DesignParameterKind kind = DesignParameterKind::kJointCoordinate;
  int joint = -1;         // the joint whose point moves
  int axis = 0;           // kJointCoordinate: 0 x, 1 y, 2 z (world)
  int anchor = -1;        // kLinkLength: joint A (does not move)
  Eigen::Vector3d direction_W = Eigen::Vector3d::UnitX();  // kLinkLength: unit A -> B at p0
  std::string label;      // "joint2.z", "length:joint1:joint2"
};

// The parameters and their values in the model they were named on.
struct DesignParameters {
  std::vector<DesignParameter> list;
  int size() const { return static_cast<int>(list.size()); }
};

// Adds the parameters of one `--vary` item, "JOINT.x", "JOINT.y", "JOINT.z"
// or "JOINT.point" (all three), JOINT a joint name (model.h). Returns false
// and sets `why` (naming the item) for an unknown joint or component, or a
// joint already varied by another item (a joint is varied once: `.point`
// names all three coordinates) or anchoring a length.
bool AddJointCoordinates(const Model& model, const std::string& item, DesignParameters* params, std::string* why);
// Adds one `--vary-length` item "A:B": the length from joint A to joint B,
// which must share a body, differ, and have distinct home points; B moves, A
// must not be varied itself.
bool AddLinkLength(const Model& model, const std::string& item, DesignParameters* params, std::string* why);
// The `vary` items then the `vary_length` items, in order (as `ccma design
// --vary --vary_length` and Python's design() name them). Returns false at
// the first bad item with `why` = "vary: ..." or "vary_length: ...".
bool AddDesignParameters(const Model& model, const std::vector<std::string>& vary,
                         const std::vector<std::string>& vary_length, DesignParameters* params, std::string* why);

// The most targets one design takes: each costs a control solve per trial.
constexpr std::size_t kMaxDesignTargets = 1000;

// The home world point of a joint [m] (from its body-frame copy p_A).
Eigen::Vector3d JointPointWorld(const Model& model, int joint);
// Current values of the parameters on `model` [m].
Eigen::VectorXd ParameterValues(const Model& model, const DesignParameters& params);
// A copy of `model` with the parameters set to p (size params.size()): the
// named joints' p_A, p_B recomputed from their new world points; everything
// else unchanged. The home state is generally no longer assembled (a forward
// solve assembles it).
Model ApplyParameters(const Model& model, const DesignParameters& params, const Eigen::VectorXd& p);

struct ParameterSensitivity {
  Eigen::MatrixXd dG_dp;  // n x P
  Eigen::MatrixXd ds_dp;  // n x P, state tangent per m
  Eigen::MatrixXd dX_dp;  // 6 x P: EE position [m/m], rotation increment [rad/m] (end_effector.h)
  double rcond = 0;       // pivot ratio of dG/ds (sensitivity.h)
  bool singular = true;   // dG/ds could not be factorised: the rest is unset
};

// dG/dp (n x P) at (s, u) on the model with parameters p, by the exact
// central difference described above (h = 1e-3 m).
Eigen::MatrixXd EnergyGradientParameterJacobian(const Model& model, const DesignParameters& params,
                                                const Eigen::VectorXd& p, const State& s, const Eigen::VectorXd& u);
// -(dG/ds)^-1 dG_dp at (s, u) on `constraints`; false if dG/ds is singular.
bool SolveStateParameterSensitivity(const ConstraintSet& constraints, const State& s, const Eigen::VectorXd& u,
                                    const Eigen::MatrixXd& dG_dp, Eigen::MatrixXd* ds_dp, double* rcond);
// All of ParameterSensitivity at a forward solution (s, u) of
// ApplyParameters(model, params, p). Returns !singular.
bool ComputeParameterSensitivity(const Model& model, const DesignParameters& params, const Eigen::VectorXd& p,
                                 const State& s, const Eigen::VectorXd& u, ParameterSensitivity* out);

// The text of the model file `text` (YAML or JSON, the one `original` was
// loaded from) with only the `point:` numbers of the joints the parameters
// move replaced by their values in `designed` (world home points, 12
// significant digits); everything else (comments, layout, other numbers)
// is kept byte for byte, a leading UTF-8 byte-order mark included. The
// numbers are patched where yaml-cpp marks them (after such a mark).
// The result is reloaded and checked against `designed`; throws
// std::runtime_error naming the joint when a point cannot be patched.
std::string PatchModelText(const std::string& text, const Model& original, const Model& designed,
                           const DesignParameters& params);

// ---- The design loop ----------------------------------------------------
// What is improved after reach and margin (design_objective.h).
enum class DesignObjective { kReach, kPayload, kPeakPush, kEndEffectorStd, kStiffness, kDeflection };

// An objective at one assembled target configuration.
struct ObjectiveAtTarget {
  bool defined = false;
  double value = 0;      // kg, N, m or m/N (DesignObjectiveUnit)
  std::string limiting;  // the actuator or base that sets it ("" for ee_std)
  std::string why;       // when !defined
};

struct DesignOptions {
  ControlOptions control;           // each target's control solve
  double target_tolerance = 1e-6;   // a target is reached within this [m or rad], in [1e-12, 1]
  double min_singular_value = 0.02; // required sigma_min of dX_c/du at every target, in [0, 100]
  double max_change = 0.5;          // |p_k - p_k0| bound [m], in (0, 100]
  double min_length = 0.02;         // lower bound on every varied length [m], in (0, 100]
  int max_iterations = 30;          // outer iterations per phase, in [1, 1000]
  DesignObjective objective = DesignObjective::kReach;
  BasePoseNoise noise;              // ee_std: the bases' pose noise, each sigma in [0, 1]
  // When not null (not owned): told of every outer iteration, the objective's
  // as a stage of their own (analyses/work_estimate.h); made with
  // MaxDesignIterations() units. It may throw WorkBoundError, which ends
  // the design.
  WorkEstimate* estimate = nullptr;
  bool IsValid(std::string* why) const;
};

// IsValid with the message naming max_iterations as `ccma design` and
// Python's design() do: design_iterations.
bool IsValidAsDesignCommand(const DesignOptions& options, std::string* why);

// The most outer iterations Design may take with `options`: max_iterations
// for reach and margin, as many again for an objective.
int MaxDesignIterations(const DesignOptions& options);

// One target on one design.
struct DesignTargetResult {
  bool reached = false;             // within target_tolerance and assembled
  double error = 0;                 // max |e| [m or rad]
  double min_singular_value = 0;    // of dX_c/du at the final controls
  bool within_limits = true;        // joint limits respected (violation <= 1e-9)
  Eigen::VectorXd controls;
};

struct DesignResult {
  bool converged = false;   // every target reached, sigma_min >= threshold, limits held
  int iterations = 0;
  Eigen::VectorXd p0, p;    // parameters before and after [m]
  std::vector<DesignTargetResult> initial, final;
  std::string message;      // why not converged ("" when converged)
  // With an objective: its worst value over the targets before and after
  // (phase 3 starts once every target is reached with margin), and why it
  // stopped improving.
  ObjectiveAtTarget objective_before, objective_after;
  int objective_iterations = 0;
  std::string objective_message;
};

// Solves every target on `model` (each from home, along a path; the model's
// home state need not be assembled): reachability and margin.
std::vector<DesignTargetResult> EvaluateTargets(const Model& model, const std::vector<PoseTarget>& targets,
                                                const DesignOptions& options);

// Moves p until every target is reached with margin: Levenberg-Marquardt on
// the stacked end-effector errors of all targets over (u_1..u_T, p), with
// de_t/du_t from the control sensitivities and de_t/dp from ds/dp, each
// trial re-solving every target on the new design (accepted when the summed
// squared error falls); then, if some target's sigma_min is below the
// threshold, steps on p raising the smallest sigma_min (its gradient in p by
// central differences of re-solved targets) while all stay reached; then,
// with an objective, steps on p along its gradient at the worst target
// (design_objective.h), each trial re-solving every target and accepted when
// all stay reached, the margin holds and the worst value improves.
// Throws std::invalid_argument for invalid options or no parameters/targets.
DesignResult Design(const Model& model, const DesignParameters& params, const std::vector<PoseTarget>& targets,
                    const DesignOptions& options);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_DESIGN_H_
