#include "problems/internal/compensated_newton.h"

#include <limits>
#include <utility>

#include "ccma/internal/dense_factorizations.h"
#include "problems/internal/end_effector_error.h"
#include "problems/internal/kkt_newton_step.h"

namespace ccma {
namespace {

// J^+, the minimum-norm inverse of J = de/du over the effective controls
// (effective x rows), at the point `system` and `kkt` were made at:
// J = -W_mu^T A_u, W = K^-1 [de/ds^T; 0] (one solve per row of e).
// False when it is not finite.
bool ControlInverse(const LoadedKkt& system, const KktFactorization& kkt, const Eigen::MatrixXd& de_ds,
                    const std::vector<int>& effective, Eigen::MatrixXd* J_pinv) {
  const int n = system.state_size(), m = system.rigid_rows();
  Eigen::MatrixXd W_mu(m, de_ds.rows());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(system.size() + m);
  for (Eigen::Index r = 0; r < de_ds.rows(); ++r) {
    rhs.head(n) = de_ds.row(r).transpose();
    W_mu.col(r) = kkt.Solve(rhs).tail(m);
  }
  Eigen::MatrixXd J(de_ds.rows(), static_cast<Eigen::Index>(effective.size()));
  for (size_t i = 0; i < effective.size(); ++i) {
    J.col(static_cast<Eigen::Index>(i)) = -W_mu.transpose() * system.A_u().col(effective[i]);
  }
  *J_pinv = MinimumNormSolver(J).solveMatrix(Eigen::MatrixXd::Identity(J.rows(), J.rows()));
  return J_pinv->allFinite();
}

}  // namespace

CompensatedNewtonResult SolveCompensatedNewton(const Model& model, const ConstraintSet& set, const PoseTarget& target,
                                               const std::vector<int>& effective, const ExternalWrench& wrench,
                                               const CompensatedNewtonOptions& options, LoadedWorkspace* workspace,
                                               LoadedPoint* x, Eigen::VectorXd* u) {
  CompensatedNewtonResult out;
  LoadedKkt& system = workspace->SystemFor(model, set);
  const EndEffectorError error(model);
  LoadedPoint trial = *x;
  Eigen::VectorXd u_trial = *u;
  Eigen::VectorXd w = workspace->w.size() == set.num_rows() ? workspace->w : Eigen::VectorXd::Zero(set.num_rows());
  Eigen::VectorXd mu_last = workspace->mu.size() == system.rigid_rows() ? workspace->mu : Eigen::VectorXd();
  const int n = system.state_size(), N = system.size();
  double last = std::numeric_limits<double>::infinity();
  Eigen::VectorXd e, z, dz, du;
  Eigen::MatrixXd de_ds, J_pinv;
  for (int i = 0; i <= options.max_iterations; ++i) {
    system.Assemble(model, set, trial, u_trial, wrench, w, mu_last, kKktIdleStiffness * system.stiffest(),
                    kKktRowRegularization);
    const KktNewtonStep step(system);
    if (!step.Solve(&workspace->kkt, &z)) return out;
    step.RemoveIdleBias(workspace->kkt, &z);
    const Eigen::VectorXd mu = z.tail(system.rigid_rows());
    const double unbalanced = step.Unbalanced(mu);
    const double row_size = system.g().size() > 0 ? system.g().lpNorm<Eigen::Infinity>() : 0.0;
    error.Evaluate(trial.s, target, &e, &de_ds);
    const double miss = e.size() > 0 ? e.lpNorm<Eigen::Infinity>() : 0.0;
    out.unbalanced = unbalanced;
    if (unbalanced <= options.force_tolerance && row_size <= kKktRowTolerance && miss <= options.error_tolerance) {
      out.converged = true;
      *x = std::move(trial);
      *u = std::move(u_trial);
      workspace->mu = mu;
      workspace->w = system.SetOrder(mu);
      workspace->at_solution = true;
      return out;
    }
    // Newton converges fast or not at all: a growing merit gives up (the caller falls back to rounds).
    const double merit = unbalanced / options.force_tolerance + row_size / kKktRowTolerance + miss / options.error_tolerance;
    if ((i >= 2 && !(merit < 2 * last)) || i == options.max_iterations) return out;
    last = merit;
    // du = J^+ (-(e + de/ds y0)), J at this point.
    if (!ControlInverse(system, workspace->kkt, de_ds, effective, &J_pinv)) return out;
    const Eigen::VectorXd du_effective = J_pinv * (-(e + de_ds * z.head(n)));
    du.setZero(system.A_u().cols());
    for (size_t c = 0; c < effective.size(); ++c) du[effective[c]] = du_effective[static_cast<Eigen::Index>(c)];
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(z.size());
    rhs.tail(system.rigid_rows()) = -system.A_u() * du;
    dz = workspace->kkt.Solve(rhs);  // (a correction: eps's biases are below the iteration's rate)
    const Eigen::VectorXd y = z.head(N) + dz.head(N);
    if (!(y.lpNorm<Eigen::Infinity>() <= kKktMaxStep) || !(du.lpNorm<Eigen::Infinity>() <= options.max_control_step)) {
      return out;
    }
    ++out.iterations;
    trial.s.Plus(y.head(n));
    trial.delta += y.tail(N - n);
    u_trial += du;
    mu_last = mu + dz.tail(system.rigid_rows());
    w = system.SetOrder(mu_last);
  }
  return out;
}

}  // namespace ccma
