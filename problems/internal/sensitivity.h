// Implicit-function sensitivities of the forward problem (paper Eq. 5-7).
//
// At a solution s_hat(u) of the forward problem, G(s_hat(u), u) = dE/ds = 0
// for all u, hence  dG/ds * ds/du = -dG/du  with dG/ds the exact Hessian of E
// (including sum_i C_i Hess(C_i), which does not vanish while E > 0), and
// dE_r/du = dE/du at s_hat (the dE/ds term vanishes there).
// One sparse LDLT factorisation of dG/ds (block-sparse: a constraint couples
// at most two bodies) serves every right-hand side.
#ifndef CCMA_PROBLEMS_INTERNAL_SENSITIVITY_H_
#define CCMA_PROBLEMS_INTERNAL_SENSITIVITY_H_

#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include "ccma/internal/constraint_set.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// Factorises dG/ds = d2E/ds2 with a sparse LDLT whose symbolic analysis
// (fill-reducing ordering) is done once per model: the block pattern (6 x 6
// blocks of bodies that share a constraint) never changes.
class HessianSolver {
 public:
  explicit HessianSolver(const ConstraintSet& constraints);
  // Numeric factorisation of the dense symmetric H (n x n); entries outside
  // the block pattern are structurally zero and ignored.
  bool Factorize(const Eigen::MatrixXd& H);
  Eigen::MatrixXd Solve(const Eigen::MatrixXd& rhs) const { return ldlt_.solve(rhs); }
  // min pivot / max pivot of the last factorisation (see Sensitivity::rcond).
  double pivot_ratio() const { return pivot_ratio_; }

 private:
  Eigen::SparseMatrix<double> H_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  double pivot_ratio_ = 0;
};

// J_s * M for a (num_rows x k) result, reading only the nonzero blocks of
// J_s (each constraint touches at most two bodies).
Eigen::MatrixXd ConstraintJacobianTimes(const ConstraintSet& constraints, const Eigen::MatrixXd& J_s,
                                        const Eigen::MatrixXd& M);

class Sensitivity {
 public:
  // Evaluates the derivatives at (s, u) and factorises dG/ds. `controls`
  // are the indices into u that count as controls (typically
  // Model::effective_control_indices()).
  // `solver` and `workspace` (optional) are reused across calls: no symbolic
  // analysis and no allocation in a control loop. The workspace must outlive
  // this object.
  Sensitivity(const ConstraintSet& constraints, const State& s, const Eigen::VectorXd& u,
              const std::vector<int>& controls, HessianSolver* solver = nullptr,
              EnergyDerivatives* workspace = nullptr);
  Sensitivity(const Sensitivity&) = delete;
  Sensitivity& operator=(const Sensitivity&) = delete;

  const EnergyDerivatives& derivatives() const { return *d_; }
  // Conditioning figure of dG/ds: the ratio of the smallest to the largest
  // pivot of its LDLT factorisation (1 for a perfectly scaled matrix, ~0 at a
  // singular configuration, where ds/du is meaningless).
  double rcond() const { return rcond_; }
  bool singular() const { return singular_; }

  // ds/du over the chosen controls (n x k), tangent units per control unit.
  Eigen::MatrixXd StateSensitivity() const;
  // ds/du * du for one change du of the chosen controls (k): one solve.
  Eigen::VectorXd StateChange(const Eigen::VectorXd& du) const;
  // dE_r/du = dE/du at s (k), m^2 per control unit.
  Eigen::VectorXd ResidualEnergyGradient() const;
  // Adjoint: for a scalar F(s, u) with partials dF_ds (n) and dF_du (k),
  // the total derivative dF/du = dF_du - (dG/du)^T (dG/ds)^-1 dF_ds, with
  // one solve instead of k.
  Eigen::VectorXd TotalDerivative(const Eigen::VectorXd& dF_ds, const Eigen::VectorXd& dF_du) const;
  // dG/du over the chosen controls (n x k).
  const Eigen::MatrixXd& dG_du() const { return dG_du_; }

 private:
  EnergyDerivatives own_derivatives_;
  EnergyDerivatives* d_;
  Eigen::MatrixXd dG_du_;
  std::vector<int> controls_;
  std::unique_ptr<HessianSolver> own_solver_;
  HessianSolver* solver_;
  double rcond_ = 0;
  bool singular_ = true;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_SENSITIVITY_H_
