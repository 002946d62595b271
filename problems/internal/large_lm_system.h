// The Levenberg-Marquardt step of a control problem with many controls
// (problems/internal/lm_loop.h), without the dense k x k matrix.
//
// The step solves (J_e^T J_e + lambda C + mu I) du = -g over the effective
// controls, with J_e = de/du (ne x k, ne <= 6) and C = J_u^T J_u + B^T S the
// Hessian of the residual energy (S = ds/du = -H^-1 B, H = dG/ds, B = dG/du;
// control_problem.cc, ImplicitGaussNewton). Formed densely, C costs k solves
// and k^2 doubles, and the step an O(k^3) factorisation: 288 MB and a minute
// for 1000 quadrupeds (6000 controls). Here C + (mu / lambda) I is never
// formed: it is the Schur complement onto u of the sparse
//   W = [H    B                        ]
//       [B^T  J_u^T J_u + (mu/lambda) I]
// (positive definite where H is and the forward problem is at a minimum of
// its energy), factorised by a sparse LDL^T whose analysis is made once per
// problem. The rank-ne term J_e^T J_e is added by the Woodbury identity; its
// cancellation (the step's components along motions C does not resist are
// divided by mu, then subtracted) is removed by iterative refinement against
// the exact product (one solve with H and one with W per step of
// refinement). The result equals the dense step to rounding
// (tests/large_lm_system_test.cc).
// Units: the controls' (m, rad), the residual's (m, rad; m^2 for C).
#ifndef CCMA_PROBLEMS_INTERNAL_LARGE_LM_SYSTEM_H_
#define CCMA_PROBLEMS_INTERNAL_LARGE_LM_SYSTEM_H_

#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "problems/internal/sensitivity.h"

namespace ccma {

// Above this many effective controls a control step uses LargeLmSystem (in
// benchmarks/scaling_benchmark.cc the sparse step is the faster from about
// 200 controls on).
constexpr int kMinLargeLmControls = 200;

// W's factorisation, kept between linearisations of one problem: the
// symbolic analysis is made for the first W and reused while the pattern
// stays.
struct LargeLmWorkspace {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt;
  Eigen::Index analysed_size = -1;
  Eigen::Index analysed_nonzeros = -1;
};

class LargeLmSystem {
 public:
  // At the linearisation point of `sensitivity` (dG/ds factorised): J_e =
  // de/du and g = J^T r over the effective controls `effective` (k),
  // lambda > 0. `workspace` outlives this object.
  LargeLmSystem(std::shared_ptr<const Sensitivity> sensitivity, std::vector<int> effective, Eigen::MatrixXd J_e,
                Eigen::VectorXd g, double lambda, LargeLmWorkspace* workspace);

  // du = -(J_e^T J_e + lambda C + mu I)^-1 g (mu > 0); false when W cannot
  // be factorised or the refined step does not reach 1e-10 of |g|.
  bool Step(double mu, Eigen::VectorXd* du) const;
  // (J_e^T J_e + lambda C) v: one solve with H.
  Eigen::VectorXd Apply(const Eigen::VectorXd& v) const;
  // An upper bound of the largest eigenvalue of J_e^T J_e + lambda C:
  // |J_e|_F^2 + lambda |J_u|_F^2 (B^T S is negative semi-definite).
  double LargestEigenvalueBound() const;

 private:
  // (C + (mu / lambda) I)^-1 for the columns of V, by W's factorisation.
  Eigen::MatrixXd SchurSolve(const Eigen::MatrixXd& V) const;
  bool Factorize(double mu) const;

  const std::shared_ptr<const Sensitivity> sensitivity_;
  const std::vector<int> effective_;
  const Eigen::MatrixXd J_e_;
  const Eigen::VectorXd g_;
  const double lambda_;
  LargeLmWorkspace* workspace_;
  Eigen::SparseMatrix<double> W_;        // mu = 0 (lower triangle)
  Eigen::SparseMatrix<double> J_u_;      // J_u over the effective controls
  Eigen::SparseMatrix<double> B_;        // dG/du over the effective controls
  mutable double factorised_mu_ = -1;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_LARGE_LM_SYSTEM_H_
