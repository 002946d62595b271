#include "problems/internal/constrained_lm_step.h"

#include <algorithm>

#include "ccma/internal/dense_factorizations.h"


namespace ccma {

Eigen::VectorXd ConstrainedLmStep(const Eigen::MatrixXd& JtJ, const Eigen::VectorXd& Jtr, double mu,
                                  const LinearConstraints& constraints,
                                  const SymmetricEigenSolver* JtJ_eigen) {
  // -V (Lambda + mu)^-1 V^T g: least norm in the directions J does not see.
  // Eigenvalues below 1e-12 of the largest are rounding noise of J^T J (its
  // null space: redundant controls), and so is g there: those components are
  // dropped rather than amplified by 1 / mu, so that the step is the
  // least-norm one whichever way J^T J was formed.
  auto damped_solve = [mu](const SymmetricEigenSolver& eig, const Eigen::VectorXd& g) {
    const Eigen::VectorXd sigma_sq = eig.eigenvalues().cwiseMax(0.0);
    const double cutoff = 1e-12 * sigma_sq.maxCoeff();
    const Eigen::VectorXd projected = eig.eigenvectors().transpose() * g;
    Eigen::VectorXd scaled(projected.size());
    for (int i = 0; i < projected.size(); ++i) {
      scaled[i] = sigma_sq[i] > cutoff ? projected[i] / (sigma_sq[i] + mu) : 0.0;
    }
    return Eigen::VectorXd(-eig.eigenvectors() * scaled);
  };
  if (constraints.rows() == 0) {
    if (JtJ_eigen != nullptr) return damped_solve(*JtJ_eigen, Jtr);
    if (JtJ.rows() > kMaxEigenSolveSize) {
      // Many controls: a pivoted LDLT of J^T J + mu (k^3 / 3, against ~9 k^3
      // for the eigen-decomposition), without the cut-off above.
      Eigen::MatrixXd damped = JtJ;
      damped.diagonal().array() += mu;
      return -damped.ldlt().solve(Jtr);
    }
    return damped_solve(SymmetricEigenSolver(JtJ), Jtr);
  }
  const int k = static_cast<int>(JtJ.cols());
  const JacobiSvd svd(constraints.A, Eigen::ComputeFullV | Eigen::ComputeFullU);
  const Eigen::VectorXd sigma = svd.singularValues();
  const double cutoff = 1e-10 * std::max(1.0, sigma.size() > 0 ? sigma[0] : 0.0);
  int rank = 0;
  while (rank < sigma.size() && sigma[rank] > cutoff) ++rank;
  const Eigen::MatrixXd V = svd.matrixV(), U = svd.matrixU();
  const Eigen::VectorXd d0 =
      V.leftCols(rank) * (sigma.head(rank).cwiseInverse().asDiagonal() * (U.leftCols(rank).transpose() * constraints.b));
  const Eigen::MatrixXd N = V.rightCols(k - rank);
  if (N.cols() == 0) return d0;
  // min over z of |J N z + (J d0 + r)|^2 + mu |d0 + N z|^2, least norm in z:
  // (J N)^T (J N) = N^T J^T J N and (J N)^T (J d0 + r) = N^T (J^T J d0 + J^T r).
  const SymmetricEigenSolver eig(N.transpose() * JtJ * N);
  const Eigen::VectorXd g = N.transpose() * (JtJ * d0 + Jtr + mu * d0);
  return d0 + N * damped_solve(eig, g);
}

}  // namespace ccma
