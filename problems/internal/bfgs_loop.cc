#include "problems/internal/bfgs_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <utility>

#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <ceres/iteration_callback.h>

#include "problems/internal/control_linearization.h"
#include "ccma/internal/elapsed.h"
#include "problems/internal/control_workspace.h"

namespace ccma {

// Trial controls farther than this from a step's start (max-norm, m or rad)
// are refused, so the line search backtracks instead of jumping the
// mechanism onto another assembly branch. A paper step moves bases ~1 cm.
constexpr double kMaxControlChangePerStep = 0.05;

// ceres::GradientProblemSolver's view of O(u_eff). Every evaluation starts
// the forward solve from the step's starting state plus the first-order
// predictor ds/du (u - u_start): O(u) is then a function of u alone, not of
// the order in which the line search visits points (a far trial point would
// otherwise drag later ones onto another branch).
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

namespace {

using Clock = std::chrono::steady_clock;

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

ceres::GradientProblemSolver::Options BfgsOptions(int max_iterations) {
  ceres::GradientProblemSolver::Options options;
  options.line_search_direction_type = ceres::BFGS;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-30;
  options.gradient_tolerance = 1e-30;
  options.parameter_tolerance = 1e-16;
  options.logging_type = ceres::SILENT;
  return options;
}

}  // namespace

ControlStepResult BfgsLoop::SolveStep(const PoseTarget& target) {
  const auto start = Clock::now();
  const int solves_before = p_.forward_solves_;
  const ControlOptions& control = p_.options_;
  ControlStepResult result;
  Eigen::VectorXd ue = p_.EffectiveControls(p_.forward_.controls());
  ceres::GradientProblemSolver::Options options = BfgsOptions(control.max_iterations);
  const double tolerance = 0.1 * control.target_tolerance;
  TargetReached reached(std::min(0.5 * tolerance * tolerance, control.lambda * kEnergyFloor),
                        [&](const ceres::IterationSummary& summary) {
                          if (!control.on_iteration) return;
                          Eigen::VectorXd e;  // the error at the last evaluated (accepted) point
                          p_.workspace_->error.Evaluate(p_.forward_.state(), target, &e, nullptr);
                          control.on_iteration(summary.iteration, MillisecondsSince(start), summary.cost,
                                               e.size() > 0 ? e.lpNorm<Eigen::Infinity>() : 0.0);
                        });
  options.callbacks.push_back(&reached);
  ceres::GradientProblem problem(new BfgsObjective(&p_, target, ue));
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(options, problem, ue.data(), &summary);
  // The solver's last evaluation may be a rejected line-search point:
  // re-assemble at the returned controls from where we are.
  const State here = p_.forward_.state();
  p_.SolveAt(ue, here);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.forward_solves = p_.forward_solves_ - solves_before;
  ControlLinearization lin;
  p_.Linearize(target, &lin);
  result.rcond = lin.rcond;
  result.singular = lin.singular;
  result.min_singular_value_dX_du = SmallestSingularValueOf(lin.J_e);
  p_.Finish(target, &result);
  result.time_ms = MillisecondsSince(start);
  return result;
}

}  // namespace ccma
