// The design loop behind `ccma design` (analyses/design.h): reach every
// target (Levenberg-Marquardt over the stacked errors), then raise the
// smallest sigma_min while every target stays reached.
#include "analyses/design.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "analyses/design_objective.h"
#include "analyses/work_estimate.h"
#include "ccma/internal/format.h"
#include "problems/internal/end_effector_error.h"

namespace ccma {

bool IsValidAsDesignCommand(const DesignOptions& options, std::string* why) {
  std::string message;
  if (options.IsValid(&message)) return true;
  if (why != nullptr) *why = RenameLeadingWord(message, {{"max_iterations", "design_iterations"}});
  return false;
}

bool DesignOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& m) {
    if (why != nullptr) *why = m;
    return false;
  };
  if (!control.IsValid(why)) return false;
  if (!(target_tolerance >= 1e-12 && target_tolerance <= 1)) return fail("target_tolerance must be in [1e-12, 1]");
  if (!(min_singular_value >= 0 && min_singular_value <= 100)) return fail("min_singular_value must be in [0, 100]");
  if (!(max_change > 0 && max_change <= 100)) return fail("max_change must be in (0, 100]");
  if (!(min_length > 0 && min_length <= 100)) return fail("min_length must be in (0, 100]");
  if (!(max_iterations >= 1 && max_iterations <= 1000)) return fail("max_iterations must be in [1, 1000]");
  if (!(noise.position_sigma >= 0 && noise.position_sigma <= 1 && noise.heading_sigma >= 0 &&
        noise.heading_sigma <= 1)) {
    return fail("the pose noise sigmas must be in [0, 1]");
  }
  return true;
}

namespace {

// Step of the central difference of sigma_min in p [m] (margin phase).
constexpr double kSigmaStep = 1e-4;
// Joint-limit violation still counted as respecting the limits [rad or m].
constexpr double kLimitSlack = 1e-9;

// One target solved on one design, with what the p step needs.
struct SolvedTarget {
  DesignTargetResult result;
  Eigen::VectorXd e;      // end-effector error (controlled components)
  Eigen::MatrixXd de_du;  // over the effective controls
  Eigen::MatrixXd de_ds;
  State s;
  Eigen::VectorXd u;
  bool usable = false;    // e, de_du valid
};

SolvedTarget SolveTarget(const Model& model, const PoseTarget& target, const DesignOptions& options,
                         bool linearize) {
  SolvedTarget out;
  ControlProblem problem(model, options.control);
  const ForwardResult home = problem.SetControls(model.home_controls());
  out.result.controls = model.home_controls();
  if (!home.assembled) return out;  // this design does not even assemble at home
  ControlResult r;
  try {
    r = problem.MoveTo(target);
  } catch (const std::invalid_argument&) {
    return out;
  }
  out.s = problem.forward().state();
  out.u = problem.controls();
  out.result.controls = out.u;
  out.result.error = r.error;
  out.result.min_singular_value = std::isfinite(r.min_singular_value_dX_du) ? r.min_singular_value_dX_du : 0;
  out.result.within_limits = r.max_limit_violation <= kLimitSlack;
  out.result.reached = r.assembled && std::isfinite(r.error) && r.error <= options.target_tolerance &&
                       out.result.within_limits;
  const EndEffectorError error(model);
  error.Evaluate(out.s, target, &out.e, linearize ? &out.de_ds : nullptr);
  out.usable = out.e.allFinite();
  if (linearize && out.usable) {
    const Eigen::MatrixXd ds_du = problem.StateSensitivity();
    out.de_du = out.de_ds * ds_du;
    out.usable = out.de_du.allFinite();
  }
  return out;
}

double SumSquaredError(const std::vector<SolvedTarget>& solved) {
  double f = 0;
  for (const SolvedTarget& t : solved) f += t.usable ? t.e.squaredNorm() : std::numeric_limits<double>::infinity();
  return f;
}

bool AllReached(const std::vector<SolvedTarget>& solved) {
  for (const SolvedTarget& t : solved) {
    if (!t.result.reached) return false;
  }
  return true;
}

double MinSigma(const std::vector<SolvedTarget>& solved) {
  double s = std::numeric_limits<double>::infinity();
  for (const SolvedTarget& t : solved) s = std::min(s, t.result.min_singular_value);
  return s;
}

// p clipped to the bounds: |p - p0| <= max_change, lengths >= min_length.
Eigen::VectorXd Clip(const DesignParameters& params, const Eigen::VectorXd& p0, const Eigen::VectorXd& p,
                     const DesignOptions& options) {
  Eigen::VectorXd q = p;
  for (int k = 0; k < q.size(); ++k) {
    q[k] = std::clamp(q[k], p0[k] - options.max_change, p0[k] + options.max_change);
    if (params.list[k].kind == DesignParameterKind::kLinkLength) q[k] = std::max(q[k], options.min_length);
  }
  return q;
}

std::vector<SolvedTarget> SolveAll(const Model& model, const DesignParameters& params, const Eigen::VectorXd& p,
                                   const std::vector<PoseTarget>& targets, const DesignOptions& options,
                                   bool linearize) {
  const Model at_p = ApplyParameters(model, params, p);
  std::vector<SolvedTarget> out;
  out.reserve(targets.size());
  for (const PoseTarget& t : targets) out.push_back(SolveTarget(at_p, t, options, linearize));
  return out;
}

std::vector<DesignTargetResult> Results(const std::vector<SolvedTarget>& solved) {
  std::vector<DesignTargetResult> r;
  for (const SolvedTarget& t : solved) r.push_back(t.result);
  return r;
}

}  // namespace

