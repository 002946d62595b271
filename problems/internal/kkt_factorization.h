// A factorisation of the loaded equilibrium's symmetric KKT matrices
// (problems/internal/loaded_newton.h) that keeps its symbolic analysis while
// their pattern stays within the one it was made for.
//
// The Newton iterations of one equilibrium, and the equilibria of nearby
// controls, factorise matrices of one structure whose numeric zeros come and
// go (a rotation's entry that vanishes at the home orientation, the rigid
// rows' curvature before the first multipliers). The analysis (a
// fill-reducing order and the factor's pattern) is made for the union of the
// patterns seen, padded with explicit zeros, and redone only when a matrix
// brings an entry outside it.
//
// Numerics: a sparse LDL^T without pivoting (Eigen's SimplicialLDLT, AMD
// order). The KKT matrix [H + eps_H I, A^T; A, -eps_A I] is symmetric
// quasi-definite where H + eps_H I is positive definite, and then every
// symmetric order factorises; elsewhere a pivot may vanish or the solution
// lose digits. A sparse LU with partial pivoting of the same matrix
// (SparseLU, analysed each time) takes over when the LDL^T fails, or when
// the caller finds its solution too inaccurate (UseLu).
#ifndef CCMA_PROBLEMS_INTERNAL_KKT_FACTORIZATION_H_
#define CCMA_PROBLEMS_INTERNAL_KKT_FACTORIZATION_H_

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

namespace ccma {

class KktFactorization {
 public:
  using Sparse = Eigen::SparseMatrix<double>;

  // Factorises the symmetric K (its lower triangle is read; the upper may
  // be stored or not): the LDL^T, or the LU when the LDL^T fails. False when neither could. K must outlive the
  // next UseLu (it may be factorised in place).
  bool Factorize(const Sparse& K);
  // Factorises the last K by the LU from now on; false when it fails.
  bool UseLu();
  // K^-1 rhs for the last factorised K.
  Eigen::VectorXd Solve(const Eigen::VectorXd& rhs) const;

  // Symbolic analyses of the LDL^T made so far (a test's view).
  int analyses() const { return analyses_; }
  // Whether the last K is solved by the LU.
  bool uses_lu() const { return use_lu_; }

 private:
  Sparse pattern_;  // the union of the patterns seen, values 0
  Sparse padded_;   // the last K on pattern_, where its own pattern differs
  const Sparse* factorized_ = nullptr;  // the last K or padded_
  Eigen::SimplicialLDLT<Sparse, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  Eigen::SparseLU<Sparse> lu_;
  bool use_lu_ = false;
  int analyses_ = 0;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_KKT_FACTORIZATION_H_
