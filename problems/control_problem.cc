#include "problems/control_problem.h"

#include <chrono>
#include <cmath>
#include <algorithm>
#include <limits>
#include <memory>

#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <ceres/iteration_callback.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "ccma/end_effector.h"
#include "ccma/rotation.h"
#include "problems/sensitivity.h"

namespace ccma {
namespace {

using Clock = std::chrono::steady_clock;

double Milliseconds(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

// Iterations stop once the step is this far inside its tolerances: the
// forward problem then sits at its own precision floor.
constexpr double kEnergyFloor = 1e-24;

}  // namespace

// ceres::GradientProblemSolver's view of O(u_eff) for the BFGS outer loop.
// Trial controls farther than this from a step's start (max-norm, m or rad)
// are refused, so the line search backtracks instead of jumping the
// mechanism onto another assembly branch. A paper step moves bases ~1 cm.
constexpr double kMaxControlChangePerStep = 0.05;

// Every evaluation starts the forward solve from the step's starting state
// plus the first-order predictor ds/du (u - u_start): O(u) is then a function
// of u alone, not of the order in which the line search visits points (a
// far trial point would otherwise drag later ones onto another branch).
class BfgsObjective final : public ceres::FirstOrderFunction {
 public:
  BfgsObjective(ControlProblem* problem, const PoseTarget& target, const Eigen::VectorXd& start)
      : problem_(problem),
        target_(target),
        start_(start),
        state_start_(problem->forward_.state()),
        ds_du_(problem->StateSensitivity()) {}
  int NumParameters() const override { return static_cast<int>(problem_->effective_.size()); }
  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    const Eigen::VectorXd ue = Eigen::Map<const Eigen::VectorXd>(parameters, NumParameters());
    if ((ue - start_).lpNorm<Eigen::Infinity>() > kMaxControlChangePerStep) return false;
    State predicted = state_start_;
    predicted.Plus(ds_du_ * (ue - start_));
    if (!problem_->SolveAt(ue, predicted)) return false;
    Eigen::VectorXd g;
    *cost = problem_->Objective(target_, gradient != nullptr ? &g : nullptr);
    if (gradient != nullptr) Eigen::Map<Eigen::VectorXd>(gradient, NumParameters()) = g;
    return std::isfinite(*cost);
  }

 private:
  ControlProblem* problem_;
  const PoseTarget target_;
  const Eigen::VectorXd start_;
  const State state_start_;
  const Eigen::MatrixXd ds_du_;
};

// Stops BFGS once O certifies the target: sqrt(2 O) bounds every error
// component, and lambda E <= O.
class TargetReached final : public ceres::IterationCallback {
 public:
  TargetReached(double objective, std::function<void(const ceres::IterationSummary&)> report)
      : objective_(objective), report_(std::move(report)) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    report_(summary);
    return summary.cost <= objective_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
  }

 private:
  const double objective_;
  const std::function<void(const ceres::IterationSummary&)> report_;
};

ControlProblem::ControlProblem(const Model& model, const ControlOptions& options)
    : options_(options),
      forward_(model, options.forward),
      error_(forward_.model()),
      effective_(forward_.model().effective_control_indices()),
      hessian_solver_(forward_.constraints()) {}

ForwardResult ControlProblem::SetControls(const Eigen::VectorXd& u) { return forward_.Assemble(u); }

PoseTarget ControlProblem::CurrentPose() const {
  const EndEffectorPose pose = forward_.end_effector();
  return {pose.position, pose.rpy};
}

Eigen::VectorXd ControlProblem::EffectiveControls(const Eigen::VectorXd& u) const {
  Eigen::VectorXd ue(static_cast<Eigen::Index>(effective_.size()));
  for (size_t c = 0; c < effective_.size(); ++c) ue[c] = u[effective_[c]];
  return ue;
}

