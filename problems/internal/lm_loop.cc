#include "problems/internal/lm_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "ccma/internal/dense_factorizations.h"
#include "problems/internal/constrained_lm_step.h"
#include "ccma/internal/elapsed.h"
#include "problems/internal/control_workspace.h"
#include "problems/internal/large_lm_system.h"
#include "problems/internal/null_space_step.h"

namespace ccma {
namespace {

using Clock = std::chrono::steady_clock;

// Largest eigenvalue of J^T J: from the eigen-decomposition when there is
// one, else by power iteration (seeded start, 30 products: a damping scale,
// a few digits suffice).
double LargestEigenvalue(const Eigen::MatrixXd& JtJ, const SymmetricEigenSolver* eig) {
  if (JtJ.rows() == 0) return 0.0;
  if (eig != nullptr) return eig->eigenvalues().cwiseMax(0.0).maxCoeff();
  Eigen::VectorXd v = Eigen::VectorXd::Ones(JtJ.rows()) / std::sqrt(double(JtJ.rows()));
  double largest = 0;
  for (int it = 0; it < 30; ++it) {
    const Eigen::VectorXd w = JtJ * v;
    largest = v.dot(w);
    const double norm = w.norm();
    if (!(norm > 0)) break;
    v = w / norm;
  }
  return std::max(largest, 0.0);
}

// The unconstrained damped step: by the large system when there is one (its
// failure falls back to the dense matrix), else ConstrainedLmStep's.
Eigen::VectorXd UnconstrainedStep(const ControlLinearization& lin, double mu) {
  Eigen::VectorXd step;
  if (lin.large && lin.large->Step(mu, &step)) return step;
  return ConstrainedLmStep(lin.DenseJtJ(), lin.Jtr, mu, LinearConstraints{}, lin.eigen());
}

// The linearisation's rcond, singularity and sigma, into a step's result.
void Note(const ControlLinearization& lin, ControlStepResult* result) {
  result->rcond = lin.rcond;
  result->singular |= lin.singular;
  result->min_singular_value_dX_du = SmallestSingularValueOf(lin.J_e);
}

}  // namespace

bool LmLoop::StepConstraintsHold() const {
  const StepConstraints& constraints = p_.workspace_->step_constraints;
  return constraints.empty() || constraints.Hold(p_.forward_.controls(), p_.forward_.state(), 1e-10);
}

ControlStepResult LmLoop::SolveStep(const PoseTarget& target) {
  StepConstraints& step_constraints = p_.workspace_->step_constraints;
  if (!step_constraints.empty()) {
    step_constraints.Begin(p_.forward_.controls(), p_.forward_.state());
  }
  return SolveBegunStep(target, /*project_first=*/false);
}

ControlStepResult LmLoop::SolveStepFrom(const PoseTarget& target, const Eigen::VectorXd& u0,
                                        const State& s0) {
  StepConstraints& step_constraints = p_.workspace_->step_constraints;
  if (!step_constraints.empty()) step_constraints.Begin(u0, s0);
  return SolveBegunStep(target, /*project_first=*/true);
}

ControlStepResult LmLoop::SolveBegunStep(const PoseTarget& target, bool project_first) {
  const auto start = Clock::now();
  const int solves_before = p_.forward_solves_;
  ControlStepResult result;
  const StepConstraints& step_constraints = p_.workspace_->step_constraints;
  p_.workspace_->active = step_constraints.NoneActive();
  // A start below a floor (SolveStepFrom): back onto the constraints first,
  // so that the descent starts where they hold (its objective cannot
  // decrease on the way there when the start is on target).
  if (project_first && !StepConstraintsHold()) ProjectOntoStepConstraints(&result);
  const bool reached = ConvergeTask(target, &result, /*report_iterations=*/true);
  if (!StepConstraintsHold()) ProjectOntoStepConstraints(&result);
  // Redundancy resolution once the task holds (see ControlOptions::Secondary).
  const ControlOptions::Secondary& secondary = p_.options_.secondary;
  if (secondary.enabled() && reached && step_constraints.empty()) {
    NullSpaceStep null_space(&p_);
    for (int it = 0; it < secondary.iterations; ++it) {
      if (!null_space.Iterate(target, &result)) break;
      ++result.null_space_steps;
    }
  }
  if (secondary.enabled()) result.secondary_objective = p_.SecondaryObjective(target);
  result.forward_solves = p_.forward_solves_ - solves_before;
  p_.Finish(target, &result);
  result.time_ms = MillisecondsSince(start);
  return result;
}

bool LmLoop::ConvergeTask(const PoseTarget& target, ControlStepResult* result, bool report_iterations) {
  const auto start = Clock::now();
  const ControlOptions& options = p_.options_;
  const int ne = p_.workspace_->error.size();
  ControlLinearization lin;
  p_.Linearize(target, &lin);
  Eigen::VectorXd r = lin.r;
  Note(lin, result);
  double O = 0.5 * r.squaredNorm();
  auto error_of = [&] { return ne > 0 ? r.head(ne).lpNorm<Eigen::Infinity>() : 0.0; };
  auto done = [&] {
    return error_of() <= 0.1 * options.target_tolerance && p_.forward_.Energy() <= kEnergyFloor &&
           StepConstraintsHold();
  };
  auto report = [&](int iteration) {
    if (options.on_iteration && report_iterations) options.on_iteration(iteration, MillisecondsSince(start), O, error_of());
  };
  report(0);
  double mu = -1;
  for (int it = 0; it < options.max_iterations && !done(); ++it) {
    const bool accepted = Iteration(target, lin, &O, &mu, &r, result);
    ++result->iterations;
    if (!accepted) break;
    report(result->iterations);
    // Converged on the new residual? Then no new linearisation is needed
    // (rcond stays that of the last one, a step of ~1e-8 away).
    if (done()) break;
    p_.Linearize(target, &lin);
    r = lin.r;
    Note(lin, result);
  }
  return error_of() <= options.target_tolerance;
}

bool LmLoop::Iteration(const PoseTarget& target, const ControlLinearization& lin, double* O, double* mu,
                       Eigen::VectorXd* r, ControlStepResult* result) {
  // Damped least squares (least norm among equivalent steps: the bases move
  // as little as possible), under the step constraints when there are any.
  if (*mu < 0) {
    const double largest = lin.large ? lin.large->LargestEigenvalueBound() : LargestEigenvalue(lin.JtJ, lin.eigen());
    *mu = 1e-12 * std::max(largest, 1e-30);
  }
  ForwardProblem& forward = p_.forward_;
  const State base = forward.state();
  const Eigen::VectorXd u_base = forward.controls();
  const Eigen::VectorXd ue = p_.EffectiveControls(u_base);
  const ForwardOptions& fo = forward.options();
  const StepConstraints& step_constraints = p_.workspace_->step_constraints;
  for (int trial = 0; trial < 16; ++trial) {
    ActiveSet active = step_constraints.NoneActive();
    const Eigen::VectorXd step = Step(lin, *mu, &active);
    if (step.lpNorm<Eigen::Infinity>() <= 1e-15 * (1.0 + ue.lpNorm<Eigen::Infinity>())) return false;
    // First-order predictor: start the forward solve at s + ds/du * step.
    const Eigen::VectorXd ds_predicted = p_.PredictedStateChange(lin, step);
    State predicted = base;
    predicted.Plus(ds_predicted);
    if (p_.SolveAt(ue + step, predicted)) {
      const double deviation = forward.state().Minus(predicted).lpNorm<Eigen::Infinity>();
      const bool jumped = deviation > fo.branch_jump_relative * ds_predicted.lpNorm<Eigen::Infinity>() +
                                          fo.branch_jump_absolute;
      const Eigen::VectorXd r_new = p_.Residuals(target);
      const double O_new = 0.5 * r_new.squaredNorm();
      result->branch_jumps_rejected += jumped;
      // Limits hold to first order; allow the second-order slack, removed by
      // the next iterations (Newton on the active bounds).
      const bool within =
          step_constraints.empty() || step_constraints.WithinTrialSlack(forward.controls(), forward.state());
      if (!jumped && within && O_new < *O) {
        *O = O_new;
        *r = r_new;
        *mu = std::max(*mu * 0.1, 1e-30);
        p_.workspace_->active = active;
        return true;
      }
    }
    forward.Restore(base, u_base);
    *mu = *mu * 10 + 1e-30;
  }
  return false;
}

Eigen::VectorXd LmLoop::Step(const ControlLinearization& lin, double mu, ActiveSet* active) const {
  const StepConstraints& constraints = p_.workspace_->step_constraints;
  if (constraints.empty()) return UnconstrainedStep(lin, mu);
  // Active set: hold every item that the step would push past a bound at
  // that bound, until no other item would cross (at most one pass per item).
  *active = constraints.NoneActive();
  const State& s = p_.forward_.state();
  const Eigen::VectorXd& u = p_.forward_.controls();
  Eigen::VectorXd step;
  // ds/du as formed, or through the linearisation's factorisation.
  const SensitivityView ds_du = lin.ds_du.size() > 0 ? SensitivityView(lin.ds_du)
                                                     : SensitivityView(*lin.sensitivity, static_cast<int>(lin.Jtr.size()));
  for (int pass = 0; pass <= constraints.max_passes(); ++pass) {
    const LinearConstraints rows = constraints.Linearize(u, s, ds_du, *active);
    step = rows.rows() == 0 ? UnconstrainedStep(lin, mu) : ConstrainedLmStep(lin.DenseJtJ(), lin.Jtr, mu, rows, lin.eigen());
    if (!constraints.Grow(u, s, ds_du, step, active)) break;
  }
  return step;
}

void LmLoop::ProjectOntoStepConstraints(ControlStepResult* result) {
  const StepConstraints& constraints = p_.workspace_->step_constraints;
  if (constraints.empty()) return;
  ForwardProblem& forward = p_.forward_;
  // Items once held stay held: releasing one that sits at its bound would
  // let the next Newton step push it past (two pairs at the margin round
  // one base), and the projection would only converge linearly.
  ActiveSet held = p_.workspace_->active;
  for (int it = 0; it < 8; ++it) {
    if (StepConstraintsHold()) break;
    const Eigen::MatrixXd ds_du = p_.StateSensitivity();
    held = constraints.AtOrBeyond(forward.controls(), forward.state(), held);
    const LinearConstraints rows = constraints.Linearize(forward.controls(), forward.state(), ds_du, held);
    const Eigen::MatrixXd none = Eigen::MatrixXd::Zero(ds_du.cols(), ds_du.cols());
    const Eigen::VectorXd d = ConstrainedLmStep(none, Eigen::VectorXd::Zero(ds_du.cols()), 1.0, rows);
    State predicted = forward.state();
    predicted.Plus(ds_du * d);
    p_.SolveAt(p_.EffectiveControls(forward.controls()) + d, predicted);
    ++result->iterations;
  }
}

}  // namespace ccma
