// Kinematic control (paper Section III-B): find controls u whose assembly
// s_hat(u) puts the end-effector at a target,
//   min_u O(u) = 1/2 |e(s_hat(u))|^2 + lambda E(s_hat(u), u),   0 < lambda < 1,
// with e the end-effector error over the controlled components and only the
// effective controls free (a reduced base's heading is no control).
//
// Gradients come from implicit-function sensitivities:
// ds/du = -(dG/ds)^-1 dG/du, dE_r/du = dE/du. Two outer loops:
//  * Levenberg-Marquardt on r(u) = [e; sqrt(lambda) C], Jacobian
//    [de/ds ds/du; sqrt(lambda) (J_s ds/du + J_u)] (the default: fewest
//    iterations and fastest, see the control benchmark);
//  * BFGS as in the paper (ceres::GradientProblemSolver), gradient
//    dO/du by one adjoint solve.
// Redundancy: among equivalent control changes LM's damped least-squares step
// is the one of least norm, so the bases move as little as possible from where
// they are; BFGS starts from the identity metric and so also moves along the
// gradient's row space only. Optionally (ControlOptions::Secondary, LM only) a
// secondary objective -- a barrier on the smallest singular value of dX/du,
// base spread, base travel -- is then minimised in the null space of the
// end-effector task, leaving the end-effector error unchanged.
// Branches: every LM trial solve starts from the first-order prediction
// s + ds/du du; a trial whose solution lands far from it (another assembly
// branch) is rejected like a trial that does not decrease O.
//
// Like ForwardProblem, a ControlProblem keeps a reference to the Model (which
// must outlive it) and owns only its workspace.
#ifndef CCMA_PROBLEMS_CONTROL_PROBLEM_H_
#define CCMA_PROBLEMS_CONTROL_PROBLEM_H_

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "ccma/end_effector.h"
#include "ccma/model.h"
#include "problems/forward_problem.h"

namespace ccma {

struct ControlLinearization;  // problems/internal/control_linearization.h
struct PathTally;             // problems/internal/path_tally.h
class Sensitivity;            // problems/internal/sensitivity.h

enum class ControlMethod { kLevenbergMarquardt, kBfgs };
// kFiniteDifference: central differences of re-solved forward problems,
// 2k solves per gradient (the baseline the paper avoids).
enum class GradientMethod { kImplicit, kFiniteDifference };

struct ControlOptions {
  ControlMethod method = ControlMethod::kLevenbergMarquardt;
  GradientMethod gradient = GradientMethod::kImplicit;
  double lambda = 0.5;              // weight of the residual energy, 0 < lambda < 1
  double max_step_m = 0.010;        // path: end-effector translation per step [m], in [1e-6, 1000]
  double max_step_rad = 0.005;      // path: end-effector rotation per step [rad], in [1e-6, 10]
  int max_iterations = 100;         // outer iterations per step, in [1, 100000]
  // A step has reached its target when every controlled component is within
  // this [m or rad] and the mechanism is assembled. The loops iterate to a
  // tenth of it (and E <= 1e-24) when they can. In [1e-14, 1].
  double target_tolerance = 1e-10;
  double finite_difference_step = 1e-6;  // [m or rad], kFiniteDifference only
  ForwardOptions forward;
  // Singularity-aware control and redundancy resolution (issue 12; all
  // weights 0 = off, the default). A secondary objective
  //   Phi(u) = 1/2 |r2(u)|^2,  r2 = [sqrt(w_sigma) (sigma_0 / sigma - 1) if sigma < sigma_0;
  //                                  sqrt(w_rho) (rho_0 / rho_i - 1) for every pivot ratio rho_i < rho_0;
  //                                  sqrt(w_spread) (c - d_ij) for every base pair closer than c;
  //                                  sqrt(w_travel) (u_eff - u_eff_start)]
  // (sigma: smallest singular value of dX_c/du, see
  // problems/internal/singularity.h; rho_i: pivot i of dG/ds's LDL^T over
  // the largest pivot, the smallest of them is the results' `rcond`, see
  // problems/internal/pivot_ratio.h; d_ij: horizontal distance between base
  // origins i and j [m]; u_start: the controls when MoveTo() began) is
  // minimised in the null space of the end-effector task: once a step has
  // reached its target, up to `iterations` Gauss-Newton steps on Phi
  // restricted to null(de/du) (the end-effector moves only to second order)
  // each followed by re-converging the task; a step is kept only if the
  // target is reached again and Phi decreased. So the end-effector error is
  // that of the plain controller; only redundant (over-actuated) systems,
  // with more effective controls than controlled components, have a null
  // space to use. Not applied under step constraints (differential bases,
  // joint limits).
  struct Secondary {
    double singularity_weight = 0;      // w_sigma >= 0 [1], in [0, 1e6]
    double singularity_threshold = 0.1; // sigma_0: barrier active below [m or rad per control unit], in [1e-6, 100]
    double pivot_weight = 0;            // w_rho >= 0 [1], in [0, 1e6]
    double pivot_threshold = 1e-3;      // rho_0: barrier active below [1], in [1e-9, 1]
    double spread_weight = 0;           // w_spread [1/m^2], in [0, 1e6]
    double clearance_m = 0.5;           // c [m], in [1e-3, 100]
    double travel_weight = 0;           // w_travel [1/(m^2 or rad^2)], in [0, 1e6]
    int iterations = 3;                 // null-space steps per control step, in [1, 100]
    double sigma_step = 1e-4;           // h of the tangent-line differences (singularity.h, pivot_ratio.h) [m or rad], in [1e-8, 1e-2]
    bool enabled() const {
      return singularity_weight > 0 || pivot_weight > 0 || spread_weight > 0 || travel_weight > 0;
    }
  } secondary;
  // Called at the start of every step (iteration 0) and after every outer
  // iteration with the wall time since the step began [ms], the objective O
  // and the largest end-effector error [m, rad] (convergence curves).
  std::function<void(int iteration, double elapsed_ms, double objective, double error)> on_iteration;