bool ControlProblem::SolveAt(const Eigen::VectorXd& ue, const State& start) {
  if (!ue.allFinite()) return false;
  Eigen::VectorXd u = forward_.controls();
  for (size_t c = 0; c < effective_.size(); ++c) u[effective_[c]] = ue[c];
  forward_.SetState(start);
  const ForwardResult r = forward_.Solve(u);
  ++forward_solves_;
  return std::isfinite(r.residual_energy);
}

void ControlProblem::Residuals(const PoseTarget& target, Eigen::VectorXd* r, Eigen::MatrixXd* J,
                               Eigen::MatrixXd* ds_du, double* rcond, bool* singular) {
  const State& s = forward_.state();
  const Eigen::VectorXd& u = forward_.controls();
  const double sqrt_lambda = std::sqrt(options_.lambda);
  Eigen::VectorXd e, C;
  Eigen::MatrixXd de_ds;
  error_.Evaluate(s, target, &e, J != nullptr ? &de_ds : nullptr);
  const int k = static_cast<int>(effective_.size());

  if (J == nullptr) {
    forward_.constraints().Evaluate(s, u, &C);
  } else if (options_.gradient == GradientMethod::kImplicit) {
    const Sensitivity sensitivity(forward_.constraints(), s, u, effective_, &hessian_solver_, &workspace_);
    const EnergyDerivatives& d = sensitivity.derivatives();
    C = d.C;
    *ds_du = sensitivity.StateSensitivity();
    J->resize(e.size() + C.size(), k);
    J->topRows(e.size()).noalias() = de_ds * *ds_du;
    J->bottomRows(C.size()) =
        sqrt_lambda * ConstraintJacobianTimes(forward_.constraints(), d.J_s, *ds_du);
    for (int c = 0; c < k; ++c) J->bottomRows(C.size()).col(c) += sqrt_lambda * d.J_u.col(effective_[c]);
    if (rcond != nullptr) *rcond = sensitivity.rcond();
    if (singular != nullptr) *singular = sensitivity.singular();
  } else {
    // Central differences of re-solved forward problems: 2k solves.
    forward_.constraints().Evaluate(s, u, &C);
    const State base = s;
    const Eigen::VectorXd u_base = u;
    const Eigen::VectorXd ue = EffectiveControls(u_base);
    const double h = options_.finite_difference_step;
    J->resize(e.size() + C.size(), k);
    ds_du->resize(base.tangent_size(), k);
    for (int c = 0; c < k; ++c) {
      Eigen::VectorXd r_side[2];
      State s_side[2];
      for (int side = 0; side < 2; ++side) {
        Eigen::VectorXd moved = ue;
        moved[c] += side == 0 ? h : -h;
        SolveAt(moved, base);
        Residuals(target, &r_side[side], nullptr, nullptr, nullptr, nullptr);
        s_side[side] = forward_.state();
      }
      J->col(c) = (r_side[0] - r_side[1]) / (2 * h);
      ds_du->col(c) = s_side[0].Minus(s_side[1]) / (2 * h);
    }
    forward_.Restore(base, u_base);
    if (rcond != nullptr) {
      *rcond = Sensitivity(forward_.constraints(), base, u_base, effective_, &hessian_solver_, &workspace_).rcond();
    }
    if (singular != nullptr) *singular = false;
  }
  r->resize(e.size() + C.size());
  *r << e, sqrt_lambda * C;
}

