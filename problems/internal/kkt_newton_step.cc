#include "problems/internal/kkt_newton_step.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ccma {
namespace {

constexpr int kKktRefinements = 4;
// A refined KKT solution's residual must be within this of max(1, |rhs|)
// (N or m): the LU's is about 1e-15 of it, the LDL^T's without pivoting
// 1e-14 after refinement here; a worse one falls back to the LU. Refinement
// stops as soon as it is reached.
constexpr double kKktResidual = 1e-12;

}  // namespace

KktNewtonStep::KktNewtonStep(const LoadedKkt& system) : system_(system) {
  rhs_.resize(system.size() + system.rigid_rows());
  rhs_.head(system.size()) = system.force();
  rhs_.tail(system.rigid_rows()) = -system.g();
}

bool KktNewtonStep::Solve(KktFactorization* kkt, Eigen::VectorXd* z) const {
  if (!kkt->Factorize(system_.K())) return false;
  if (SolveRefined(*kkt, rhs_, z)) return true;
  return !kkt->uses_lu() && kkt->UseLu() && SolveRefined(*kkt, rhs_, z);
}

bool KktNewtonStep::SolveAgain(const KktFactorization& kkt, const Eigen::VectorXd& rhs, Eigen::VectorXd* z) const {
  return SolveRefined(kkt, rhs, z);
}

void KktNewtonStep::RemoveIdleBias(const KktFactorization& kkt, Eigen::VectorXd* z) const {
  Eigen::VectorXd bias = Eigen::VectorXd::Zero(z->size());
  bias.head(system_.size()) = system_.eps_H() * z->head(system_.size());
  *z += kkt.Solve(bias);
}

double KktNewtonStep::Unbalanced(const Eigen::VectorXd& mu) const {
  const Eigen::VectorXd r = system_.force() - system_.A().transpose() * mu;
  return r.size() > 0 ? r.lpNorm<Eigen::Infinity>() : 0.0;
}

// z from kkt's factor with up to kKktRefinements steps of iterative
// refinement against K without eps_A; true when the residual is within
// kKktResidual of |rhs| or of the products K z sums (ComponentwiseScale).
bool KktNewtonStep::SolveRefined(const KktFactorization& kkt, const Eigen::VectorXd& rhs, Eigen::VectorXd* z) const {
  const Eigen::Index m = system_.rigid_rows();
  *z = kkt.Solve(rhs);
  const double target = kKktResidual * std::max(1.0, rhs.lpNorm<Eigen::Infinity>());
  double size = std::numeric_limits<double>::infinity();
  for (int r = 0; r <= kKktRefinements && z->allFinite(); ++r) {
    Eigen::VectorXd residual = rhs - system_.K().selfadjointView<Eigen::Lower>() * *z;
    residual.tail(m) -= kKktRowRegularization * z->tail(m);
    const double next = residual.lpNorm<Eigen::Infinity>();
    if (!(next < size)) break;  // refinement has stopped gaining
    size = next;
    if (r == kKktRefinements || size <= target) break;
    *z += kkt.Solve(residual);
  }
  if (!z->allFinite()) return false;
  return size <= target || size <= kKktResidual * ComponentwiseScale(*z);
}

// max_i (|K| |z|)_i: the size of the products a residual of K z sums. With
// stiff springs (1e7 N/m) over millimetres it is far above |rhs|, and the
// rounding of a residual is relative to it, not to |rhs| (Oettli-Prager).
double KktNewtonStep::ComponentwiseScale(const Eigen::VectorXd& z) const {
  const Eigen::VectorXd abs_z = z.cwiseAbs();
  Eigen::VectorXd products = Eigen::VectorXd::Zero(z.size());
  const LoadedKkt::Sparse& K = system_.K();  // lower triangle
  for (int col = 0; col < K.outerSize(); ++col) {
    for (LoadedKkt::Sparse::InnerIterator it(K, col); it; ++it) {
      const double a = std::abs(it.value());
      products[it.row()] += a * abs_z[col];
      if (it.row() != col) products[col] += a * abs_z[it.row()];
    }
  }
  return products.size() > 0 ? products.lpNorm<Eigen::Infinity>() : 0.0;
}

void AssembleStep(const Model& model, const ConstraintSet& set, bool chord, const LoadedPoint& x,
                  const Eigen::VectorXd& u, const ExternalWrench& wrench, const Eigen::VectorXd& w,
                  const Eigen::VectorXd& mu_last, LoadedKkt* system) {
  if (chord) {
    system->AssembleResiduals(model, set, x, u, wrench, mu_last);
    return;
  }
  const Eigen::VectorXd weights = w.size() > 0 ? w : Eigen::VectorXd::Zero(set.num_rows());
  system->Assemble(model, set, x, u, wrench, weights, mu_last, kKktIdleStiffness * system->stiffest(),
                   kKktRowRegularization);
}

bool SolveKktAt(const LoadedKkt& system, bool full, const Eigen::VectorXd& mu_last, KktFactorization* kkt,
                Eigen::VectorXd* z) {
  const KktNewtonStep step(system);
  if (full) {
    if (!step.Solve(kkt, z)) return false;
  } else {
    Eigen::VectorXd rhs = step.rhs();
    rhs.head(system.size()) -= system.reaction();
    if (!step.SolveAgain(*kkt, rhs, z)) return false;
    z->tail(system.rigid_rows()) += mu_last;
  }
  step.RemoveIdleBias(*kkt, z);
  return true;
}

double UnbalancedAt(const LoadedKkt& system, bool chord, const Eigen::VectorXd& mu) {
  if (!chord) return KktNewtonStep(system).Unbalanced(mu);
  const Eigen::VectorXd r = system.force() - system.reaction();
  return r.size() > 0 ? r.lpNorm<Eigen::Infinity>() : 0.0;
}

}  // namespace ccma