std::vector<DesignTargetResult> EvaluateTargets(const Model& model, const std::vector<PoseTarget>& targets,
                                                const DesignOptions& options) {
  std::vector<DesignTargetResult> r;
  for (const PoseTarget& t : targets) r.push_back(SolveTarget(model, t, options, false).result);
  return r;
}

namespace {

// What the two phases of Design share: the problem, the current design p
// and its solved targets.
struct DesignLoop {
  const Model& model;
  const DesignParameters& params;
  const std::vector<PoseTarget>& targets;
  const DesignOptions& options;
  Eigen::VectorXd p0, p;
  std::vector<SolvedTarget> solved;
  double f = 0;    // summed squared error of `solved`
  double mu = -1;  // LM damping, set from the first linearisation
};

// The stacked errors r of all targets and J = [blockdiag(de_t/du_t) | de_t/dp]
// over (u_1..u_T, p). False when dG/ds is singular at a target.
bool StackErrors(const DesignLoop& loop, Eigen::MatrixXd* J, Eigen::VectorXd* r) {
  const int P = loop.params.size();
  int rows = 0, cols = P;
  for (const SolvedTarget& t : loop.solved) {
    rows += static_cast<int>(t.e.size());
    cols += static_cast<int>(t.de_du.cols());
  }
  *J = Eigen::MatrixXd::Zero(rows, cols);
  r->resize(rows);
  int row = 0, col = 0;
  for (const SolvedTarget& t : loop.solved) {
    ParameterSensitivity sens;
    if (!ComputeParameterSensitivity(loop.model, loop.params, loop.p, t.s, t.u, &sens)) return false;
    const int m = static_cast<int>(t.e.size()), k = static_cast<int>(t.de_du.cols());
    J->block(row, col, m, k) = t.de_du;
    J->block(row, cols - P, m, P) = t.de_ds * sens.ds_dp;
    r->segment(row, m) = t.e;
    row += m;
    col += k;
  }
  return true;
}

// Levenberg-Marquardt on (J, r): raises the damping until a clipped step on
// p, with every target re-solved, lowers the summed squared error (then
// accepts it and returns true) or the damping runs out.
bool DampedStep(DesignLoop* loop, const Eigen::MatrixXd& J, const Eigen::VectorXd& r) {
  const int P = loop->params.size();
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  const Eigen::VectorXd Jtr = J.transpose() * r;
  if (loop->mu < 0) loop->mu = 1e-3 * std::max(JtJ.diagonal().maxCoeff(), 1e-12);
  while (loop->mu < 1e12) {
    Eigen::MatrixXd A = JtJ;
    A.diagonal().array() += loop->mu;
    const Eigen::VectorXd step = A.ldlt().solve(-Jtr);
    const Eigen::VectorXd p_trial = Clip(loop->params, loop->p0, loop->p + step.tail(P), loop->options);
    if ((p_trial - loop->p).norm() < 1e-14) {
      loop->mu *= 10;
      continue;
    }
    std::vector<SolvedTarget> trial =
        SolveAll(loop->model, loop->params, p_trial, loop->targets, loop->options, true);
    const double f_trial = SumSquaredError(trial);
    if (f_trial < loop->f) {
      loop->p = p_trial;
      loop->solved = std::move(trial);
      loop->f = f_trial;
      loop->mu = std::max(loop->mu / 3, 1e-12);
      return true;
    }
    loop->mu *= 10;
  }
  return false;
}

// Phase 1, one iteration: "" after an accepted step, else why it stopped.
std::string ReachStep(DesignLoop* loop) {
  for (const SolvedTarget& t : loop->solved) {
    if (!t.usable) return "a target could not be solved on the current design";
  }
  Eigen::MatrixXd J;
  Eigen::VectorXd r;
  if (!StackErrors(*loop, &J, &r)) return "dG/ds is singular at a target on the current design";
  if (!DampedStep(loop, J, r)) return "no design step reduces the target errors further (bounds or a local minimum)";
  return "";
}

// The gradient in p of the worst target's sigma_min, by central differences
// of the target re-solved on the perturbed designs.
Eigen::VectorXd SigmaGradient(const DesignLoop& loop, int worst) {
  const int P = loop.params.size();
  Eigen::VectorXd g(P);
  for (int k = 0; k < P; ++k) {
    Eigen::VectorXd pk = loop.p;
    pk[k] += kSigmaStep;
    const Model plus = ApplyParameters(loop.model, loop.params, pk);
    pk[k] -= 2 * kSigmaStep;
    const Model minus = ApplyParameters(loop.model, loop.params, pk);
    g[k] = (SolveTarget(plus, loop.targets[worst], loop.options, false).result.min_singular_value -
            SolveTarget(minus, loop.targets[worst], loop.options, false).result.min_singular_value) /
           (2 * kSigmaStep);
  }
  return g;
}

// Phase 2, one iteration: a Newton step on the smallest sigma_min toward 1.5
// times the threshold (at most 0.05 m, halved up to 6 times), accepted when
// every target stays reached and sigma_min rises. "" or why it stopped.
std::string MarginStep(DesignLoop* loop) {
  int worst = 0;
  for (int t = 1; t < static_cast<int>(loop->solved.size()); ++t) {
    if (loop->solved[t].result.min_singular_value < loop->solved[worst].result.min_singular_value) worst = t;
  }
  const Eigen::VectorXd g = SigmaGradient(*loop, worst);
  if (!(g.squaredNorm() > 0) || !g.allFinite()) {
    return "the margin cannot be raised (sigma_min does not change with the parameters)";
  }
  const double sigma = MinSigma(loop->solved);
  Eigen::VectorXd step = (1.5 * loop->options.min_singular_value - sigma) * g / g.squaredNorm();
  if (step.norm() > 0.05) step *= 0.05 / step.norm();
  for (int halving = 0; halving < 6; ++halving, step /= 2) {
    const Eigen::VectorXd p_trial = Clip(loop->params, loop->p0, loop->p + step, loop->options);
    std::vector<SolvedTarget> trial =
        SolveAll(loop->model, loop->params, p_trial, loop->targets, loop->options, true);
    if (AllReached(trial) && MinSigma(trial) > sigma) {
      loop->p = p_trial;
      loop->solved = std::move(trial);
      return "";
    }
  }
  return "no design step raises the smallest sigma_min while keeping every target reached";
}

// The worst objective value over the solved targets on design p (the
// smallest payload, the largest push or std), and which target it is at.
ObjectiveAtTarget WorstObjective(const DesignLoop& loop, const std::vector<SolvedTarget>& solved,
                                 const Eigen::VectorXd& p, int* worst) {
  const Model at_p = ApplyParameters(loop.model, loop.params, p);
  ObjectiveAtTarget out;
  const double sign = IsMaximised(loop.options.objective) ? -1.0 : 1.0;  // larger sign * value is worse
  for (int t = 0; t < static_cast<int>(solved.size()); ++t) {
    const ObjectiveAtTarget v =
        EvaluateObjective(loop.options.objective, at_p, solved[t].s, solved[t].u, loop.options.noise);
    if (!v.defined) return v;
    if (t == 0 || sign * v.value > sign * out.value) {
      out = v;
      if (worst != nullptr) *worst = t;
    }
  }
  return out;
}

// Phase 3, one iteration: a step of `*length` [m] along the objective's
// gradient at the worst target (halved up to 6 times), accepted when every
// target stays reached, sigma_min stays at or above the threshold and the
// worst value improves. "" or why it stopped.
std::string ObjectiveStep(DesignLoop* loop, double* length, ObjectiveAtTarget* current) {
  int worst = 0;
  *current = WorstObjective(*loop, loop->solved, loop->p, &worst);
  if (!current->defined) return current->why;
  Eigen::VectorXd g;
  std::string why;
  const SolvedTarget& t = loop->solved[worst];
  if (!ObjectiveGradient(loop->options.objective, loop->model, loop->params, loop->p, t.s, t.u, loop->options.noise,
                         &g, &why)) {
    return why;
  }
  if (!(g.norm() > 0)) return "the objective does not change with the parameters";
  const double sign = IsMaximised(loop->options.objective) ? 1.0 : -1.0;
  const double margin = std::min(loop->options.min_singular_value, MinSigma(loop->solved));
  for (int halving = 0; halving < 6; ++halving, *length /= 2) {
    const Eigen::VectorXd p_trial = Clip(loop->params, loop->p0, loop->p + sign * *length * g / g.norm(), loop->options);
    if ((p_trial - loop->p).norm() < 1e-12) continue;
    std::vector<SolvedTarget> trial = SolveAll(loop->model, loop->params, p_trial, loop->targets, loop->options, true);
    if (!AllReached(trial) || MinSigma(trial) < margin) continue;
    const ObjectiveAtTarget v = WorstObjective(*loop, trial, p_trial, nullptr);
    if (v.defined && sign * (v.value - current->value) > 1e-9 * (1 + std::abs(current->value))) {
      loop->p = p_trial;
      loop->solved = std::move(trial);
      *current = v;
      *length *= 1.5;
      return "";
    }
  }
  return "no design step improves the " + std::string(DesignObjectiveName(loop->options.objective)) +
         " objective further (a local optimum, the bounds or the margin)";
}

// Phase 3: the objective, while every target stays reached with margin.
void ImproveObjective(DesignLoop* loop, DesignResult* result) {
  WorkEstimate* estimate = loop->options.estimate;
  if (estimate != nullptr) {
    estimate->BeginStage("design iterations of the " + std::string(DesignObjectiveName(loop->options.objective)) +
                             " objective",
                         loop->options.max_iterations, 0, true);
  }
  result->objective_before = WorstObjective(*loop, loop->solved, loop->p, nullptr);
  result->objective_after = result->objective_before;
  double length = 0.02;
  for (int it = 0; it < loop->options.max_iterations; ++it) {
    ObjectiveAtTarget current;
    result->objective_message = ObjectiveStep(loop, &length, &current);
    if (estimate != nullptr) estimate->Update(it + 1);
    if (!result->objective_message.empty()) break;
    result->objective_after = current;
    result->objective_iterations = it + 1;
  }
}

}  // namespace