  // True if every field is in range (including `forward`); otherwise false
  // and, if `why` is not null, a message naming the field and its range.
  bool IsValid(std::string* why) const;
};

// One solve toward one target (no path splitting).
struct ControlStepResult {
  bool reached = false;     // target within tolerance and assembled
  bool assembled = false;
  bool singular = false;    // dG/ds was singular at some accepted point
  int iterations = 0;       // outer iterations
  int forward_solves = 0;
  int branch_jumps_rejected = 0;  // LM trials that landed on another branch
  double objective = 0;     // O at the returned controls
  double error = 0;         // max |e| over the controlled components [m, rad]
  double residual_energy = 0;
  double rcond = 0;         // pivot ratio of dG/ds at the last linearisation
  // Smallest singular value of dX_c/du (controlled end-effector components
  // over the effective controls) at the last linearisation, m or rad per
  // control unit: it falls to 0 at the edge of the workspace, where dG/ds
  // may stay well conditioned.
  double min_singular_value_dX_du = 0;
  double secondary_objective = 0;  // Phi at the returned controls (0 when off; +inf if dG/ds failed to factorise)
  int null_space_steps = 0;        // accepted secondary (null-space) steps
  // Inequalities and non-holonomic bases (model_format.md): the largest joint
  // limit violation [rad or m] and lateral displacement of a differential
  // base over this step [m] at the returned controls (both ~0), and the
  // joints held at a limit when the step ended ("" if none).
  double max_limit_violation = 0;
  double max_lateral_displacement = 0;
  // Clearance (model_format.md `collision`): how far [m] a pair of shapes is
  // below collision.margin at the returned controls (0; a pair that started
  // below keeps its starting clearance instead).
  double max_clearance_violation = 0;
  // Effort limits (model_format.md `effort_limits`, `push_limit`, with
  // masses): how far [N or N*m] an effort or push is beyond its limit (0).
  double max_effort_violation = 0;
  std::string limited_by;  // also the pairs of shapes held at the margin, the efforts at a limit
  double time_ms = 0;
};

struct ControlResult {
  bool converged = false;   // final target reached (see ControlStepResult)
  bool assembled = false;
  int steps = 0;            // path steps taken
  int iterations = 0;       // outer iterations, all steps
  int forward_solves = 0;
  int branch_jumps_rejected = 0;
  double objective = 0;
  double error = 0;
  double residual_energy = 0;
  double max_step_residual_energy = 0;  // worst E over the path's steps
  double rcond = 0;                     // at the end
  double min_rcond = 0;                 // over the path
  double min_singular_value_dX_du = 0;  // at the end (see ControlStepResult)
  double min_singular_value_dX_du_on_path = 0;  // smallest over the path's steps
  double secondary_objective = 0;       // Phi at the end (0 when off)
  int null_space_steps = 0;             // accepted null-space steps, all steps
  double max_limit_violation = 0;       // worst over the path's steps
  double max_lateral_displacement = 0;  // worst over the path's steps
  double max_clearance_violation = 0;   // worst over the path's steps
  double max_effort_violation = 0;      // worst over the path's steps [N or N*m]
  std::string limited_by;               // joints at a limit, pairs at the margin, when it stopped
  double solve_time_ms = 0;
  std::string warning;      // empty, or why the target was not reached
};

class ControlProblem {
 public:
  // Throws std::invalid_argument if !options.IsValid().
  explicit ControlProblem(const Model& model, const ControlOptions& options = {});
  // The problem keeps a reference to the model: a temporary would dangle.
  explicit ControlProblem(const Model&& model, const ControlOptions& options = {}) = delete;
  ~ControlProblem();
  ControlProblem(const ControlProblem&) = delete;
  ControlProblem& operator=(const ControlProblem&) = delete;

