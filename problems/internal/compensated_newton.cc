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

// The step from the solve z = [y0; mu0] at the point: the controls' du =
// J^+ (-(e + de/ds y0)) (J_pinv over the effective controls), the
// configuration's y = y0 + (K^-1 [0; -A_u du])_top, and the multipliers
// after it.
struct JointStep {
  Eigen::VectorXd y, du, mu;
};
JointStep StepFrom(const LoadedKkt& system, const KktFactorization& kkt, const Eigen::VectorXd& z,
                   const Eigen::VectorXd& e, const Eigen::MatrixXd& de_ds, const Eigen::MatrixXd& J_pinv,
                   const std::vector<int>& effective) {
  const int n = system.state_size(), N = system.size(), m = system.rigid_rows();
  JointStep out;
  const Eigen::VectorXd du_effective = J_pinv * (-(e + de_ds * z.head(n)));
  out.du.setZero(system.A_u().cols());
  for (size_t c = 0; c < effective.size(); ++c) out.du[effective[c]] = du_effective[static_cast<Eigen::Index>(c)];
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(z.size());
  rhs.tail(m) = -system.A_u() * out.du;
  const Eigen::VectorXd dz = kkt.Solve(rhs);  // (a correction: eps's biases are below the iteration's rate)
  out.y = z.head(N) + dz.head(N);
  out.mu = z.tail(m) + dz.tail(m);
  return out;
}

// What the tests measure at a point: the unbalanced force with the
// current rows and the multipliers mu (a full step's own; a chord step's
// the last ones, the certificate its residual was taken with), the rigid
// rows' residual, the end-effector error e.
struct Residuals {
  double unbalanced = 0, rows = 0, miss = 0;
};
Residuals ResidualsAt(const LoadedKkt& system, bool chord, const Eigen::VectorXd& mu, const Eigen::VectorXd& e) {
  Residuals r;
  r.unbalanced = UnbalancedAt(system, chord, mu);
  r.rows = system.g().size() > 0 ? system.g().lpNorm<Eigen::Infinity>() : 0.0;
  r.miss = e.size() > 0 ? e.lpNorm<Eigen::Infinity>() : 0.0;
  return r;
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
  Eigen::VectorXd mu_last = workspace->mu.size() == system.rigid_rows() ? workspace->mu : Eigen::VectorXd();
  const int n = system.state_size(), N = system.size();
  double last_merit = std::numeric_limits<double>::infinity(), last_size = last_merit;
  int full_steps = 0, chords = 0;
  bool full = true;
  Eigen::VectorXd e, z;
  Eigen::MatrixXd de_ds, J_pinv;
  for (int i = 0; i <= options.max_iterations; ++i) {
    const bool chord = !full && mu_last.size() == system.rigid_rows();
    AssembleStep(model, set, chord, trial, u_trial, wrench,
                 mu_last.size() > 0 && !chord ? system.SetOrder(mu_last) : Eigen::VectorXd(), mu_last, &system);
    if (!SolveKktAt(system, !chord, mu_last, &workspace->kkt, &z)) return out;
    error.Evaluate(trial.s, target, &e, &de_ds);
    const Eigen::VectorXd mu = chord ? mu_last : Eigen::VectorXd(z.tail(system.rigid_rows()));
    const Residuals r = ResidualsAt(system, chord, mu, e);
    out.unbalanced = r.unbalanced;
    const double step_size = z.head(N).lpNorm<Eigen::Infinity>();
    if (options.tolerances.Converged(r.unbalanced, step_size) && r.rows <= kKktRowTolerance &&
        r.miss <= options.error_tolerance) {
      out.converged = true;
      *x = std::move(trial);
      *u = std::move(u_trial);
      workspace->KeepMultipliers(mu);
      return out;
    }
    if (!chord) {
      // Newton converges fast or not at all: a growing merit gives up (the caller falls back to rounds).
      const double merit = r.unbalanced / options.tolerances.force + r.rows / kKktRowTolerance + r.miss / options.error_tolerance;
      if ((full_steps++ >= 2 && !(merit < 2 * last_merit)) || i == options.max_iterations) return out;
      last_merit = merit;
      if (!ControlInverse(system, workspace->kkt, de_ds, effective, &J_pinv)) return out;
      chords = 0;
    }
    const JointStep next = StepFrom(system, workspace->kkt, z, e, de_ds, J_pinv, effective);
    const double size = std::max(next.y.lpNorm<Eigen::Infinity>(), next.du.lpNorm<Eigen::Infinity>());
    if (!(next.y.lpNorm<Eigen::Infinity>() <= kKktMaxStep) || !(next.du.lpNorm<Eigen::Infinity>() <= options.max_control_step)) {
      return out;
    }
    ++out.iterations;
    trial.s.Plus(next.y.head(n));
    trial.delta += next.y.tail(N - n);
    u_trial += next.du;
    mu_last = next.mu;
    // Chord steps (the last factorisation, new residuals) while they shrink
    // at least tenfold; a full step where they stall.
    full = ++chords > options.max_chords || !(size < 0.1 * last_size);
    last_size = size;
  }
  return out;
}

}  // namespace ccma