double ControlProblem::Objective(const PoseTarget& target, Eigen::VectorXd* gradient) {
  const State& s = forward_.state();
  const Eigen::VectorXd& u = forward_.controls();
  Eigen::VectorXd e;
  Eigen::MatrixXd de_ds;
  const bool implicit = options_.gradient == GradientMethod::kImplicit;
  error_.Evaluate(s, target, &e, gradient != nullptr && implicit ? &de_ds : nullptr);
  if (gradient == nullptr || !implicit) {
    const double O = 0.5 * e.squaredNorm() + options_.lambda * forward_.Energy();
    if (gradient != nullptr) {
      const State base = s;
      const Eigen::VectorXd u_base = u;
      const int k = static_cast<int>(effective_.size());
      const Eigen::VectorXd ue = EffectiveControls(u_base);
      const double h = options_.finite_difference_step;
      gradient->resize(k);
      for (int c = 0; c < k; ++c) {
        double O_side[2];
        for (int side = 0; side < 2; ++side) {
          Eigen::VectorXd moved = ue;
          moved[c] += side == 0 ? h : -h;
          SolveAt(moved, base);
          O_side[side] = Objective(target, nullptr);
        }
        (*gradient)[c] = (O_side[0] - O_side[1]) / (2 * h);
      }
      forward_.Restore(base, u_base);
    }
    return O;
  }
  // Adjoint: dO/du = lambda dE/du - (dG/du)^T (dG/ds)^-1 (de/ds^T e + lambda G).
  const Sensitivity sensitivity(forward_.constraints(), s, u, effective_, &hessian_solver_, &workspace_);
  const EnergyDerivatives& d = sensitivity.derivatives();
  const Eigen::VectorXd dO_ds = de_ds.transpose() * e + options_.lambda * d.G;
  *gradient = sensitivity.TotalDerivative(dO_ds, options_.lambda * sensitivity.ResidualEnergyGradient());
  return 0.5 * e.squaredNorm() + options_.lambda * d.energy;
}

Eigen::MatrixXd ControlProblem::StateSensitivity() {
  if (options_.gradient == GradientMethod::kImplicit) {
    return Sensitivity(forward_.constraints(), forward_.state(), forward_.controls(), effective_,
                       &hessian_solver_, &workspace_)
        .StateSensitivity();
  }
  Eigen::VectorXd r;
  Eigen::MatrixXd J, ds_du;
  Residuals(CurrentPose(), &r, &J, &ds_du, nullptr, nullptr);
  return ds_du;
}

ControlStepResult ControlProblem::SolveStep(const PoseTarget& target) {
  return options_.method == ControlMethod::kBfgs ? SolveStepBfgs(target) : SolveStepLm(target);
}

ControlStepResult ControlProblem::SolveStepLm(const PoseTarget& target) {
  const auto start = Clock::now();
  const int solves_before = forward_solves_;
  ControlStepResult result;
  Eigen::VectorXd ue = EffectiveControls(forward_.controls());

  Eigen::VectorXd r, r_new;
  Eigen::MatrixXd J, ds_du;
  bool singular = false;
  Residuals(target, &r, &J, &ds_du, &result.rcond, &singular);
  result.singular |= singular;
  double O = 0.5 * r.squaredNorm();
  const int ne = error_.size();
  auto manipulability = [&] {
    if (ne == 0) return 0.0;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J.topRows(ne));
    return svd.singularValues().minCoeff();
  };
  result.min_singular_value_dX_du = manipulability();
  auto report = [&](int iteration) {
    if (options_.on_iteration) {
      const double error = ne > 0 ? r.head(ne).lpNorm<Eigen::Infinity>() : 0.0;
      options_.on_iteration(iteration, Milliseconds(start), 0.5 * r.squaredNorm(), error);
    }
  };
  report(0);
  double mu = -1;
  for (int it = 0; it < options_.max_iterations; ++it) {
    const double error = ne > 0 ? r.head(ne).lpNorm<Eigen::Infinity>() : 0.0;
    if (error <= 0.1 * options_.target_tolerance && forward_.Energy() <= kEnergyFloor) break;
    // Damped least squares through the eigen-decomposition of J^T J (k x k,
    // k <= a few dozen): step = -V (S + mu)^-1 V^T J^T r. Among equivalent
    // steps (redundant controls) this is the one of least norm.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(J.transpose() * J);
    const Eigen::VectorXd sigma_sq = eig.eigenvalues().cwiseMax(0.0);
    const Eigen::VectorXd Vt_g = eig.eigenvectors().transpose() * (J.transpose() * r);
    if (mu < 0) mu = 1e-12 * std::max(sigma_sq.maxCoeff(), 1e-30);
    const State base = forward_.state();
    const Eigen::VectorXd u_base = forward_.controls();
    bool accepted = false, stationary = false;
    for (int trial = 0; trial < 16 && !accepted; ++trial) {
      const Eigen::VectorXd coeff = Vt_g.array() / (sigma_sq.array() + mu);
      const Eigen::VectorXd step = -eig.eigenvectors() * coeff;
      if (step.lpNorm<Eigen::Infinity>() <= 1e-15 * (1.0 + ue.lpNorm<Eigen::Infinity>())) {
        stationary = true;
        break;
      }
      // First-order predictor: start the forward solve at s + ds/du * step.
      State predicted = base;
      predicted.Plus(ds_du * step);
      if (SolveAt(ue + step, predicted)) {
        Residuals(target, &r_new, nullptr, nullptr, nullptr, nullptr);
        const double O_new = 0.5 * r_new.squaredNorm();
        if (O_new < O) {
          ue += step;
          O = O_new;
          mu = std::max(mu * 0.1, 1e-30);
          accepted = true;
          break;
        }
      }
      forward_.Restore(base, u_base);
      mu = mu * 10 + 1e-30;
    }
    ++result.iterations;
    if (!accepted || stationary) break;
    // Converged on the new residual? Then no new linearisation is needed
    // (rcond stays that of the last one, a step of ~1e-8 away).
    r = r_new;
    report(result.iterations);
    const double new_error = ne > 0 ? r.head(ne).lpNorm<Eigen::Infinity>() : 0.0;
    if (new_error <= 0.1 * options_.target_tolerance && forward_.Energy() <= kEnergyFloor) break;
    Residuals(target, &r, &J, &ds_du, &result.rcond, &singular);
    result.singular |= singular;
    result.min_singular_value_dX_du = manipulability();
  }
  result.forward_solves = forward_solves_ - solves_before;
  Finish(target, &result);
  result.time_ms = Milliseconds(start);
  return result;
}

