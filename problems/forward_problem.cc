#include "problems/forward_problem.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <ceres/problem.h>
#include <ceres/solver.h>

#include "ccma/internal/constraint_set.h"
#include "ccma/internal/format.h"
#include "ccma/internal/elapsed.h"
#include "ccma/internal/in_range.h"
#include "ccma/internal/pose_manifold.h"
#include "ccma/limits.h"
#include "ccma/rotation.h"
#include "problems/internal/planar_rigid_motion.h"
#include "problems/internal/sensitivity.h"
#include "problems/internal/sparse_lm.h"

namespace ccma {
namespace {

// max |dE/ds| [m] that counts as stationary after the Newton polish (the
// gradient tolerance of the Ceres path is 1e-15; the polish ends near 1e-16).
constexpr double kPolishedGradient = 1e-14;

using Clock = std::chrono::steady_clock;

ceres::Solver::Options SolverOptions(const ForwardOptions& options) {
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  LinearSolverChoice choice = options.linear_solver;
  if (choice == LinearSolverChoice::kAuto) choice = LinearSolverChoice::kEigenSparseNormalCholesky;
  switch (choice) {
    case LinearSolverChoice::kDenseNormalCholesky:
      so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
      break;
    case LinearSolverChoice::kSparseNormalCholesky:
      so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      so.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
      break;
    case LinearSolverChoice::kEigenSparseNormalCholesky:
      so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      so.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
      break;
    default:
      so.linear_solver_type = ceres::DENSE_QR;
  }
  so.max_num_iterations = options.max_iterations;
  // Tight tolerances: a reachable assembly must end near E ~ 1e-28, and the
  // sensitivities of the control problem need dE/ds ~ 0 to machine precision.
  // The gradient tolerance is at rounding level (|dE/ds| ~ 2e-16 at a
  // solution): at 1e-14 Ceres stopped on 6dof_asymmetric at E ~ 2e-26, its
  // state 1.6e-11 from the solution, and the native path (which converges to
  // rounding level) could not be checked against it to 1e-12.
  so.function_tolerance = 1e-15;
  so.gradient_tolerance = 1e-15;
  so.parameter_tolerance = 1e-15;
  so.initial_trust_region_radius = 1e8;  // warm starts are near-Newton steps
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = options.log_progress;
  return so;
}


}  // namespace

bool ForwardOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!InRange(assembly_tolerance, 1e-32, 1.0)) {
    return fail("assembly_tolerance must lie in [1e-32, 1] (m^2), got " + FormatG(assembly_tolerance));
  }
  if (!InRange(max_iterations, 1, 100000)) {
    return fail("max_iterations must lie in [1, 100000], got " + std::to_string(max_iterations));
  }
  if (!InRange(max_control_step, 1e-6, 1e3)) {
    return fail("max_control_step must lie in [1e-6, 1000] (m or rad), got " + FormatG(max_control_step));
  }
  if (!InRange(max_newton_polish_steps, 0, 1000)) {
    return fail("max_newton_polish_steps must lie in [0, 1000], got " + std::to_string(max_newton_polish_steps));
  }
  if (!InRange(branch_jump_relative, 0, 1e6) || !InRange(branch_jump_absolute, 0, 1e6)) {
    return fail("branch_jump_relative and branch_jump_absolute must lie in [0, 1e6]");
  }
  return true;
}

// Everything a ForwardProblem owns besides its state and controls.
struct ForwardProblem::Workspace {
  explicit Workspace(const Model& model)
      : constraints(model), lm(constraints), hessian_solver(constraints),
        moves_rigidly(MovesRigidlyWithItsBases(model)) {}
  ConstraintSet constraints;
  BodyFrames frames;                      // the predictor's Energy workspace
  SparseLevenbergMarquardt lm;            // ForwardSolver::kNative
  PoseManifold manifold;
  std::unique_ptr<ceres::Problem> problem;
  ceres::Solver::Options solver_options;
  HessianSolver hessian_solver;           // Newton polish and Assemble's predictor
  EnergyDerivatives derivatives[2];       // current point and candidate
  // The secant predictor's memory: the state and controls before the last
  // solve (valid once one solve has run), and scratch.
  bool has_last_step = false;
  State state_before_last;
  Eigen::VectorXd controls_before_last, du, du_last, ds;
  State predicted;
  const bool moves_rigidly;  // no joint to the ground (planar_rigid_motion.h)
  // state_ is the converged end of the last Solve() for controls_, with E =
  // last_energy (nothing has set the state since).
  bool converged_here = false;
  double last_energy = 0;
  // E up to which the rigid image of that state counts as converged (0: no
  // rigid prediction for this solve).
  double rigid_energy = 0;
  double world_pose[kPoseAmbientSize] = {0, 0, 0, 1, 0, 0, 0};  // the ground, constant
};

