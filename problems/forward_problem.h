// The forward problem (simulation, paper Section III-A):
//   s_hat(u) = argmin_s E(s, u) = 1/2 C(s, u)^T C(s, u)
// as one ceres::Problem over the body poses, built once per model. The control
// blocks are held constant; each Solve() warm-starts from the last state, so
// a control loop can call it thousands of times without rebuilding anything.
//
// Model and workspace (as in Pinocchio): the Model is constant and shared;
// the problem keeps a reference to it (the model must outlive the problem)
// and owns only its per-problem workspace (state, Ceres problem, buffers).
//
// Honest reporting: a solve converges to dE/ds = 0, not necessarily E = 0.
// `assembled` says whether E fell below ForwardOptions::assembly_tolerance;
// controls the mechanism cannot reach leave E > 0 and assembled = false.
// Assemble() also reports a jump to another assembly branch.
#ifndef CCMA_PROBLEMS_FORWARD_PROBLEM_H_
#define CCMA_PROBLEMS_FORWARD_PROBLEM_H_

#include <functional>
#include <memory>
#include <string>
#include <utility>

#include <Eigen/Core>

#include "ccma/end_effector.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

class ConstraintSet;  // internal (ccma/internal/constraint_set.h)

// Linear solver inside each Levenberg-Marquardt step. Sparse normal Cholesky
// with Eigen's simplicial factorisation is the fastest on every reference
// model (benchmarks/forward_benchmark.cc); the others remain for comparison.
enum class LinearSolverChoice {
  kAuto,
  kDenseQr,
  kDenseNormalCholesky,
  kSparseNormalCholesky,       // SuiteSparse CHOLMOD
  kEigenSparseNormalCholesky,  // Eigen::SimplicialLDLT
};

// The minimiser of E over the state. Both use the same analytic cost
// functions and pose increments and stop on the same tolerances.
enum class ForwardSolver {
  // ccma's own sparse Levenberg-Marquardt loop (problems/internal/sparse_lm.h):
  // pattern and symbolic factorisation once per model, no per-call
  // preprocessing or allocation. The default: several times faster per call.
  kNative,
  // ceres::Solve on a ceres::Problem built once per model (the reference).
  kCeres,
};

struct ForwardOptions {
  ForwardSolver solver = ForwardSolver::kNative;
  // E [m^2] below which the mechanism counts as assembled. 1e-16 means every
  // constraint row is below ~1.4e-8 (m, or rad-like for directions). When the
  // controls can be reached, solves end near E ~ 1e-28, far below.
  double assembly_tolerance = 1e-16;
  int max_iterations = 100;  // per Solve() (per sub-step in Assemble())
  // Assemble() splits a control change into sub-steps no larger than this
  // (max-norm over u; m and rad) to stay on the branch connected to the start.
  double max_control_step = 0.02;
  // kCeres only; kAuto: Eigen sparse normal Cholesky (see LinearSolverChoice).
  LinearSolverChoice linear_solver = LinearSolverChoice::kAuto;
  // Solve() starts from a secant prediction when the controls keep moving
  // the way they moved in the last solve (a path: du nearly parallel to the
  // last du, 0 < alpha <= 2 times it): s + alpha (s_last - s_before_last),
  // taken only if E is lower there than at s. Saves about one iteration per
  // step along a path; never changes which minimum LM converges to nearby.
  bool secant_predictor = true;
  // Solve() first checks whether the new controls are the last ones moved by
  // one planar rigid motion (every base's (x, y) and heading by the same
  // rotation about world z and horizontal translation, actuated joints held)
  // in a model with no joint to the ground; if so it moves every body by
  // that motion, which keeps every constraint, and when the last solve had
  // converged the solve ends without an iteration: E stays at the last
  // solve's, plus the rounding of the moved poses, accepted up to 1e-26 m^2
  // (rows ~1e-13 m; problems/internal/planar_rigid_motion.h). Takes
  // precedence over the secant predictor.
  bool rigid_motion_predictor = true;
  // kCeres only: print Ceres' per-iteration progress to stdout.
  bool log_progress = false;
  // When E stays > assembly_tolerance, Levenberg-Marquardt (Gauss-Newton)
  // converges only linearly; up to this many Newton steps on the exact
  // Hessian of E (as in the paper) then make dE/ds ~ 0 to machine
  // precision, which the control sensitivities assume. The native solver
  // hands over to them as soon as its convergence turns linear (and resumes
  // if they do not reach dE/ds ~ 0); 0 turns both off.
  int max_newton_polish_steps = 8;
  // Branch jumps in Assemble(): a sub-step whose solved state differs from
  // the first-order prediction s + ds/du du by more than
  //   branch_jump_relative * |ds/du du| + branch_jump_absolute
  // (max-norm over the state tangent: m and rad) is reported as a jump.
  double branch_jump_relative = 0.5;
  double branch_jump_absolute = 0.01;

