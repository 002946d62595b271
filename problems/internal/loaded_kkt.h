// The loaded equilibrium's Newton matrix (problems/internal/loaded_newton.h)
// assembled block by block into a sparsity pattern fixed per model.
//
// K = [H + eps_H I, A^T; A, -eps_A I] over y = [ds; delta] (the state
// tangent and the compliant controls' yields) and the rigid rows'
// multipliers mu, with A, S, k in CompliantEquilibrium's row order
// (problems/internal/compliant_equilibrium.h) and
//   H = S^T diag(k) S + sum_i w_i Hess(C_i) + the compliant joints' spring
//       curvature - dQ/ds,
// the last two by their symmetric parts (their skew parts are the
// rotations' own, world-frame increments composing on the left: 0 where the
// forces balance).
// A constraint block touches at most two bodies and one control block, a
// spring at most two bodies, a load one body: K's pattern is the union of
// those 6 x 6 (and rows x 6) blocks, known from the model alone. It is built
// once, so that the factorisation's symbolic analysis is made once per
// model, and each Newton step only overwrites the values: no dense n x n or
// m x n matrix, nothing allocated.
// Units: m, rad, N, N*m.
#ifndef CCMA_PROBLEMS_INTERNAL_LOADED_KKT_H_
#define CCMA_PROBLEMS_INTERNAL_LOADED_KKT_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "ccma/internal/constraint_set.h"
#include "ccma/loads.h"
#include "ccma/model.h"
#include "ccma/state.h"
#include "problems/internal/compliant_equilibrium.h"

namespace ccma {

// A configuration of the compliant mechanism: the state and the yield of
// each compliant control (CompliantEquilibrium::compliant_controls order).
struct LoadedPoint {
  State s;
  Eigen::VectorXd delta;
};

class LoadedKkt {
 public:
  using Sparse = Eigen::SparseMatrix<double>;
  using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

  // The layout and pattern of `model` with its constraint set `set`.
  LoadedKkt(const Model& model, const ConstraintSet& set);

  // Whether this is the layout of `model` with `set` (a workspace reused for
  // another model builds a new one).
  bool Fits(const Model& model, const ConstraintSet& set) const;

  int state_size() const { return n_; }
  int size() const { return N_; }                   // n + compliant controls
  int rigid_rows() const { return m_; }             // A's rows
  double stiffest() const { return stiffest_; }     // the largest k [N/m or N*m/rad], 1 without springs
  const std::vector<int>& compliant_controls() const { return compliant_; }
  const std::vector<int>& set_rows() const { return set_rows_; }  // per A row: its set row, or -1
  // A's multipliers mu in the constraint set's row order (0 on the rows A
  // does not have: a compliant joint's springs).
  Eigen::VectorXd SetOrder(const Eigen::VectorXd& mu) const;

  // At x, the controls as commanded u plus the yields x.delta: the rigid
  // rows' residual g, the springs' stretch e, the unbalanced generalized
  // force force = [Q; 0] - S^T k e, and K (both triangles) and A.
  // w (set order, num_rows) weighs the rigid rows' curvature; mu (A order,
  // or empty) the compliant joints' rigid directions'; eps_H, eps_A as above.
  void Assemble(const Model& model, const ConstraintSet& set, const LoadedPoint& x, const Eigen::VectorXd& u,
                const ExternalWrench& wrench, const Eigen::VectorXd& w, const Eigen::VectorXd& mu, double eps_H,
                double eps_A);

  // g, e and force at x, and reaction = A(x)^T mu (mu in A's order, the
  // last multipliers), K, A and A_u left as the last Assemble made them: a
  // chord step, the last factorisation solving for the new residuals
  // [force - reaction; -g] and the multipliers' change.
  void AssembleResiduals(const Model& model, const ConstraintSet& set, const LoadedPoint& x, const Eigen::VectorXd& u,
                         const ExternalWrench& wrench, const Eigen::VectorXd& mu);
  const Eigen::VectorXd& reaction() const { return reaction_; }

  const Sparse& K() const { return K_; }  // the lower triangle of the symmetric K
  double eps_H() const { return eps_H_; }  // as last assembled
  const RowSparse& A() const { return A_; }
  // dg/du over every control (rigid rows x num_controls): how the rigid
  // rows' residual moves with the commanded controls (a compliant one's
  // column is also A's on its yield).
  const Eigen::MatrixXd& A_u() const { return A_u_; }
  const Eigen::VectorXd& g() const { return g_; }
  const Eigen::VectorXd& e() const { return e_; }
  const Eigen::VectorXd& force() const { return force_; }

 private:
  struct SpringJoint {
    int joint = 0;
    int a_row = 0;  // its rigid directions' first row in A
    int s_row = 0;  // its springs' first row in S
  };

  static std::vector<double> Signature(const Model& model, const ConstraintSet& set);
  // The residuals, and with matrices_ K and A, at x.
  void Evaluate(const Model& model, const ConstraintSet& set, const LoadedPoint& x, const Eigen::VectorXd& u,
                const ExternalWrench& wrench, const Eigen::VectorXd& w, const Eigen::VectorXd& mu);
  void BuildPattern(const Model& model, const ConstraintSet& set);
  void AssembleBlocks(const ConstraintSet& set, const State& s, const Eigen::VectorXd& u_eff, const Eigen::VectorXd& w,
                      const Eigen::VectorXd& mu);
  void AddReaction(const ConstraintBlock& block, int a_row, const double* const* jacobians, const Eigen::VectorXd& mu);
  void AssembleSprings(const Model& model, const State& s, const Eigen::VectorXd& mu);
  // Where entry (row, col) of K (or of A) is in its values: found in the
  // pattern by the first assembly, which records the places in the order it
  // adds its entries (a tape); every later one adds the same entries in the
  // same order and reads them back.
  template <typename Sparse>
  int Where(const Sparse& M, int outer, int inner);
  // K(row0 + i, col0 + j) += M(i, j) on and below the diagonal.
  template <typename Derived>
  void AddToK(int row0, int col0, const Eigen::MatrixBase<Derived>& M);
  // A rigid row block at A row `a_row`, columns col0..: into A and K.
  template <typename Derived>
  void AddRigid(int a_row, int col0, const Eigen::MatrixBase<Derived>& M);
  // body_a's and body_b's 6 x 6 blocks of a 12 x 12 local matrix into K's H.
  void AddPair(int body_a, int body_b, const Eigen::Matrix<double, 12, 12>& local);

  std::vector<double> signature_;
  int n_ = 0, N_ = 0, m_ = 0, set_size_ = 0;
  double eps_H_ = 0;
  double stiffest_ = 1;
  std::vector<int> compliant_, delta_of_control_;
  Eigen::VectorXd k_;
  std::vector<int> set_rows_;
  std::vector<int> block_a_row_;  // per set block: its first row in A, or -1 (a compliant joint's own block)
  std::vector<SpringJoint> spring_joints_;
  Sparse K_;
  RowSparse A_;
  Eigen::MatrixXd A_u_;
  std::vector<int> tape_;
  size_t tape_position_ = 0;
  bool recording_ = true;
  bool matrices_ = true;  // Assemble (true) or AssembleResiduals
  Eigen::VectorXd g_, e_, force_, reaction_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_LOADED_KKT_H_