ForwardProblem::ForwardProblem(const Model& model, const ForwardOptions& options)
    : model_(model), options_(options) {
  std::string why;
  if (!options_.IsValid(&why)) throw std::invalid_argument("ForwardOptions: " + why);
  state_ = State::Home(model_);
  controls_ = model_.home_controls();
  workspace_ = std::make_unique<Workspace>(model_);

  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.enable_fast_removal = false;
  workspace_->problem = std::make_unique<ceres::Problem>(problem_options);
  ceres::Problem& problem = *workspace_->problem;
  for (int i = 0; i < model_.num_bodies(); ++i) {
    problem.AddParameterBlock(state_.pose(i), kPoseAmbientSize, &workspace_->manifold);
  }
  std::vector<double*> blocks;
  for (const ConstraintBlock& block : workspace_->constraints.blocks()) {
    blocks.clear();
    for (int body : block.bodies) {
      // The ground: one constant identity pose block, shared.
      if (body == kWorld && !problem.HasParameterBlock(workspace_->world_pose)) {
        problem.AddParameterBlock(workspace_->world_pose, kPoseAmbientSize);
        problem.SetParameterBlockConstant(workspace_->world_pose);
      }
      blocks.push_back(body == kWorld ? workspace_->world_pose : state_.pose(body));
    }
    if (block.control_size > 0) {
      double* control = controls_.data() + block.control_offset;
      if (!problem.HasParameterBlock(control)) {
        problem.AddParameterBlock(control, block.control_size);
        problem.SetParameterBlockConstant(control);
      }
      blocks.push_back(control);
    }
    problem.AddResidualBlock(block.cost.get(), nullptr, blocks);
  }
  workspace_->solver_options = SolverOptions(options_);
}

ForwardProblem::~ForwardProblem() = default;

const ConstraintSet& ForwardProblem::constraints() const { return workspace_->constraints; }

double ForwardProblem::Energy() const { return workspace_->constraints.Energy(state_, controls_); }

void ForwardProblem::CheckControls(const Eigen::VectorXd& u) const {
  if (u.size() != workspace_->constraints.num_controls()) {  // cached: Model counts its joints
    throw std::invalid_argument("controls: expected " + std::to_string(model_.num_controls()) +
                                " values (3 per mobile base, 6 per legged base, then 1 per actuated joint), got " +
                                std::to_string(u.size()));
  }
  for (int i = 0; i < u.size(); ++i) {
    if (!(std::abs(u[i]) <= kMaxMagnitude)) {
      throw std::invalid_argument("controls: entry " + std::to_string(i) + " (" + FormatG(u[i]) +
                                  ") must be a finite number in [-" + FormatG(kMaxMagnitude) + ", " +
                                  FormatG(kMaxMagnitude) + "] (m or rad)");
    }
  }
}

void ForwardProblem::PredictFromLastStep(const Eigen::VectorXd& u) {
  Workspace& w = *workspace_;
  w.rigid_energy = 0;
  PlanarRigidMotion motion;
  if (options_.rigid_motion_predictor && w.moves_rigidly && PlanarRigidMotionBetween(model_, controls_, u, &motion)) {
    w.state_before_last = state_;
    w.controls_before_last = controls_;
    w.has_last_step = true;
    ApplyPlanarRigidMotion(motion, &state_);
    // The image of a converged state is converged (E and the norm of dE/ds
    // are invariant) up to the rounding of the moved poses, which adds up
    // over many moves: hence an absolute bound (kRigidImageEnergy), past
    // which the LM iterates back to rounding level. A stationary point out
    // of reach keeps its E > kRigidImageEnergy: rounding changes it only to
    // second order.
    if (w.converged_here) w.rigid_energy = std::max(kRigidImageEnergy, w.last_energy * (1 + 1e-9));
    return;
  }
  if (options_.secant_predictor && w.has_last_step) {
    w.du = u - controls_;
    w.du_last = controls_ - w.controls_before_last;
    const double last = w.du_last.squaredNorm();
    const double alpha = last > 0 ? w.du.dot(w.du_last) / last : 0;
    // Only along a path: the new change nearly parallel to the last one.
    if (alpha > 0 && alpha <= 2 && (w.du - alpha * w.du_last).norm() <= 0.05 * w.du.norm()) {
      state_.Minus(w.state_before_last, &w.ds);
      w.ds *= alpha;
      w.predicted = state_;
      w.predicted.Plus(w.ds);
      if (w.constraints.Energy(w.predicted, u, &w.frames) < w.constraints.Energy(state_, u, &w.frames)) {
        w.state_before_last = state_;
        state_ = w.predicted;  // a copy into the same storage (Ceres holds its addresses)
        w.controls_before_last = controls_;
        w.has_last_step = true;
        return;
      }
    }
  }
  w.state_before_last = state_;
  w.controls_before_last = controls_;
  w.has_last_step = true;
}