  // Assembles the mechanism at u (from the current state, following the
  // branch) and makes u the starting controls.
  ForwardResult SetControls(const Eigen::VectorXd& u);

  // Moves the controls straight to u, a correction too small to need a
  // control step (a compensated control's, problems/compensated_control.h),
  // when nothing a control step enforces could object: no step constraint
  // holds equalities (differential arcs), no secondary objective shapes the
  // redundancy, the mechanism assembles at u and every step constraint
  // (joint and effort limits, clearance) holds there to 1e-9. Otherwise the
  // controls and state stay as they were and it returns false.
  bool CorrectTo(const Eigen::VectorXd& u);
  // Whether CorrectTo may accept anything: no differential arcs, no
  // secondary objective.
  bool correctable() const;

  // One outer solve toward `target`, warm-started from the current controls.
  // Throws std::invalid_argument for a target entry that is not finite or
  // outside [-kMaxMagnitude, kMaxMagnitude].
  ControlStepResult SolveStep(const PoseTarget& target);

  // Walks the end-effector to `target` along a PosePath (path.h) with steps of
  // at most max_step_m / max_step_rad, each warm-started from the last.
  // `on_step` (optional) sees every step's target and result. Throws
  // std::invalid_argument as SolveStep() and PosePath do.
  ControlResult MoveTo(const PoseTarget& target,
                       const std::function<void(const PoseTarget&, const ControlStepResult&)>&
                           on_step = nullptr);

  // O and dO/du (effective controls) at the current, solved, controls.
  double Objective(const PoseTarget& target, Eigen::VectorXd* gradient = nullptr);
  // ds/du (state tangent x effective controls) at the current solution, by
  // the chosen gradient method.
  Eigen::MatrixXd StateSensitivity();
  // Smallest singular value sigma of dX_c/du at the current, solved,
  // controls (m or rad per control unit) and, if asked, d sigma/du over the
  // effective controls (problems/internal/singularity.h). NaN if dG/ds is
  // singular there.
  double SmallestSingularValue(const PoseTarget& target, Eigen::VectorXd* gradient = nullptr);
  // Pivot ratio rho of dG/ds (the results' `rcond`, dimensionless) at the
  // current, solved, controls and, if asked, d rho/du over the effective
  // controls (problems/internal/pivot_ratio.h). NaN if dG/ds did not factorise.
  double PivotRatio(Eigen::VectorXd* gradient = nullptr);
  // The secondary objective Phi (options().secondary) at the current, solved,
  // controls and, if asked, dPhi/du over the effective controls.
  double SecondaryObjective(const PoseTarget& target, Eigen::VectorXd* gradient = nullptr);
  // Called after every step of every MoveTo path (a compensated control's
  // rounds too) with the step's index and the path's step count (1-based):
  // what a caller's progress and work bound count (apps/work_bound.h). Null:
  // nothing. It may throw to stop the move (the exception leaves MoveTo).
  void SetPathStepObserver(std::function<void(int step, int steps)> observer) {
    path_step_observer_ = std::move(observer);
  }
  // Where base travel is measured from (set by SetControls and MoveTo).
  void SetTravelOrigin(const Eigen::VectorXd& u) { travel_origin_ = u; }

