#include "problems/forward_problem.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include <ceres/problem.h>
#include <ceres/solver.h>

#include "ccma/pose_manifold.h"
#include "ccma/rotation.h"

namespace ccma {

struct ForwardProblem::CeresParts {
  PoseManifold manifold;
  std::unique_ptr<ceres::Problem> problem;
  ceres::Solver::Options solver_options;
};

ForwardProblem::ForwardProblem(const Model& model, const ForwardOptions& options)
    : model_(model),
      options_(options),
      constraints_(model_),
      state_(State::Home(model_)),
      controls_(model_.home_controls()),
      ceres_(std::make_unique<CeresParts>()),
      hessian_solver_(std::make_unique<HessianSolver>(constraints_)) {
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.enable_fast_removal = false;
  ceres_->problem = std::make_unique<ceres::Problem>(problem_options);
  ceres::Problem& problem = *ceres_->problem;

  for (int i = 0; i < model_.num_bodies(); ++i) {
    problem.AddParameterBlock(state_.pose(i), kPoseAmbientSize, &ceres_->manifold);
  }
  for (int k = 0; k < model_.num_bases(); ++k) {
    problem.AddParameterBlock(controls_.data() + 3 * k, 3);
    problem.SetParameterBlockConstant(controls_.data() + 3 * k);
  }
  std::vector<double*> blocks;
  for (const ConstraintBlock& block : constraints_.blocks()) {
    blocks.clear();
    for (int body : block.bodies) blocks.push_back(state_.pose(body));
    if (block.base >= 0) blocks.push_back(controls_.data() + 3 * block.base);
    problem.AddResidualBlock(block.cost.get(), nullptr, blocks);
  }

  ceres::Solver::Options& so = ceres_->solver_options;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  LinearSolverChoice choice = options_.linear_solver;
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
  so.max_num_iterations = options_.max_iterations;
  // Tight tolerances: a reachable assembly must end near E ~ 1e-28, and the
  // sensitivities of the control problem need dE/ds ~ 0 to machine precision.
  so.function_tolerance = 1e-15;
  so.gradient_tolerance = 1e-14;
  so.parameter_tolerance = 1e-15;
  so.initial_trust_region_radius = 1e8;  // warm starts are near-Newton steps
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = options_.log_progress;
}

ForwardProblem::~ForwardProblem() = default;

void ForwardProblem::CheckControls(const Eigen::VectorXd& u) const {
  if (u.size() != model_.num_controls()) {
    throw std::invalid_argument("controls: expected " +
                                std::to_string(model_.num_controls()) +
                                " values (3 per mobile base), got " +
                                std::to_string(u.size()));
  }
  for (int i = 0; i < u.size(); ++i) {
    if (!std::isfinite(u[i])) {
      throw std::invalid_argument("controls: entry " + std::to_string(i) +
                                  " is not a finite number");
    }
  }
}

ForwardResult ForwardProblem::Solve(const Eigen::VectorXd& u) {
  CheckControls(u);
  controls_ = u;  // the control blocks alias controls_' storage
  const auto start = std::chrono::steady_clock::now();
  ceres::Solver::Summary summary;
  ceres::Solve(ceres_->solver_options, ceres_->problem.get(), &summary);
  const auto stop = std::chrono::steady_clock::now();

  ForwardResult result;
  result.solve_time_ms = std::chrono::duration<double, std::milli>(stop - start).count();
  result.residual_energy = summary.final_cost;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.assembled = summary.IsSolutionUsable() &&
                     result.residual_energy < options_.assembly_tolerance;
  result.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  result.message = summary.message;
  if (!result.assembled && options_.max_newton_polish_steps > 0) {
    NewtonPolish(&result);
    result.solve_time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  return result;
}

void ForwardProblem::NewtonPolish(ForwardResult* result) {
  // Two workspaces, swapped: the current point and the candidate.
  EnergyDerivatives* now = &polish_workspace_[0];
  EnergyDerivatives* next = &polish_workspace_[1];
  constraints_.EvaluateDerivatives(state_, controls_, now);
  for (int step = 0; step < options_.max_newton_polish_steps; ++step) {
    if (now->G.lpNorm<Eigen::Infinity>() <= 1e-16 || !hessian_solver_->Factorize(now->H) ||
        hessian_solver_->pivot_ratio() <= 0) {
      break;  // stationary, or H not positive definite (not near a minimum)
    }
    const Eigen::VectorXd ds = -hessian_solver_->Solve(now->G);
    const State before = state_;
    state_.Plus(ds);
    constraints_.EvaluateDerivatives(state_, controls_, next);
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
  const EnergyDerivatives& d = *now;
  result->residual_energy = d.energy;
  result->gradient_norm = d.G.lpNorm<Eigen::Infinity>();
  result->assembled = result->residual_energy < options_.assembly_tolerance;
}

ForwardResult ForwardProblem::Assemble(const Eigen::VectorXd& u) {
  CheckControls(u);
  const Eigen::VectorXd from = controls_;
  // Headings matter modulo 2 pi (motor rows use cos, sin): walk the short way.
  Eigen::VectorXd change = u - from;
  for (int k = 0; k < model_.num_bases(); ++k) change[3 * k + 2] = WrapAngle(change[3 * k + 2]);
  const double distance = change.lpNorm<Eigen::Infinity>();
  const int substeps =
      std::max(1, static_cast<int>(std::ceil(distance / options_.max_control_step)));
  ForwardResult total;
  for (int i = 1; i <= substeps; ++i) {
    const Eigen::VectorXd u_i =
        i == substeps ? u : Eigen::VectorXd(from + change * (double(i) / substeps));
    const ForwardResult step = Solve(u_i);
    total.iterations += step.iterations;
    total.solve_time_ms += step.solve_time_ms;
    total.converged = step.converged;
    total.assembled = step.assembled;
    total.residual_energy = step.residual_energy;
    total.message = step.message;
  }
  total.substeps = substeps;
  return total;
}

void ForwardProblem::ResetToHome() {
  const State home = State::Home(model_);
  SetState(home);
  controls_ = model_.home_controls();
}

void ForwardProblem::Restore(const State& s, const Eigen::VectorXd& u) {
  CheckControls(u);
  SetState(s);
  controls_ = u;  // same size: the control blocks keep their addresses
}

void ForwardProblem::SetState(const State& s) {
  if (s.num_bodies() != model_.num_bodies()) {
    throw std::invalid_argument("SetState: wrong number of bodies");
  }
  // Copy in place: Ceres holds pointers into state_'s storage.
  if (&s == &state_) return;
  for (int i = 0; i < model_.num_bodies(); ++i) {
    std::copy(s.pose(i), s.pose(i) + kPoseAmbientSize, state_.pose(i));
  }
}

}  // namespace ccma