ForwardResult ForwardProblem::Solve(const Eigen::VectorXd& u) {
  CheckControls(u);
  const auto start = Clock::now();
  PredictFromLastStep(u);
  controls_ = u;  // the control blocks alias controls_' storage
  ForwardResult result;
  bool usable = true;
  bool polished = false;
  if (options_.solver == ForwardSolver::kNative) {
    // Where Gauss-Newton turns linear (E > 0 at a stationary point: the
    // trial controls of a control step, unreachable controls), the exact
    // Newton polish takes over at once rather than after tens of linearly
    // converging iterations; should it not reach dE/ds ~ 0, LM resumes.
    const bool polish = options_.max_newton_polish_steps > 0;
    SparseLmSummary summary =
        workspace_->lm.Solve(&state_, controls_, options_.max_iterations, polish, workspace_->rigid_energy);
    result.iterations = summary.iterations;
    if (summary.linear) {
      result.residual_energy = summary.energy;
      NewtonPolish(&result);
      polished = true;
      if (!(result.gradient_norm <= kPolishedGradient)) {
        summary = workspace_->lm.Solve(&state_, controls_, options_.max_iterations - summary.iterations, false);
        result.iterations += summary.iterations;
        polished = false;  // the polish after LM, as without the early stop
      } else {
        summary.converged = true;
        summary.energy = result.residual_energy;
        summary.gradient_norm = result.gradient_norm;
      }
    }
    result.residual_energy = summary.energy;
    result.converged = summary.converged;
    result.gradient_norm = summary.gradient_norm;
    result.gradient_norm_is_bound = summary.gradient_norm_is_bound;
    result.message = summary.converged ? "converged" : "not converged: iteration limit or no decrease";
  } else {
    ceres::Solver::Summary summary;
    ceres::Solve(workspace_->solver_options, workspace_->problem.get(), &summary);
    result.residual_energy = summary.final_cost;
    result.converged = summary.termination_type == ceres::CONVERGENCE;
    result.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
    result.message = summary.message;
    usable = summary.IsSolutionUsable();
  }
  result.solve_time_ms = MillisecondsSince(start);
  result.assembled = usable && result.residual_energy < options_.assembly_tolerance;
  if (!result.assembled && !polished && options_.max_newton_polish_steps > 0) {
    NewtonPolish(&result);
    result.solve_time_ms = MillisecondsSince(start);
  }
  workspace_->converged_here = result.converged;
  workspace_->last_energy = result.residual_energy;
  return result;
}

void ForwardProblem::NewtonPolish(ForwardResult* result) {
  const ConstraintSet& constraints = workspace_->constraints;
  HessianSolver& solver = workspace_->hessian_solver;
  EnergyDerivatives* now = &workspace_->derivatives[0];
  EnergyDerivatives* next = &workspace_->derivatives[1];
  constraints.EvaluateDerivatives(state_, controls_, now);
  for (int step = 0; step < options_.max_newton_polish_steps; ++step) {
    if (now->G.lpNorm<Eigen::Infinity>() <= 1e-16 || !solver.Factorize(now->H) ||
        solver.pivot_ratio() <= 0) {
      break;  // stationary, or H not positive definite (not near a minimum)
    }
    const Eigen::VectorXd ds = -solver.Solve(now->G);
    const State before = state_;
    state_.Plus(ds);
    constraints.EvaluateDerivatives(state_, controls_, next);
    // Near a minimum E changes by O(|ds|^2) ~ rounding: judge by the gradient.
    if (!(next->G.lpNorm<Eigen::Infinity>() < now->G.lpNorm<Eigen::Infinity>()) ||
        next->energy > now->energy * (1 + 1e-12) + 1e-30) {
      SetState(before);
      break;
    }
    std::swap(now, next);
    ++result->newton_steps;
    if (ds.lpNorm<Eigen::Infinity>() < 1e-15) break;
  }
  result->residual_energy = now->energy;
  result->gradient_norm = now->G.lpNorm<Eigen::Infinity>();
  result->gradient_norm_is_bound = false;
  result->assembled = result->residual_energy < options_.assembly_tolerance;
}

