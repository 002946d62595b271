// Implicit-function sensitivities of the forward problem (paper Eq. 5-7).
//
// At a solution s_hat(u) of the forward problem, G(s_hat(u), u) = dE/ds = 0
// for all u, hence  dG/ds * ds/du = -dG/du  with dG/ds the exact Hessian of E
// (including sum_i C_i Hess(C_i), which does not vanish while E > 0), and
// dE_r/du = dE/du at s_hat (the dE/ds term vanishes there).
// One sparse LDLT factorisation of dG/ds (hessian_solver.h; block-sparse: a
// constraint couples at most two bodies) serves every right-hand side.
#ifndef CCMA_PROBLEMS_INTERNAL_SENSITIVITY_H_
#define CCMA_PROBLEMS_INTERNAL_SENSITIVITY_H_

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "ccma/model.h"
#include "ccma/state.h"
#include "problems/internal/hessian_solver.h"

namespace ccma {

class Sensitivity {
 public:
  // Evaluates the derivatives at (s, u) and factorises dG/ds. `controls`
  // are the indices into u that count as controls (typically
  // Model::effective_control_indices()).
  // `solver` and `workspace` (optional) are reused across calls: no symbolic
  // analysis and no allocation in a control loop. The workspace must outlive
  // this object.
  // `regularization` mu >= 0 factorises dG/ds + mu I instead (idle_motions.h).
  Sensitivity(const ConstraintSet& constraints, const State& s, const Eigen::VectorXd& u,
              const std::vector<int>& controls, HessianSolver* solver = nullptr,
              EnergyDerivatives* workspace = nullptr, double regularization = 0.0);
  Sensitivity(const Sensitivity&) = delete;
  Sensitivity& operator=(const Sensitivity&) = delete;

  const EnergyDerivatives& derivatives() const { return *d_; }
  // Conditioning figure of dG/ds: the ratio of the smallest to the largest
  // pivot of its LDLT factorisation (1 for a perfectly scaled matrix, ~0 at a
  // singular configuration, where ds/du is meaningless).
  double rcond() const { return rcond_; }
  bool singular() const { return singular_; }

  // ds/du over the chosen controls (n x k, dense: each control moves the
  // whole loop), tangent units per control unit. k sparse solves.
  Eigen::MatrixXd StateSensitivity() const;
  // ds/du * du for one change du of the chosen controls (k): one solve.
  Eigen::VectorXd StateChange(const Eigen::VectorXd& du) const;
  // dE_r/du = dE/du at s (k), m^2 per control unit.
  Eigen::VectorXd ResidualEnergyGradient() const;
  // Adjoint: for a scalar F(s, u) with partials dF_ds (n) and dF_du (k),
  // the total derivative dF/du = dF_du - (dG/du)^T (dG/ds)^-1 dF_ds, with
  // one solve instead of k.
  Eigen::VectorXd TotalDerivative(const Eigen::VectorXd& dF_ds, const Eigen::VectorXd& dF_du) const;
  // dG/du over the chosen controls times du (k): n, sparse work.
  Eigen::VectorXd dG_du_times(const Eigen::VectorXd& du) const;

  // Products with S = ds/du = -(dG/ds)^-1 B (B = dG/du over the chosen
  // controls) that never form S (dense n x k): with X = L^-1 P B sparse,
  //   B^T S = -X^T D^-1 X (k x k),  F S = -(L^-1 P F^T)^T D^-1 X for a
  //   matrix F (rows x n) with few nonzero columns (e.g. de/ds), and
  //   S^T v = -X^T D^-1 L^-1 P v (k).
  // Sparse: O(nonzeros reached + k^2 * shared rows), no n x k anywhere;
  // dense (small models, see ProductsPath): X itself. Returns false (and
  // leaves `out` alone) if dG/ds could not be factorised.
  struct Products {
    Eigen::MatrixXd BtS;  // k x k
    Eigen::MatrixXd FS;   // rows(F) x k
    Eigen::VectorXd Stv;  // k
  };
  // How: kSparse as above; kDense forms X = L^-1 P B and L^-1 P F^T as dense
  // n x k and n x rows(F) matrices (one forward substitution per column) and
  // multiplies them as matrices, which is faster while they are small; kAuto
  // takes kDense while n (k + rows(F)) <= kDenseProductsLimit, so a large
  // model never forms them.
  enum class ProductsPath { kAuto, kSparse, kDense };
  static constexpr Eigen::Index kDenseProductsLimit = 1 << 12;  // doubles (32 KiB)
  bool ImplicitProducts(const Eigen::MatrixXd& F, const Eigen::VectorXd& v, Products* out,
                        ProductsPath path = ProductsPath::kAuto) const;

 private:
  // The two paths of ImplicitProducts (dG/ds factorised).
  void DenseProducts(const Eigen::MatrixXd& F, const Eigen::VectorXd& v, Products* out) const;
  void SparseProducts(const Eigen::MatrixXd& F, const Eigen::VectorXd& v, Products* out) const;

  EnergyDerivatives own_derivatives_;
  EnergyDerivatives* d_;
  std::vector<int> controls_;
  std::unique_ptr<HessianSolver> own_solver_;
  HessianSolver* solver_;
  double rcond_ = 0;
  bool singular_ = true;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_SENSITIVITY_H_
