#include "problems/internal/trajectory_planner.h"

#include <algorithm>
#include <cmath>

#include "problems/internal/control_linearization.h"
#include "problems/internal/control_workspace.h"
#include "problems/internal/sensitivity_view.h"

namespace ccma {
namespace {

// Rows within this distance [m or rad] of a bound enter a plan's
// linearisation; a trial that crosses a row left out is rejected.
constexpr double kWatch = 0.1;
// Largest change [m or rad] of any control in one iteration: a trust
// region well below any shape's size, so that no step jumps through an
// obstacle between two iterations (each iteration's steps are checked).
constexpr double kMaxChange = 0.02;
// A trial step whose residual energy exceeds this [m^2] (1 mm of constraint
// residual) has left the assembly manifold: rejected.
constexpr double kMaxTrialEnergy = 1e-6;

}  // namespace

TrajectoryPlanner::TrajectoryPlanner(ControlProblem* problem, const PlanOptions& options)
    : p_(*problem), options_(options) {
  const int num_bases = p_.forward_.model().num_bases();
  for (size_t c = 0; c < p_.effective_.size(); ++c) {
    const int u = p_.effective_[c];
    if (u < 3 * num_bases && u % 3 != 2) base_columns_.push_back(static_cast<int>(c));
  }
}

Eigen::VectorXd TrajectoryPlanner::BaseResiduals(const std::vector<PlannedStep>& steps,
                                                 Eigen::SparseMatrix<double>* J) const {
  const int n = static_cast<int>(steps.size()), m = static_cast<int>(p_.effective_.size());
  const int per_column = 2 * n - 1;
  Eigen::VectorXd r(per_column * static_cast<int>(base_columns_.size()));
  std::vector<Eigen::Triplet<double>> triplets;
  const double ws = std::sqrt(options_.smoothness_weight), wt = std::sqrt(options_.travel_weight);
  int row = 0;
  for (int c : base_columns_) {
    const int u = p_.effective_[static_cast<size_t>(c)];
    auto x = [&](int k) { return k == 0 ? u0_effective_[c] : steps[static_cast<size_t>(k - 1)].u[u]; };
    auto add = [&](int k, double value) {  // d x_k (k >= 1) enters with `value`
      if (k >= 1) triplets.emplace_back(row, (k - 1) * m + c, value);
    };
    for (int k = 1; k <= n; ++k, ++row) {  // travel
      r[row] = wt * (x(k) - x(k - 1));
      add(k, wt), add(k - 1, -wt);
    }
    for (int k = 1; k < n; ++k, ++row) {  // smoothness
      r[row] = ws * (x(k + 1) - 2 * x(k) + x(k - 1));
      add(k + 1, ws), add(k, -2 * ws), add(k - 1, ws);
    }
  }
  J->resize(r.size(), static_cast<Eigen::Index>(n) * m);
  J->setFromTriplets(triplets.begin(), triplets.end());
  return r;
}

double TrajectoryPlanner::Objective(const std::vector<PlannedStep>& steps) const {
  double f = 0;
  Eigen::VectorXd e;
  for (const PlannedStep& step : steps) {
    p_.workspace_->error.Evaluate(step.s, step.target, &e, nullptr);
    const double w = step.waypoint ? options_.waypoint_weight : options_.path_weight;
    f += 0.5 * w * e.squaredNorm() + p_.options_.lambda * step.energy;
  }
  Eigen::SparseMatrix<double> J;
  return f + 0.5 * BaseResiduals(steps, &J).squaredNorm();
}

void TrajectoryPlanner::AddBaseTerms(const std::vector<PlannedStep>& steps, PlanSystem* system) const {
  Eigen::SparseMatrix<double> J;
  const Eigen::VectorXd r = BaseResiduals(steps, &J);
  const Eigen::SparseMatrix<double> JtJ = (J.transpose() * J).pruned();
  system->H += JtJ;
  system->g += J.transpose() * r;
}

PlanSystem TrajectoryPlanner::Linearize(const Eigen::VectorXd& u0, const State& s0,
                                        const std::vector<PlannedStep>& steps) {
  const int m = static_cast<int>(p_.effective_.size()), n = static_cast<int>(steps.size());
  PlanSystem system;
  system.controls = m;
  system.steps = n;
  system.g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n) * m);
  std::vector<Eigen::Triplet<double>> triplets;
  StepConstraints& constraints = p_.workspace_->step_constraints;
  ControlLinearization lin;
  for (int k = 0; k < n; ++k) {
    const PlannedStep& step = steps[static_cast<size_t>(k)];
    p_.forward_.Restore(step.s, step.u);
    p_.Linearize(step.target, &lin);
    // Weight w_k on the end-effector part only: J^T J = J_e^T J_e + lambda (constraint part).
    const int ne = static_cast<int>(lin.J_e.rows());
    const double w = step.waypoint ? options_.waypoint_weight : options_.path_weight;
    const Eigen::MatrixXd JeJe = lin.J_e.transpose() * lin.J_e;
    const Eigen::MatrixXd H = lin.DenseJtJ() + (w - 1.0) * JeJe;
    system.g.segment(static_cast<Eigen::Index>(k) * m, m) =
        lin.Jtr + (w - 1.0) * lin.J_e.transpose() * lin.r.head(ne);
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < m; ++j) {
        if (H(i, j) != 0) triplets.emplace_back(k * m + i, k * m + j, H(i, j));
      }
    }
    if (constraints.empty()) continue;
    const SensitivityView ds_du = lin.ds_du.size() > 0 ? SensitivityView(lin.ds_du) : SensitivityView(*lin.sensitivity, m);
    constraints.Begin(k == 0 ? u0 : steps[static_cast<size_t>(k - 1)].u, k == 0 ? s0 : steps[static_cast<size_t>(k - 1)].s);
    for (InequalityRow& row : constraints.Inequalities(step.u, step.s, ds_du, kWatch)) {
      system.rows.push_back({k, std::move(row)});
    }
  }
  system.H.resize(static_cast<Eigen::Index>(n) * m, static_cast<Eigen::Index>(n) * m);
  system.H.setFromTriplets(triplets.begin(), triplets.end());
  AddBaseTerms(steps, &system);
  return system;
}