int MaxDesignIterations(const DesignOptions& options) {
  return options.objective == DesignObjective::kReach ? options.max_iterations : 2 * options.max_iterations;
}

DesignResult Design(const Model& model, const DesignParameters& params, const std::vector<PoseTarget>& targets,
                    const DesignOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("design options: " + why);
  if (params.size() == 0) throw std::invalid_argument("design: no parameters to vary");
  if (targets.empty()) throw std::invalid_argument("design: no targets");
  DesignLoop loop{model, params, targets, options, {}, {}, {}};
  loop.p0 = ParameterValues(model, params);
  loop.p = loop.p0;
  loop.solved = SolveAll(model, params, loop.p, targets, options, true);
  loop.f = SumSquaredError(loop.solved);
  DesignResult result;
  result.p0 = loop.p0;
  result.initial = Results(loop.solved);
  int it = 0;
  const auto counted = [&options](int done) {
    if (options.estimate != nullptr) options.estimate->Update(done);
  };
  for (; it < options.max_iterations && !AllReached(loop.solved); ++it) {  // phase 1: reach every target
    result.message = ReachStep(&loop);
    counted(it + 1);
    if (!result.message.empty()) break;
  }
  for (; it < options.max_iterations && AllReached(loop.solved) &&  // phase 2: margin
         MinSigma(loop.solved) < options.min_singular_value;
       ++it) {
    result.message = MarginStep(&loop);
    counted(it + 1);
    if (!result.message.empty()) break;
  }
  result.converged = AllReached(loop.solved) && MinSigma(loop.solved) >= options.min_singular_value;
  if (result.converged && options.objective != DesignObjective::kReach) ImproveObjective(&loop, &result);
  result.p = loop.p;
  result.iterations = it;
  result.final = Results(loop.solved);
  if (result.converged) {
    result.message.clear();
  } else if (result.message.empty()) {
    result.message = AllReached(loop.solved) ? "every target reached but sigma_min stays below the threshold"
                                             : "iteration limit reached before every target was reachable";
  }
  return result;
}

}  // namespace ccma