  // True if every field is in range; otherwise false and, if `why` is not
  // null, a message naming the field and its range.
  bool IsValid(std::string* why) const;
};

struct ForwardResult {
  bool converged = false;   // the solver's convergence test held (dE/ds ~ 0)
  bool assembled = false;   // residual_energy < assembly_tolerance
  double residual_energy = 0;  // E(s_hat, u) [m^2]
  int iterations = 0;       // LM iterations (trial steps), summed over sub-steps
  int substeps = 1;         // solves made (Assemble() may split the step)
  int newton_steps = 0;     // exact-Newton polish steps after LM (E > 0)
  double gradient_norm = 0; // max |dE/ds| at the end
  // gradient_norm is an upper bound, 2 |J|_F |C|, not the value: the solve
  // moved an assembled state rigidly with its bases and checked its residuals
  // only (ForwardOptions::rigid_motion_predictor; E <= 1e-24 m^2 there).
  bool gradient_norm_is_bound = false;
  double solve_time_ms = 0; // wall time of the solve(s)
  // Assemble() only: some sub-step left the branch its predictor followed
  // (see ForwardOptions::branch_jump_relative); the largest deviation from
  // the prediction [m or rad] and the sub-step where it happened.
  bool branch_jump = false;
  double branch_jump_size = 0;
  int branch_jump_substep = -1;
  std::string message;      // the solver's termination message (last solve)
};

class ForwardProblem {
 public:
  // Throws std::invalid_argument if !options.IsValid().
  explicit ForwardProblem(const Model& model, const ForwardOptions& options = {});
  // The problem keeps a reference to the model: a temporary would dangle.
  explicit ForwardProblem(const Model&& model, const ForwardOptions& options = {}) = delete;
  ~ForwardProblem();
  ForwardProblem(const ForwardProblem&) = delete;
  ForwardProblem& operator=(const ForwardProblem&) = delete;

  // One warm-started solve at controls u (model.h: 3 per base, x [m], y [m],
  // theta [rad]), from the current state. Throws std::invalid_argument if u
  // has the wrong size or an entry that is not finite or outside
  // [-kMaxMagnitude, kMaxMagnitude] (ccma/limits.h).
  ForwardResult Solve(const Eigen::VectorXd& u);

  // Moves the controls from their current value to u in sub-steps of at most
  // options.max_control_step, solving after each: follows the assembly branch
  // from the current configuration, and reports a branch jump (ForwardResult).
  // What `ccma simulate` uses. Throws std::invalid_argument as Solve() does,
  // and when more than kMaxAssemblySubsteps sub-steps would be needed.
  ForwardResult Assemble(const Eigen::VectorXd& u);
  // The number of sub-steps Assemble(u) will take. Throws as Assemble() does.
  int SubstepsTo(const Eigen::VectorXd& u) const;
  // Called after every sub-step of Assemble() with its index and the
  // sub-step count (1-based): what a caller's progress and work bound count
  // (apps/work_bound.h). Null: nothing. It may throw to stop the walk.
  void SetSubstepObserver(std::function<void(int substep, int substeps)> observer) {
    substep_observer_ = std::move(observer);
  }

  // Back to the home configuration and home controls (no solve).
  void ResetToHome();
  // Replaces the state (e.g. to warm-start from a saved configuration).
  void SetState(const State& s);
  // Replaces state and controls without solving (undoing a trial step).
  void Restore(const State& s, const Eigen::VectorXd& u);

  const Model& model() const { return model_; }
  const State& state() const { return state_; }
  const Eigen::VectorXd& controls() const { return controls_; }
  EndEffectorPose end_effector() const { return ComputeEndEffectorPose(model_, state_); }
  // E at the current state and controls [m^2].
  double Energy() const;
  const ForwardOptions& options() const { return options_; }

  // Internal: the model's constraints (ccma/internal/constraint_set.h).
  const ConstraintSet& constraints() const;

 private:
  struct Workspace;  // Ceres problem, constraint set, Newton buffers
  void CheckControls(const Eigen::VectorXd& u) const;
  // Exact-Newton steps on E from the current state; updates `result`.
  void NewtonPolish(ForwardResult* result);
  // Moves the state to the rigid-motion prediction or else the secant
  // prediction for controls u (ForwardOptions::rigid_motion_predictor,
  // secant_predictor); remembers this step for the next.
  void PredictFromLastStep(const Eigen::VectorXd& u);
  // u - controls, headings wrapped to the short way.
  Eigen::VectorXd ControlChange(const Eigen::VectorXd& u) const;
  // Number of sub-steps to move the controls by `change`; throws when too many.
  int SubstepCount(const Eigen::VectorXd& change) const;

  const Model& model_;
  const ForwardOptions options_;
  State state_;
  Eigen::VectorXd controls_;
  std::unique_ptr<Workspace> workspace_;
  std::function<void(int, int)> substep_observer_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_FORWARD_PROBLEM_H_