  const Eigen::VectorXd& controls() const { return forward_.controls(); }
  const std::vector<int>& effective_controls() const { return effective_; }
  const ForwardProblem& forward() const { return forward_; }
  ForwardProblem& forward() { return forward_; }
  const ControlOptions& options() const { return options_; }
  // The current end-effector pose as a target (a path's starting point).
  PoseTarget CurrentPose() const;

 private:
  // The parts of a control step (problems/internal/): the outer loops, the
  // null-space secondary objectives and the differential bases' turning.
  // They drive the forward problem through the private services below.
  friend class LmLoop;
  friend class BfgsLoop;
  friend class BfgsObjective;
  friend class NullSpaceStep;
  friend class SecondaryObjectiveTerms;
  friend class DifferentialTurning;
  friend class TrajectoryPlanner;
  struct Workspace;  // end-effector error, Hessian solver, step constraints, buffers
  // The entries of u that are controls.
  Eigen::VectorXd EffectiveControls(const Eigen::VectorXd& u) const;
  // Re-solves the forward problem at u (effective entries replaced by ue)
  // from `start`; returns false if the solve was not usable.
  bool SolveAt(const Eigen::VectorXd& ue, const State& start);
  // r = [e; sqrt(lambda) C] at the current solution.
  Eigen::VectorXd Residuals(const PoseTarget& target) const;
  // The Gauss-Newton model of r(u) at the current solution: r, ds/du and
  // J^T J, J^T r of dr/du_eff (implicit or finite differences;
  // problems/internal/control_linearization.h).
  void Linearize(const PoseTarget& target, ControlLinearization* lin);
  // The sensitivities at the current solution; when dG/ds is singular only
  // through idle motions (de_ds given: problems/internal/idle_motions.h),
  // those of dG/ds + mu I.
  std::unique_ptr<Sensitivity> LinearizedSensitivity(const Eigen::MatrixXd* de_ds);
  void LargeGaussNewton(const Eigen::VectorXd& e, const Eigen::MatrixXd& de_ds, ControlLinearization* lin);
  void LinearizeByFiniteDifferences(const PoseTarget& target, Eigen::MatrixXd* J, Eigen::MatrixXd* ds_du);
  // ds/du * du at the last linearisation (one sparse solve when ds/du was
  // not formed).
  Eigen::VectorXd PredictedStateChange(const ControlLinearization& lin, const Eigen::VectorXd& du) const;
  // Error, energy, step-constraint measures and `reached` of a step's result.
  void Finish(const PoseTarget& target, ControlStepResult* result);
  // After a stop that left the mechanism unassembled: restores the last
  // assembled configuration of the path (problems/internal/path_tally.h) and
  // measures it against `target`.
  void ReturnToLastAssembled(const PoseTarget& target, PathTally* tally);
  void CheckTarget(const PoseTarget& target) const;

  const ControlOptions options_;
  ForwardProblem forward_;
  const std::vector<int> effective_;
  std::unique_ptr<Workspace> workspace_;
  Eigen::VectorXd travel_origin_;  // all controls; the start of base travel
  int forward_solves_ = 0;
  std::function<void(int, int)> path_step_observer_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_CONTROL_PROBLEM_H_