Eigen::VectorXd ForwardProblem::ControlChange(const Eigen::VectorXd& u) const {
  // Headings matter modulo 2 pi (motor rows use cos, sin): walk the short way.
  Eigen::VectorXd change = u - controls_;
  for (int k = 0; k < model_.num_bases(); ++k) {
    change[model_.base_control(k) + kBaseHeading] = WrapAngle(change[model_.base_control(k) + kBaseHeading]);
  }
  return change;
}

int ForwardProblem::SubstepsTo(const Eigen::VectorXd& u) const {
  CheckControls(u);
  return SubstepCount(ControlChange(u));
}

int ForwardProblem::SubstepCount(const Eigen::VectorXd& change) const {
  // Computed in double and bounded before any conversion to an integer.
  const double count = std::ceil(change.lpNorm<Eigen::Infinity>() / options_.max_control_step);
  if (!(count <= static_cast<double>(kMaxAssemblySubsteps))) {
    throw std::invalid_argument("controls: moving them by " + FormatG(change.lpNorm<Eigen::Infinity>()) +
                                " (m or rad) in sub-steps of " + FormatG(options_.max_control_step) +
                                " would take more than " + std::to_string(kMaxAssemblySubsteps) +
                                " sub-steps");
  }
  return std::max(1, static_cast<int>(count));
}

ForwardResult ForwardProblem::Assemble(const Eigen::VectorXd& u) {
  CheckControls(u);
  const Eigen::VectorXd from = controls_;
  const Eigen::VectorXd change = ControlChange(u);
  const int substeps = SubstepCount(change);
  std::vector<int> all_controls(static_cast<size_t>(model_.num_controls()));
  for (int c = 0; c < model_.num_controls(); ++c) all_controls[c] = c;

  ForwardResult total;
  total.substeps = substeps;
  for (int i = 1; i <= substeps; ++i) {
    const Eigen::VectorXd u_i = i == substeps ? u : Eigen::VectorXd(from + change * (double(i) / substeps));
    // First-order prediction of this sub-step, to tell continuation from a jump.
    const Sensitivity sensitivity(workspace_->constraints, state_, controls_, all_controls,
                                  &workspace_->hessian_solver, &workspace_->derivatives[0]);
    Eigen::VectorXd du = u_i - controls_;
    for (int k = 0; k < model_.num_bases(); ++k) {
      du[model_.base_control(k) + kBaseHeading] = WrapAngle(du[model_.base_control(k) + kBaseHeading]);
    }
    const Eigen::VectorXd ds_predicted = sensitivity.StateChange(du);
    const State before = state_;
    const ForwardResult step = Solve(u_i);
    if (!sensitivity.singular()) {
      State predicted = before;
      predicted.Plus(ds_predicted);
      const double deviation = state_.Minus(predicted).lpNorm<Eigen::Infinity>();
      const double allowed = options_.branch_jump_relative * ds_predicted.lpNorm<Eigen::Infinity>() +
                             options_.branch_jump_absolute;
      if (deviation > allowed && deviation > total.branch_jump_size) {
        total.branch_jump = true;
        total.branch_jump_size = deviation;
        total.branch_jump_substep = i;
      }
    }
    total.iterations += step.iterations;
    total.newton_steps += step.newton_steps;
    total.solve_time_ms += step.solve_time_ms;
    total.converged = step.converged;
    total.assembled = step.assembled;
    total.residual_energy = step.residual_energy;
    total.gradient_norm = step.gradient_norm;
    total.gradient_norm_is_bound = step.gradient_norm_is_bound;
    total.message = step.message;
    if (substep_observer_) substep_observer_(i, substeps);
  }
  return total;
}

void ForwardProblem::ResetToHome() {
  SetState(State::Home(model_));
  // Copy into the existing storage: assigning a temporary would swap buffers
  // and leave Ceres' control blocks pointing at freed memory.
  const Eigen::VectorXd home = model_.home_controls();
  controls_ = home;
}

void ForwardProblem::Restore(const State& s, const Eigen::VectorXd& u) {
  CheckControls(u);
  SetState(s);
  controls_ = u;  // same size: the control blocks keep their addresses
}

void ForwardProblem::SetState(const State& s) {
  if (s.num_bodies() != model_.num_bodies()) {
    throw std::invalid_argument("SetState: expected " + std::to_string(model_.num_bodies()) +
                                " bodies, got " + std::to_string(s.num_bodies()));
  }
  // A state from elsewhere: the last step no longer predicts the next.
  workspace_->has_last_step = false;
  workspace_->converged_here = false;
  // Copy in place: Ceres holds pointers into state_'s storage.
  if (&s == &state_) return;
  for (int i = 0; i < model_.num_bodies(); ++i) {
    std::copy(s.pose(i), s.pose(i) + kPoseAmbientSize, state_.pose(i));
  }
}

}  // namespace ccma
