// ControlProblem: the objective O(u), its Gauss-Newton linearisation and
// the public entry points. The outer loops, the null-space secondary
// objectives and the differential turning are their own files in
// problems/internal/ (lm_loop, bfgs_loop, null_space_step,
// secondary_objective, differential_turning); ControlOptions::IsValid is in
// control_options.cc.
#include "problems/control_problem.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "ccma/internal/constraint_set.h"
#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "problems/internal/bfgs_loop.h"
#include "problems/internal/constrained_lm_step.h"
#include "problems/internal/control_linearization.h"
#include "problems/internal/control_workspace.h"
#include "problems/internal/differential_turning.h"
#include "problems/internal/finite_differences.h"
#include "problems/internal/idle_motions.h"
#include "problems/internal/large_lm_system.h"
#include "problems/internal/lm_loop.h"
#include "problems/internal/path_tally.h"
#include "problems/internal/pivot_ratio.h"
#include "problems/internal/secondary_objective.h"
#include "problems/internal/sensitivity.h"
#include "problems/internal/singularity.h"
#include "problems/path.h"

namespace ccma {
namespace {

ForwardOptions ValidatedForwardOptions(const ControlOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("ControlOptions: " + why);
  return options.forward;
}

// de/ds S, S^T G and B^T S (S = ds/du): by sparse forward substitution, or
// from S itself when `dense` (the step constraints read ds/du) or the sparse
// path declines; lin->ds_du is S then, else empty.
Sensitivity::Products SensitivityProducts(const Sensitivity& sensitivity, const Eigen::MatrixXd& de_ds,
                                          const std::vector<int>& effective, bool dense, ControlLinearization* lin) {
  const EnergyDerivatives& d = sensitivity.derivatives();
  const int k = static_cast<int>(effective.size());
  Sensitivity::Products products;
  lin->ds_du.resize(0, 0);
  if (dense || !sensitivity.ImplicitProducts(de_ds, d.G, &products)) {
    lin->ds_du = sensitivity.StateSensitivity();
    const Eigen::MatrixXd& S = lin->ds_du;
    products.FS.noalias() = de_ds * S;
    products.Stv.noalias() = S.transpose() * d.G;
    products.BtS.setZero(k, k);
    for (int c = 0; c < k; ++c) {
      for (SparseColMajor::InnerIterator it(d.dG_du, effective[c]); it; ++it) {
        products.BtS.row(c) += it.value() * S.row(it.row());
      }
    }
  }
  return products;
}

void ImplicitGaussNewton(const Sensitivity& sensitivity, const Eigen::VectorXd& e, const Eigen::MatrixXd& de_ds,
                         const std::vector<int>& effective, const std::vector<int>& column, double lambda,
                         bool dense, ControlLinearization* lin) {
  // The LM model of O(u) = 1/2 |e|^2 + lambda E_r(u), E_r(u) = E(s_hat(u), u):
  //   Gauss-Newton on e:  J_e = de/ds S,  S = ds/du = -H^-1 B,  B = dG/du;
  //   exact on E_r: its Hessian is the Schur complement of the full
  //   d2E/d(s, u)2 onto the controls, J_u^T J_u + B^T S (B^T S = -B^T H^-1 B),
  //   and its gradient is S^T G + dE/du (= dE/du at a solution, G = 0).
  // (Gauss-Newton on the constraint rows, (J_s S + J_u)^T (J_s S + J_u),
  // would differ by S^T (J_s^T J_s - H) S = O(|C|): it needs S as a dense
  // n x k matrix, this does not.) Without step constraints S is never
  // formed: B^T S, de/ds S and S^T G come from sparse forward substitution
  // (Sensitivity::ImplicitProducts) and the LM trials predict with one solve.
  const EnergyDerivatives& d = sensitivity.derivatives();
  const int k = static_cast<int>(effective.size());
  const Sensitivity::Products products = SensitivityProducts(sensitivity, de_ds, effective, dense, lin);
  lin->J_e = products.FS;
  // J_u^T J_u + B^T S over the effective controls (B^T S = -B^T H^-1 B is symmetric).
  Eigen::MatrixXd C_part = 0.5 * (products.BtS + products.BtS.transpose());
  for (int row = 0; row < d.J_u.outerSize(); ++row) {
    for (SparseRowMajor::InnerIterator a(d.J_u, row); a; ++a) {
      if (column[a.col()] < 0) continue;
      for (SparseRowMajor::InnerIterator b(d.J_u, row); b; ++b) {
        if (column[b.col()] >= 0) C_part(column[a.col()], column[b.col()]) += a.value() * b.value();
      }
    }
  }
  lin->JtJ.noalias() = lin->J_e.transpose() * lin->J_e;
  lin->JtJ += lambda * C_part;
  lin->Jtr.noalias() = lin->J_e.transpose() * e;
  Eigen::VectorXd constraint_part = products.Stv;
  for (int c = 0; c < k; ++c) constraint_part[c] += d.dE_du[effective[c]];
  lin->Jtr += lambda * constraint_part;
}

}  // namespace

ControlProblem::ControlProblem(const Model& model, const ControlOptions& options)
    : options_(options),
      forward_(model, ValidatedForwardOptions(options)),
      effective_(model.effective_control_indices()),
      workspace_(std::make_unique<Workspace>(model, forward_.constraints(), effective_)),
      travel_origin_(forward_.controls()) {}

ControlProblem::~ControlProblem() = default;

ForwardResult ControlProblem::SetControls(const Eigen::VectorXd& u) {
  travel_origin_ = u;
  return forward_.Assemble(u);
}

bool ControlProblem::correctable() const {
  return !workspace_->step_constraints.has_equalities() && !options_.secondary.enabled();
}

bool ControlProblem::CorrectTo(const Eigen::VectorXd& u) {
  const StepConstraints& constraints = workspace_->step_constraints;
  if (!correctable() || u.size() != forward_.controls().size()) return false;
  const State s0 = forward_.state();
  const Eigen::VectorXd u0 = forward_.controls();
  const ForwardResult r = forward_.Assemble(u);
  if (r.assembled && (constraints.empty() || constraints.Hold(u, forward_.state(), 1e-9))) return true;
  forward_.Restore(s0, u0);
  return false;
}

PoseTarget ControlProblem::CurrentPose() const {
  const EndEffectorPose pose = forward_.end_effector();
  return {pose.position, pose.rpy};
}

void ControlProblem::CheckTarget(const PoseTarget& target) const {
  for (int i = 0; i < 6; ++i) {
    const double v = i < 3 ? target.position[i] : target.rpy[i - 3];
    if (!(std::abs(v) <= kMaxMagnitude)) {
      throw std::invalid_argument(std::string("target: ") + kEndEffectorComponentNames[i] + " (" + FormatG(v) +
                                  ") must be a finite number in [-" + FormatG(kMaxMagnitude) + ", " +
                                  FormatG(kMaxMagnitude) + "] (m or rad)");
    }
  }
}

Eigen::VectorXd ControlProblem::EffectiveControls(const Eigen::VectorXd& u) const {
  Eigen::VectorXd ue(static_cast<Eigen::Index>(effective_.size()));
  for (size_t c = 0; c < effective_.size(); ++c) ue[c] = u[effective_[c]];
  return ue;
}

bool ControlProblem::SolveAt(const Eigen::VectorXd& ue, const State& start) {
  if (!ue.allFinite() || ue.lpNorm<Eigen::Infinity>() > kMaxMagnitude) return false;
  Eigen::VectorXd u = forward_.controls();
  for (size_t c = 0; c < effective_.size(); ++c) u[effective_[c]] = ue[c];
  forward_.SetState(start);
  const ForwardResult r = forward_.Solve(u);
  ++forward_solves_;
  return std::isfinite(r.residual_energy);
}

Eigen::VectorXd ControlProblem::Residuals(const PoseTarget& target) const {
  Eigen::VectorXd e, C;
  workspace_->error.Evaluate(forward_.state(), target, &e, nullptr);
  forward_.constraints().Evaluate(forward_.state(), forward_.controls(), &C);
  Eigen::VectorXd r(e.size() + C.size());
  r << e, std::sqrt(options_.lambda) * C;
  return r;
}

std::unique_ptr<Sensitivity> ControlProblem::LinearizedSensitivity(const Eigen::MatrixXd* de_ds) {
  const auto make = [&](double mu) {
    return std::make_unique<Sensitivity>(forward_.constraints(), forward_.state(), forward_.controls(), effective_,
                                         &workspace_->hessian_solver, &workspace_->derivatives, mu);
  };
  std::unique_ptr<Sensitivity> sensitivity = make(0.0);
  if (!sensitivity->singular() || de_ds == nullptr) return sensitivity;
  // Singular: well posed all the same when every unresisted motion is idle
  // (problems/internal/idle_motions.h).
  const double mu = IdleRegularization(sensitivity->derivatives().H);
  std::unique_ptr<Sensitivity> regularized = make(mu);
  if (!regularized->singular() &&
      OnlyIdleMotions(workspace_->hessian_solver, regularized->derivatives().H, mu, *de_ds)) {
    return regularized;
  }
  return make(0.0);  // the shared workspace holds the regularised factors: redo
}

void ControlProblem::Linearize(const PoseTarget& target, ControlLinearization* lin) {
  lin->large.reset();
  lin->form_JtJ = nullptr;
  const bool finite_differences = options_.gradient == GradientMethod::kFiniteDifference;
  Eigen::VectorXd e;
  Eigen::MatrixXd de_ds;
  workspace_->error.Evaluate(forward_.state(), target, &e, finite_differences ? nullptr : &de_ds);
  lin->sensitivity = LinearizedSensitivity(finite_differences ? nullptr : &de_ds);
  const Sensitivity& sensitivity = *lin->sensitivity;
  lin->rcond = sensitivity.rcond();
  lin->singular = sensitivity.singular();
  const EnergyDerivatives& d = sensitivity.derivatives();
  // r = [e; sqrt(lambda) C] from these evaluations (the same numbers as
  // Residuals(target), which would evaluate both again).
  lin->r.resize(e.size() + d.C.size());
  lin->r << e, std::sqrt(options_.lambda) * d.C;
  if (finite_differences) {
    Eigen::MatrixXd J;
    LinearizeByFiniteDifferences(target, &J, &lin->ds_du);
    lin->singular = false;
    lin->J_e = J.topRows(workspace_->error.size());
    lin->large.reset();
    lin->JtJ.noalias() = J.transpose() * J;
    lin->Jtr.noalias() = J.transpose() * lin->r;
  } else if (static_cast<int>(effective_.size()) >= kMinLargeLmControls && !lin->singular) {
    LargeGaussNewton(e, de_ds, lin);
  } else {
    ImplicitGaussNewton(sensitivity, e, de_ds, effective_, workspace_->effective_column, options_.lambda,
                        /*dense=*/false, lin);
  }
  lin->has_eigen = lin->JtJ.size() > 0 && lin->JtJ.cols() <= kMaxEigenSolveSize;
  if (lin->has_eigen) lin->JtJ_eigen.compute(lin->JtJ);
}

// The Gauss-Newton model of ImplicitGaussNewton without the k x k matrix
// (problems/internal/large_lm_system.h): J_e = de/ds S by one adjoint solve
// per end-effector row, S^T G by one more; J^T J formed only if a reader asks.
void ControlProblem::LargeGaussNewton(const Eigen::VectorXd& e, const Eigen::MatrixXd& de_ds, ControlLinearization* lin) {
  const Sensitivity& sensitivity = *lin->sensitivity;
  const int k = static_cast<int>(effective_.size());
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(k);
  lin->ds_du.resize(0, 0);
  lin->J_e.resize(de_ds.rows(), k);
  for (Eigen::Index r = 0; r < de_ds.rows(); ++r) {
    lin->J_e.row(r) = sensitivity.TotalDerivative(de_ds.row(r).transpose(), none).transpose();  // de/ds S
  }
  const EnergyDerivatives& d = sensitivity.derivatives();
  Eigen::VectorXd constraint_part = sensitivity.TotalDerivative(d.G, none);  // S^T G
  for (int c = 0; c < k; ++c) constraint_part[c] += d.dE_du[effective_[c]];
  lin->Jtr.noalias() = lin->J_e.transpose() * e;
  lin->Jtr += options_.lambda * constraint_part;
  lin->JtJ.resize(0, 0);
  lin->large = std::make_shared<LargeLmSystem>(lin->sensitivity, effective_, lin->J_e, lin->Jtr, options_.lambda,
                                               &workspace_->large_lm);
  const std::shared_ptr<const Sensitivity> kept = lin->sensitivity;
  lin->form_JtJ = [this, kept, e, de_ds] {
    ControlLinearization dense;
    ImplicitGaussNewton(*kept, e, de_ds, effective_, workspace_->effective_column, options_.lambda, /*dense=*/false,
                        &dense);
    return dense.JtJ;
  };
}

Eigen::VectorXd ControlProblem::PredictedStateChange(const ControlLinearization& lin, const Eigen::VectorXd& du) const {
  if (lin.ds_du.size() > 0) return lin.ds_du * du;
  // -H^-1 B du with the factorisation of the last Linearize (still in the
  // workspace: the trial solves use the forward problem's own).
  const SparseColMajor& B = workspace_->derivatives.dG_du;
  Eigen::VectorXd B_du = Eigen::VectorXd::Zero(B.rows());
  for (size_t c = 0; c < effective_.size(); ++c) {
    if (du[c] != 0) B_du += du[c] * B.col(effective_[c]);
  }
  return -workspace_->hessian_solver.Solve(B_du);
}

void ControlProblem::LinearizeByFiniteDifferences(const PoseTarget& target, Eigen::MatrixXd* J,
                                                  Eigen::MatrixXd* ds_du) {
  // Central differences of re-solved forward problems: 2k solves each.
  const State base = forward_.state();
  const Eigen::VectorXd u_base = forward_.controls();
  const double h = options_.finite_difference_step;
  *J = CentralDifferenceJacobian(
      [&](const Eigen::VectorXd& ue) {
        SolveAt(ue, base);
        return Residuals(target);
      },
      EffectiveControls(u_base), h);
  *ds_du = CentralDifferenceJacobian(
      [&](const Eigen::VectorXd& ue) {
        SolveAt(ue, base);
        return Eigen::VectorXd(forward_.state().Minus(base));
      },
      EffectiveControls(u_base), h);
  forward_.Restore(base, u_base);
}

double ControlProblem::Objective(const PoseTarget& target, Eigen::VectorXd* gradient) {
  const State& s = forward_.state();
  const Eigen::VectorXd& u = forward_.controls();
  Eigen::VectorXd e;
  if (gradient == nullptr || options_.gradient == GradientMethod::kFiniteDifference) {
    workspace_->error.Evaluate(s, target, &e, nullptr);
    const double O = 0.5 * e.squaredNorm() + options_.lambda * forward_.Energy();
    if (gradient != nullptr) {
      const State base = s;
      const Eigen::VectorXd u_base = u;
      *gradient = CentralDifferenceGradient(
          [&](const Eigen::VectorXd& ue) {
            SolveAt(ue, base);
            return Objective(target, nullptr);
          },
          EffectiveControls(u_base), options_.finite_difference_step);
      forward_.Restore(base, u_base);
    }
    return O;
  }
  // Adjoint: dO/du = lambda dE/du - (dG/du)^T (dG/ds)^-1 (de/ds^T e + lambda G).
  Eigen::MatrixXd de_ds;
  workspace_->error.Evaluate(s, target, &e, &de_ds);
  const Sensitivity sensitivity(forward_.constraints(), s, u, effective_, &workspace_->hessian_solver,
                                &workspace_->derivatives);
  const EnergyDerivatives& d = sensitivity.derivatives();
  const Eigen::VectorXd dO_ds = de_ds.transpose() * e + options_.lambda * d.G;
  *gradient = sensitivity.TotalDerivative(dO_ds, options_.lambda * sensitivity.ResidualEnergyGradient());
  return 0.5 * e.squaredNorm() + options_.lambda * d.energy;
}

Eigen::MatrixXd ControlProblem::StateSensitivity() {
  if (options_.gradient == GradientMethod::kImplicit) {
    return Sensitivity(forward_.constraints(), forward_.state(), forward_.controls(), effective_,
                       &workspace_->hessian_solver, &workspace_->derivatives)
        .StateSensitivity();
  }
  Eigen::MatrixXd J, ds_du;
  LinearizeByFiniteDifferences(CurrentPose(), &J, &ds_du);
  return ds_du;
}

double ControlProblem::SmallestSingularValue(const PoseTarget& target, Eigen::VectorXd* gradient) {
  const SmallestSingularValueResult r = SmallestSingularValueOfdXdu(
      forward_.constraints(), workspace_->error, target, forward_.state(), forward_.controls(), effective_,
      gradient != nullptr, options_.secondary.sigma_step, &workspace_->sigma_solver, &workspace_->sigma_derivatives);
  if (!r.valid) {
    if (gradient != nullptr) gradient->setConstant(static_cast<Eigen::Index>(effective_.size()),
                                                    std::numeric_limits<double>::quiet_NaN());
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (gradient != nullptr) *gradient = r.gradient;
  return r.sigma;
}

double ControlProblem::PivotRatio(Eigen::VectorXd* gradient) {
  const PivotRatioResult r =
      PivotRatioOfdGds(forward_.constraints(), forward_.state(), forward_.controls(), effective_, gradient != nullptr,
                       options_.secondary.sigma_step, &workspace_->sigma_solver, &workspace_->sigma_derivatives);
  if (!r.valid) {
    if (gradient != nullptr) gradient->setConstant(static_cast<Eigen::Index>(effective_.size()),
                                                    std::numeric_limits<double>::quiet_NaN());
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (gradient != nullptr) *gradient = r.gradient;
  return r.rho;
}

double ControlProblem::SecondaryObjective(const PoseTarget& target, Eigen::VectorXd* gradient) {
  Eigen::VectorXd r2;
  Eigen::MatrixXd J2;
  SecondaryObjectiveTerms(this).Evaluate(target, &r2, gradient != nullptr ? &J2 : nullptr);
  if (gradient != nullptr) *gradient = J2.transpose() * r2;
  return 0.5 * r2.squaredNorm();
}

ControlStepResult ControlProblem::SolveStep(const PoseTarget& target) {
  CheckTarget(target);
  return options_.method == ControlMethod::kBfgs ? BfgsLoop(this).SolveStep(target) : LmLoop(this).SolveStep(target);
}

void ControlProblem::Finish(const PoseTarget& target, ControlStepResult* result) {
  Eigen::VectorXd e;
  workspace_->error.Evaluate(forward_.state(), target, &e, nullptr);
  result->residual_energy = forward_.Energy();
  result->error = e.size() > 0 ? e.lpNorm<Eigen::Infinity>() : 0.0;
  result->objective = 0.5 * e.squaredNorm() + options_.lambda * result->residual_energy;
  result->assembled = result->residual_energy < forward_.options().assembly_tolerance;
  const StepConstraints& constraints = workspace_->step_constraints;
  if (!constraints.empty()) constraints.Report(forward_.controls(), forward_.state(), workspace_->active, result);
  result->reached = result->assembled && result->error <= options_.target_tolerance &&
                    result->max_limit_violation <= 1e-9 && result->max_lateral_displacement <= 1e-9 &&
                    result->max_clearance_violation <= 1e-9 && result->max_effort_violation <= 1e-6;
}

ControlResult ControlProblem::MoveTo(
    const PoseTarget& target,
    const std::function<void(const PoseTarget&, const ControlStepResult&)>& on_step) {
  const auto start = std::chrono::steady_clock::now();
  CheckTarget(target);
  const PosePath path(forward_.model(), CurrentPose(), target, options_.max_step_m, options_.max_step_rad);
  travel_origin_ = forward_.controls();
  PathTally tally(on_step);
  tally.KeepIfAssembled(forward_.Energy() < forward_.options().assembly_tolerance, forward_.state(),
                        forward_.controls(), 0);
  for (int i = 1; i <= path.steps(); ++i) {
    const PoseTarget step_target = path.At(i);
    ControlStepResult turn;
    if (DifferentialTurning(this).Turn(step_target, &turn)) tally.Add(CurrentPose(), turn, true);
    const ControlStepResult step = SolveStep(step_target);
    tally.Add(step_target, step);
    if (!step.reached) {
      tally.result.warning = StepNotReached(i, path.steps(), step);
      if (i < path.steps()) tally.Add(target, SolveStep(target));  // best controls for the real target
      break;
    }
    tally.KeepIfAssembled(step.assembled, forward_.state(), forward_.controls(), i);
    if (path_step_observer_) path_step_observer_(i, path.steps());
  }
  if (!tally.last.assembled && tally.have_assembled) ReturnToLastAssembled(target, &tally);
  return tally.Close(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
}

void ControlProblem::ReturnToLastAssembled(const PoseTarget& target, PathTally* tally) {
  // A stop never leaves the mechanism torn: its controls and poses must be
  // usable. The last assembled configuration is restored and measured
  // against the final target (not reached: the warning says why).
  forward_.Restore(tally->assembled_state, tally->assembled_controls);
  ControlStepResult restored = tally->last;
  Finish(target, &restored);
  restored.reached = false;
  tally->last = restored;
  tally->result.warning += "; returned the last assembled configuration (" +
                           (tally->assembled_step == 0 ? std::string("the start")
                                                        : "path step " + std::to_string(tally->assembled_step)) +
                           ")";
}

}  // namespace ccma