bool TrajectoryPlanner::Trial(const Eigen::VectorXd& u0, const State& s0, const Eigen::VectorXd& d,
                              const std::vector<PlannedStep>& steps, std::vector<PlannedStep>* out) {
  const int m = static_cast<int>(p_.effective_.size());
  std::vector<PlannedStep>& next = *out;
  next = steps;
  StepConstraints& constraints = p_.workspace_->step_constraints;
  for (size_t k = 0; k < next.size(); ++k) {
    PlannedStep& step = next[k];
    p_.forward_.Restore(step.s, step.u);
    const Eigen::VectorXd ue = p_.EffectiveControls(step.u) + d.segment(static_cast<Eigen::Index>(k) * m, m);
    // Not assembled exactly: lambda E is part of the objective, which the
    // next iterations drive down (as in a control step).
    if (!p_.SolveAt(ue, step.s) || !(p_.forward_.Energy() < kMaxTrialEnergy)) return false;
    step.u = p_.forward_.controls();
    step.s = p_.forward_.state();
    step.energy = p_.forward_.Energy();
    if (constraints.empty()) continue;
    constraints.Begin(k == 0 ? u0 : next[k - 1].u, k == 0 ? s0 : next[k - 1].s);
    if (!constraints.WithinTrialSlack(step.u, step.s)) return false;
  }
  return true;
}

int TrajectoryPlanner::Optimize(const Eigen::VectorXd& u0, const State& s0,
                                std::vector<PlannedStep>* steps,
                                const std::function<bool(int)>& keep_going,
                                std::string* stopped_by) {
  u0_effective_ = p_.EffectiveControls(u0);
  double f = Objective(*steps), mu = -1;
  *stopped_by = "plan_iterations";
  for (int iterations = 0; iterations < options_.max_iterations; ++iterations) {
    if (keep_going && !keep_going(iterations)) {
      *stopped_by = "plan_time_s";
      return iterations;
    }
    const PlanSystem system = Linearize(u0, s0, *steps);
    if (mu < 0) {
      double largest = 0;
      for (int i = 0; i < system.H.outerSize(); ++i) largest = std::max(largest, system.H.coeff(i, i));
      mu = 1e-8 * std::max(largest, 1e-30);
    }
    bool accepted = false;
    for (int trial = 0; trial < 16 && !accepted; ++trial) {
      Eigen::VectorXd d;
      std::vector<PlannedStep> next;
      const bool solved = SolvePlanSystem(system, mu, kMaxChange, 200, &d);
      if (solved && d.lpNorm<Eigen::Infinity>() > 1e-14 && Trial(u0, s0, d, *steps, &next)) {
        const double f_new = Objective(next);
        if (f_new < f) {
          accepted = true;
          *steps = std::move(next);
          const double decrease = f - f_new;
          f = f_new;
          mu = std::max(mu * 0.1, 1e-30);
          if (decrease <= 1e-14 * (1.0 + f)) {
            *stopped_by = "converged";
            return iterations + 1;
          }
          continue;
        }
      }
      mu = mu * 10 + 1e-30;
    }
    if (!accepted) {
      *stopped_by = "converged";
      return iterations;
    }
  }
  return options_.max_iterations;
}

}  // namespace ccma
