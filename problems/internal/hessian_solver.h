// dG/ds = d2E/ds2 factorised as P^T L D L^T P, for the implicit-function
// sensitivities (sensitivity.h), the forward problem's Newton polish and its
// predictor.
//
// dG/ds is symmetric but not always positive definite (E > 0 adds
// sum_i C_i Hess(C_i)), so this is an LDL^T without pivoting, whose pivots D
// are read as the conditioning figure (pivot_ratio, reported as `rcond`).
// P is the fill-reducing order (AMD on the scalar pattern), computed once per
// model. The numbers are those of a scalar sparse LDL^T of P H P^T in natural
// order (tests/hessian_solver_test.cc checks them against Eigen's
// SimplicialLDLT); the work is organised in dense 6 x 6 blocks of that
// permuted matrix (a body has 6 tangent coordinates, and AMD keeps a body's
// coordinates together, so the blocks are nearly all dense), over the fixed
// block pattern and update list of BlockElimination. Fixed-size block
// products replace the scalar loop's indexed updates: 2.5 times fewer
// instructions than Eigen's SimplicialLDLT on the paper's models (callgrind).
#ifndef CCMA_PROBLEMS_INTERNAL_HESSIAN_SOLVER_H_
#define CCMA_PROBLEMS_INTERNAL_HESSIAN_SOLVER_H_

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "ccma/state.h"
#include "problems/internal/block_elimination.h"

namespace ccma {

class HessianSolver {
 public:
  // Symbolic analysis of the constraint set's hessian_pattern(): the order P,
  // the block pattern of the factor and where each entry of H lands.
  explicit HessianSolver(const ConstraintSet& constraints);

  // Numeric factorisation of H, which must have the constraint set's
  // hessian_pattern() (EnergyDerivatives::H does). False if a pivot is zero
  // or not finite (then nothing else may be called but Factorize).
  bool Factorize(const SparseColMajor& H);
  // Whether the last factorisation succeeded (Solve and the rest are valid).
  bool factorized() const { return factorized_; }
  // min pivot / max |pivot| of the last factorisation (negative: H is
  // indefinite; see Sensitivity::rcond).
  double pivot_ratio() const { return pivot_ratio_; }
  // D (n), the pivots in permuted order.
  const Eigen::VectorXd& pivots() const { return D_; }
  // P, fixed per model: (P v)[P.indices()[i]] = v[i].
  using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;
  const Permutation& permutation() const { return P_; }

  // (dG/ds)^-1 rhs, for one or many right-hand sides (n or n x c).
  Eigen::VectorXd Solve(const Eigen::VectorXd& rhs) const;
  Eigen::MatrixXd Solve(const Eigen::MatrixXd& rhs) const;

  // The columns `columns` of a sparse n x c matrix M mapped to L^-1 P M, by
  // sparse forward substitution along the elimination tree: the work is that
  // of the blocks reached (a control's column is supported on its base's
  // body, whose path to the root is a few bodies), not n per column; four
  // columns at a time, over the union of their reaches. Entry lists per row
  // of the result, for the products of Sensitivity::ImplicitProducts:
  // rows[i] = {(column, value)}.
  struct SparseFactorColumns {
    std::vector<std::vector<std::pair<int, double>>> rows;  // n (permuted rows)
  };
  void ForwardSubstitute(const SparseColMajor& M, const std::vector<int>& columns, SparseFactorColumns* out) const;
  // L^-1 P v for a dense v (n).
  Eigen::VectorXd ForwardSubstitute(const Eigen::VectorXd& v) const;
  // Y <- L^-1 Y for the columns of Y (n x c), already in permuted order
  // ((P v)[permutation().indices()[i]] = v[i]): one pass over the factor for
  // all columns.
  void ForwardSubstitutePermuted(Eigen::MatrixXd* Y) const;
  // Three reusable dense matrices for callers of ForwardSubstitutePermuted
  // (resized only when their size changes).
  Eigen::MatrixXd* dense_scratch(int i) const { return &dense_scratch_[i]; }
  // Two reusable result buffers for ForwardSubstitute (their row lists keep
  // their capacity, so a control loop does not allocate after its first step).
  SparseFactorColumns* scratch(int i) const { return &scratch_[i]; }

 private:
  static constexpr int kB = kPoseTangentSize;  // block size
  using Block = Eigen::Matrix<double, kB, kB>;
  using BlockVector = Eigen::Matrix<double, kB, 1>;
  static constexpr int kGroup = 4;  // ForwardSubstitute's columns per pass
  using GroupWork = Eigen::Matrix<double, Eigen::Dynamic, kGroup, Eigen::RowMajor>;
  using GroupBlock = Eigen::Matrix<double, kB, kGroup, Eigen::RowMajor>;

  HessianSolver(const ConstraintSet& constraints, Permutation P);
  // Columns first .. first + Width - 1 of Y <- L^-1 of them (permuted order).
  template <int Width>
  void ForwardSubstituteColumns(Eigen::MatrixXd* Y, Eigen::Index first) const;
  // y <- L^-1 y and y <- L^-T y, y in permuted order (n).
  void ForwardInPlace(double* y) const;
  void BackwardInPlace(double* y) const;

  Permutation P_;
  BlockElimination elimination_;  // blocks of P H P^T, 6 x 6, and of its factor
  // Factorize's input: value k of H (its lower triangle, permuted into the
  // lower triangle of P H P^T) -> its place in factor_'s doubles (block * 36
  // + column-major offset), and the places no value of H lands on.
  std::vector<std::pair<int, int>> scatter_;
  std::vector<int> zeros_;
  // The factor, in elimination_'s layout: diagonal block j holds L_jj^-1
  // (unit lower triangular), the others L_ij. Factorize's input in place.
  std::vector<Block> factor_;
  std::vector<Block> scaled_;  // one column's L_ij D_j during Factorize
  Eigen::VectorXd D_;
  double pivot_ratio_ = 0;
  bool factorized_ = false;
  // ForwardSubstitute's work: the reached blocks, their marks, the dense
  // rows of a group of columns (zero between calls) and two result buffers.
  mutable std::vector<int> reach_, mark_;
  mutable GroupWork group_work_;
  mutable SparseFactorColumns scratch_[2];
  mutable Eigen::MatrixXd dense_scratch_[3];
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_HESSIAN_SOLVER_H_
