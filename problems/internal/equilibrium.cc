#include "problems/internal/equilibrium.h"

#include <stdexcept>
#include <string>

#include "ccma/internal/dense_factorizations.h"
#include "ccma/loads.h"

namespace ccma {

Equilibrium::Equilibrium(const ConstraintSet& set, const State& s, const Eigen::VectorXd& u) {
  if (static_cast<long>(set.num_rows()) * set.state_size() > kMaxStaticsEntries) {
    throw std::invalid_argument("statics: " + std::to_string(set.num_rows()) + " constraint rows x " +
                                std::to_string(set.state_size()) + " state coordinates exceed " +
                                std::to_string(kMaxStaticsEntries) + " entries");
  }
  Eigen::VectorXd C;
  set.Evaluate(s, u, &C, &J_s_, &J_u_);
  cod_.setThreshold(1e-10);
  cod_.compute(J_s_.transpose());
}

Equilibrium::Adjoint Equilibrium::AdjointOf(const Eigen::VectorXd& w, const Eigen::VectorXd& Q) const {
  Adjoint a;
  a.lambda = Multipliers(Q);
  const Eigen::VectorXd Juw = J_u_ * w;
  a.mu = StateSolution(Juw);
  a.zeta = Juw - J_s_ * a.mu;
  const double scale = 1.0 + Juw.lpNorm<Eigen::Infinity>();
  a.unique = a.zeta.size() == 0 || a.zeta.lpNorm<Eigen::Infinity>() <= 1e-8 * scale;
  if (a.unique) {
    // zeta is rounding here, and eta (1 / the smallest singular value of
    // J_s) would only amplify it: the term is exactly zero.
    a.zeta.setZero();
    a.eta = Eigen::VectorXd::Zero(J_s_.cols());
  } else {
    a.eta = StateSolution(a.lambda);
  }
  return a;
}

double EffortLagrangian(const ConstraintSet& set, const Model& loads_model, const State& s,
                        const Eigen::VectorXd& u, const Eigen::VectorXd& w, const Equilibrium::Adjoint& a) {
  Eigen::VectorXd C;
  Eigen::MatrixXd J_s, J_u;
  set.Evaluate(s, u, &C, &J_s, &J_u);
  const Eigen::VectorXd Q = GeneralizedLoads(loads_model, s);
  return -w.dot(J_u.transpose() * a.lambda) + a.mu.dot(J_s.transpose() * a.lambda + Q) - a.zeta.dot(J_s * a.eta);
}

}  // namespace ccma