ControlStepResult ControlProblem::SolveStepBfgs(const PoseTarget& target) {
  const auto start = Clock::now();
  const int solves_before = forward_solves_;
  ControlStepResult result;
  Eigen::VectorXd ue = EffectiveControls(forward_.controls());

  ceres::GradientProblemSolver::Options options;
  options.line_search_direction_type = ceres::BFGS;
  options.max_num_iterations = options_.max_iterations;
  options.function_tolerance = 1e-30;
  options.gradient_tolerance = 1e-30;
  options.parameter_tolerance = 1e-16;
  options.logging_type = ceres::SILENT;
  const double tolerance = 0.1 * options_.target_tolerance;
  TargetReached reached(
      std::min(0.5 * tolerance * tolerance, options_.lambda * kEnergyFloor),
      [&](const ceres::IterationSummary& summary) {
        if (!options_.on_iteration) return;
        Eigen::VectorXd e;  // the error at the last evaluated (accepted) point
        error_.Evaluate(forward_.state(), target, &e, nullptr);
        options_.on_iteration(summary.iteration, Milliseconds(start), summary.cost,
                              e.size() > 0 ? e.lpNorm<Eigen::Infinity>() : 0.0);
      });
  options.callbacks.push_back(&reached);
  ceres::GradientProblem problem(new BfgsObjective(this, target, ue));
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(options, problem, ue.data(), &summary);
  // The solver's last evaluation may be a rejected line-search point:
  // re-assemble at the returned controls from where we are.
  const State here = forward_.state();
  SolveAt(ue, here);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.forward_solves = forward_solves_ - solves_before;
  {
    Eigen::VectorXd r;
    Eigen::MatrixXd J, ds_du;
    Residuals(target, &r, &J, &ds_du, &result.rcond, &result.singular);
    if (error_.size() > 0) {
      result.min_singular_value_dX_du =
          Eigen::JacobiSVD<Eigen::MatrixXd>(J.topRows(error_.size())).singularValues().minCoeff();
    }
  }
  Finish(target, &result);
  result.time_ms = Milliseconds(start);
  return result;
}

