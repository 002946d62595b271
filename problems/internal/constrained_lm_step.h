// The damped least-squares step of Levenberg-Marquardt under linear
// equality constraints (the control step's outer loop, lm_loop.h):
//   min |J d + r|^2 + mu |d|^2   subject to   A d = b
// given J^T J (k x k) and J^T r (k), through the null space of A (SVD,
// rank-revealing): d = d0 + N z with d0 the least-norm solution of A d = b; z
// by the same least-norm eigen-solve as the unconstrained step. With no
// constraint rows it is the unconstrained step, -V (Lambda + mu)^-1 V^T J^T r
// with J^T J = V Lambda V^T; pass that decomposition (`JtJ_eigen`) to reuse
// it across damping trials.
#ifndef CCMA_PROBLEMS_INTERNAL_CONSTRAINED_LM_STEP_H_
#define CCMA_PROBLEMS_INTERNAL_CONSTRAINED_LM_STEP_H_

#include <Eigen/Core>

#include "ccma/internal/dense_factorizations.h"
#include "problems/internal/step_constraint.h"

namespace ccma {

// Above this many controls the unconstrained step uses an LDLT instead of
// the eigen-decomposition (see ConstrainedLmStep).
constexpr int kMaxEigenSolveSize = 64;

Eigen::VectorXd ConstrainedLmStep(const Eigen::MatrixXd& JtJ, const Eigen::VectorXd& Jtr, double mu,
                                  const LinearConstraints& constraints,
                                  const SymmetricEigenSolver* JtJ_eigen = nullptr);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_CONSTRAINED_LM_STEP_H_
