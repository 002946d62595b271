#include "problems/internal/idle_motions.h"

#include <algorithm>
#include <random>

#include <Eigen/QR>

#include "ccma/internal/dense_factorizations.h"

namespace ccma {

double IdleRegularization(const SparseColMajor& H) {
  double largest = 0;
  for (Eigen::Index j = 0; j < H.outerSize(); ++j) {
    for (SparseColMajor::InnerIterator it(H, j); it; ++it) {
      if (it.row() == j) largest = std::max(largest, std::abs(it.value()));
    }
  }
  return 1e-9 * std::max(largest, 1e-300);
}

bool OnlyIdleMotions(const HessianSolver& solver, const SparseColMajor& H_regularized, double mu,
                     const Eigen::MatrixXd& de_ds) {
  if (!solver.factorized()) return false;
  const Eigen::VectorXd& pivots = solver.pivots();
  const int candidates = static_cast<int>((pivots.array().abs() <= 1e3 * mu).count());
  if (candidates == 0) return true;
  if ((pivots.array() < 0).any()) return false;  // indefinite: not a clean null space
  // Inverse iteration on (H + mu I): its unresisted eigenvalues are about mu,
  // the others at least the smallest resisted curvature, so each pass shrinks
  // the other components by that ratio.
  const Eigen::Index n = pivots.size();
  std::mt19937 random(1);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd V = Eigen::MatrixXd::NullaryExpr(n, candidates, [&]() { return normal(random); });
  for (int pass = 0; pass < 4; ++pass) {
    V = solver.Solve(V);
    V = Eigen::HouseholderQR<Eigen::MatrixXd>(V).householderQ() * Eigen::MatrixXd::Identity(n, candidates);
  }
  // Within span(V), the directions H resists less than 10 mu are the
  // unresisted motions; each must leave the end-effector where it is.
  const Eigen::MatrixXd W = V.transpose() * (H_regularized * V);
  const SymmetricEigenSolver eigen(0.5 * (W + W.transpose()));
  const double scale = std::max(de_ds.norm(), 1e-300);
  for (Eigen::Index i = 0; i < eigen.eigenvalues().size(); ++i) {
    if (eigen.eigenvalues()[i] > 10 * mu) continue;
    if ((de_ds * (V * eigen.eigenvectors().col(i))).norm() > 1e-8 * scale) return false;
  }
  return true;
}

}  // namespace ccma