void ControlProblem::Finish(const PoseTarget& target, ControlStepResult* result) {
  Eigen::VectorXd e;
  error_.Evaluate(forward_.state(), target, &e, nullptr);
  result->residual_energy = forward_.Energy();
  result->error = e.size() > 0 ? e.lpNorm<Eigen::Infinity>() : 0.0;
  result->objective = 0.5 * e.squaredNorm() + options_.lambda * result->residual_energy;
  result->assembled = result->residual_energy < forward_.options().assembly_tolerance;
  result->reached = result->assembled && result->error <= options_.target_tolerance;
}

ControlResult ControlProblem::MoveTo(
    const PoseTarget& target,
    const std::function<void(const PoseTarget&, const ControlStepResult&)>& on_step) {
  const auto start = Clock::now();
  const auto& controlled = forward_.model().end_effector.controlled;
  const PoseTarget from = CurrentPose();

  // Path length over the controlled components.
  double distance = 0;
  for (int k = 0; k < 3; ++k) {
    if (controlled[k]) distance += std::pow(target.position[k] - from.position[k], 2);
  }
  distance = std::sqrt(distance);
  const bool full_rotation = controlled[kRoll] && controlled[kPitch] && controlled[kYaw];
  const Eigen::Matrix3d R_from = RotationFromRpy(from.rpy);
  const Eigen::Vector3d phi =
      QuaternionLog(Eigen::Quaterniond(RotationFromRpy(target.rpy) * R_from.transpose()));
  Eigen::Vector3d angle_change = Eigen::Vector3d::Zero();
  double angle = full_rotation ? phi.norm() : 0.0;
  for (int k = 0; k < 3 && !full_rotation; ++k) {
    if (!controlled[3 + k]) continue;
    angle_change[k] = WrapAngle(target.rpy[k] - from.rpy[k]);
    angle = std::max(angle, std::abs(angle_change[k]));
  }
  const int steps = std::max(
      {1, static_cast<int>(std::ceil(distance / options_.max_step_m - 1e-9)),
       static_cast<int>(std::ceil(angle / options_.max_step_rad - 1e-9))});

  ControlResult result;
  result.min_rcond = std::numeric_limits<double>::infinity();
  ControlStepResult last;
  auto account = [&](const PoseTarget& step_target, const ControlStepResult& step) {
    ++result.steps;
    result.iterations += step.iterations;
    result.forward_solves += step.forward_solves;
    result.max_step_residual_energy = std::max(result.max_step_residual_energy, step.residual_energy);
    result.min_rcond = std::min(result.min_rcond, step.rcond);
    if (on_step) on_step(step_target, step);
    last = step;
  };
  for (int i = 1; i <= steps; ++i) {
    const double t = double(i) / steps;
    PoseTarget step_target = target;
    if (i < steps) {
      step_target.position = from.position + t * (target.position - from.position);
      step_target.rpy = full_rotation
                            ? RpyFromRotation(QuaternionExp(t * phi).toRotationMatrix() * R_from)
                            : Eigen::Vector3d(from.rpy + t * angle_change);
    }
    const ControlStepResult step = SolveStep(step_target);
    account(step_target, step);
    if (!step.reached) {
      result.warning = "path step " + std::to_string(i) + " of " + std::to_string(steps) +
                       " not reached (error " + std::to_string(step.error) +
                       ", residual energy " + std::to_string(step.residual_energy) +
                       (step.singular ? ", dG/ds singular" : "") +
                       "): the target may be outside the workspace or past a singularity";
      if (i < steps) account(target, SolveStep(target));  // best controls for the real target
      break;
    }
  }
  result.converged = last.reached && result.warning.empty();
  result.assembled = last.assembled;
  result.objective = last.objective;
  result.error = last.error;
  result.residual_energy = last.residual_energy;
  result.rcond = last.rcond;
  result.min_singular_value_dX_du = last.min_singular_value_dX_du;
  result.solve_time_ms = Milliseconds(start);
  return result;
}

}  // namespace ccma
