#include "problems/internal/null_space_step.h"

#include <algorithm>
#include <cmath>


#include "ccma/internal/dense_factorizations.h"
#include "problems/internal/control_workspace.h"
#include "problems/internal/lm_loop.h"
#include "problems/internal/secondary_objective.h"

namespace ccma {
namespace {

// Null space of the task's Gauss-Newton model J^T J = J_e^T J_e + lambda
// d2E_r/du2: control changes that move neither the end-effector nor the
// residual energy to first order (an over-constrained loop also has control
// directions that keep the end-effector but pull the loop apart). Columns:
// an orthonormal basis (k x nullity), empty when there is no redundancy.
Eigen::MatrixXd TaskNullSpace(const Eigen::MatrixXd& JtJ) {
  const int k = static_cast<int>(JtJ.rows());
  const SymmetricEigenSolver eig(JtJ);
  const Eigen::VectorXd& ev = eig.eigenvalues();  // increasing
  int nullity = 0;
  while (nullity < k && ev[nullity] <= 1e-9 * std::max(ev[k - 1], 1e-300)) ++nullity;
  return eig.eigenvectors().leftCols(nullity);
}

}  // namespace

bool NullSpaceStep::TryStep(const PoseTarget& target, const ControlLinearization& lin, const Eigen::VectorXd& du,
                            double phi, ControlStepResult* result) {
  ForwardProblem& forward = p_.forward_;
  const State base = forward.state();
  State predicted = base;
  predicted.Plus(p_.PredictedStateChange(lin, du));
  ControlStepResult inner;
  if (!p_.SolveAt(p_.EffectiveControls(forward.controls()) + du, predicted) ||
      !LmLoop(&p_).ConvergeTask(target, &inner, /*report_iterations=*/false)) {
    return false;
  }
  Eigen::VectorXd e;
  p_.workspace_->error.Evaluate(forward.state(), target, &e, nullptr);
  const bool reached = (e.size() == 0 || e.lpNorm<Eigen::Infinity>() <= p_.options_.target_tolerance) &&
                       forward.Energy() < forward.options().assembly_tolerance;
  // Another assembly branch: the state moved far more than a control change
  // of this size moves it (the same test as Assemble's, with a factor 10 for
  // the task's re-convergence).
  const double jump = forward.state().Minus(base).lpNorm<Eigen::Infinity>();
  const bool jumped = jump > forward.options().branch_jump_relative * 10 * du.lpNorm<Eigen::Infinity>() +
                                 forward.options().branch_jump_absolute;
  Eigen::VectorXd r2_new;
  SecondaryObjectiveTerms(&p_).Evaluate(target, &r2_new, nullptr);
  const double phi_new = 0.5 * r2_new.squaredNorm();
  result->iterations += inner.iterations;
  result->branch_jumps_rejected += inner.branch_jumps_rejected + jumped;
  if (!(reached && !jumped && phi_new < phi)) return false;
  result->rcond = inner.rcond;
  result->singular |= inner.singular;
  result->min_singular_value_dX_du = inner.min_singular_value_dX_du;
  return true;
}

bool NullSpaceStep::Iterate(const PoseTarget& target, ControlStepResult* result) {
  Eigen::VectorXd r2;
  Eigen::MatrixXd J2;
  SecondaryObjectiveTerms(&p_).Evaluate(target, &r2, &J2);
  const double phi = 0.5 * r2.squaredNorm();
  if (!(phi > 0) || !std::isfinite(phi)) return false;
  ControlLinearization lin;
  p_.Linearize(target, &lin);
  const Eigen::MatrixXd N = TaskNullSpace(lin.DenseJtJ());
  if (N.cols() == 0) return false;  // no redundancy here
  const Eigen::MatrixXd JN = J2 * N;
  const Eigen::MatrixXd JtJ = JN.transpose() * JN;
  const Eigen::VectorXd Jtr = JN.transpose() * r2;
  const State base = p_.forward_.state();
  const Eigen::VectorXd u_base = p_.forward_.controls();
  double mu = 1e-6 * std::max(JtJ.trace(), 1e-30);
  double radius = p_.options_.max_step_m;  // trust region [m or rad, max-norm]
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd z = -(JtJ + mu * Eigen::MatrixXd::Identity(JtJ.rows(), JtJ.cols())).ldlt().solve(Jtr);
    Eigen::VectorXd du = N * z;
    // No farther than one path step per iteration (and a quarter of that
    // after each refusal): the re-converged task stays on the branch and
    // the first-order prediction stays good.
    const double largest = du.lpNorm<Eigen::Infinity>();
    if (!(largest > 1e-14)) return false;
    if (largest > radius) du *= radius / largest;
    if (TryStep(target, lin, du, phi, result)) return true;
    p_.forward_.Restore(base, u_base);
    mu = mu * 10 + 1e-30;
    radius = 0.25 * std::min(radius, largest);
  }
  return false;
}

}  // namespace ccma
