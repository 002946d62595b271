// Linear static equilibrium of a compliant mechanism at one configuration
// (model_format.md, "Compliance"): the algebra of `ccma statics`'s
// compliance outputs (analyses/compliance.h), written so that the loaded
// equilibrium and its control and design uses can share it.
//
// Variables y = [ds; delta]: the state tangent (per body [dphi; dp], state.h)
// and one yield per compliant control (a base's x, y, theta when the base has
// `stiffness`, an actuated joint's q when its motor has one), in control
// order. A control's yield is what its motor rows see: C(s, u + delta).
//
// Rigid rows A y = 0: dC/ds of every constraint block, with dC/du on the
// compliant controls' columns acting on delta, except the block of a joint
// with `translation`/`rotation` stiffness; such a joint contributes instead
// its spring directions (ccma/internal/joint_spring_directions.h): those
// without a stiffness value as rigid rows, the others as springs. Springs
// S y with stiffness k (diagonal): the joints' spring directions and delta.
// Energy 1/2 y^T H y - f^T y with H = S^T diag(k) S, f = [Q; 0].
//
// Solution: Z = null(A) from one complete orthogonal decomposition of A^T
// (relative rank threshold 1e-10). Z splits into Z1, the motions that
// stretch some spring, and Z0 = null(S Z), the motions no spring resists:
// the rigid mechanism's own idle motions at held controls (a leg spinning
// about its axis), decided on the geometry S Z alone so that no stiffness
// value changes the split. K1 = Z1^T H Z1 is positive definite;
// y = Z1 K1^-1 Z1^T f (nothing along Z0), and the compliance of any linear
// measure G y is G Z1 K1^-1 Z1^T G^T. A measure that moves along Z0 is not
// held by the mechanism (UnheldMotion). The multipliers lambda solve
// A^T lambda = H y - f (least squares, minimum norm): a block's generalized
// force on the bodies is A_block^T lambda, as in equilibrium.h, and a
// control's effort -dC/du^T lambda (a compliant one's is -k delta).
// Dense, like equilibrium.h, and bounded by kMaxStaticsEntries.
#ifndef CCMA_PROBLEMS_INTERNAL_COMPLIANT_EQUILIBRIUM_H_
#define CCMA_PROBLEMS_INTERNAL_COMPLIANT_EQUILIBRIUM_H_

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "ccma/internal/constraint_set.h"
#include "ccma/internal/dense_factorizations.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// Rows of one joint: its own block's (or its rigid spring directions') rows
// in A, its motor's rows in A, and its springs' rows in S ({row, count}).
struct CompliantJointRows {
  int a_row = 0, a_rows = 0;
  int motor_row = 0, motor_rows = 0;
  int s_row = 0, s_rows = 0;
};

class CompliantEquilibrium {
 public:
  // How much of the decomposition the constructor makes.
  enum class Factorization {
    kNone,          // A, A_u, S and k only (a design adjoint's Lagrangian at
                    // nearby states, a Newton step): nothing that solves
                    // (Displacement, Multipliers, Compliance, UnheldMotion,
                    // determinate) may be called
    kIdleMotions,   // also the split of null(A) into Z1 and Z0: UnheldMotion only
    kEfforts,       // everything but determinate() (a trajectory row's efforts)
    kFull,          // everything
  };

  // Builds A, S, k at (s, u) and factorises. Throws std::invalid_argument
  // when a dense matrix would exceed kMaxStaticsEntries doubles.
  CompliantEquilibrium(const Model& model, const ConstraintSet& set, const State& s, const Eigen::VectorXd& u,
                       Factorization factorization = Factorization::kFull);

  // The compliant controls of a model, in the order of delta: every control
  // of a base with `stiffness`, then every actuated joint whose motor has one.
  static std::vector<int> CompliantControls(const Model& model);

  int state_size() const { return n_; }
  int size() const { return static_cast<int>(A_.cols()); }  // n + compliant controls
  const std::vector<int>& compliant_controls() const { return compliant_; }
  const Eigen::MatrixXd& A() const { return A_; }
  const Eigen::MatrixXd& A_u() const { return A_u_; }  // dC/du of A's rows, every control
  const Eigen::MatrixXd& S() const { return S_; }
  const Eigen::VectorXd& k() const { return k_; }
  const std::vector<CompliantJointRows>& joint_rows() const { return joint_rows_; }

  // Per row of A: its row in the constraint set, or -1 (a compliant joint's
  // rigid spring direction).
  const std::vector<int>& set_rows() const { return set_rows_; }

  // y for the generalized loads f (size()).
  Eigen::VectorXd Displacement(const Eigen::VectorXd& f) const;
  // The same with `extra` added to H on the motions springs resist (a
  // Newton step: the geometric stiffness of the preload); when
  // Z1^T (H + extra) Z1 is not positive definite (the preload softens the
  // mechanism past its springs), Displacement(f) and *newton = false.
  Eigen::VectorXd Displacement(const Eigen::VectorXd& f, const Eigen::MatrixXd& extra, bool* newton) const;
  // H y = S^T diag(k) S y.
  Eigen::VectorXd SpringForce(const Eigen::VectorXd& y) const;
  // lambda: A^T lambda = H y - f in least squares, minimum norm.
  Eigen::VectorXd Multipliers(const Eigen::VectorXd& y, const Eigen::VectorXd& f) const;
  // Every control's effort under the generalized loads Q (state size) [N
  // or N*m]: -dC/du^T lambda, a compliant control's -k delta; unique even
  // where the rigid mechanism is indeterminate. *unbalanced (if given): what
  // the springs and rigid rows leave of the loads [N or N*m].
  Eigen::VectorXd Efforts(const Eigen::VectorXd& Q, double* unbalanced = nullptr) const;
  // G Z1 K1^-1 Z1^T G^T for G (rows x size()), exactly symmetric.
  Eigen::MatrixXd Compliance(const Eigen::MatrixXd& G) const;
  // max |G Z0| relative to max |G|: 0 when no idle motion moves G y.
  double UnheldMotion(const Eigen::MatrixXd& G) const;
  // The rank of G Z1 (relative threshold 1e-10): how many independent
  // directions of the measure G (rows x size()) the sprung motions move,
  // decided on the geometry alone (Z1 is orthonormal), whatever the
  // stiffness values. Fewer than G's rows: some combination is held rigidly.
  int MovedDirections(const Eigen::MatrixXd& G) const;
  // max |Z0^T f|: the generalized force f (size()) along the motions no
  // spring resists, which no displacement can balance [N or N*m].
  double IdleForce(const Eigen::VectorXd& f) const;
  // The loads fix every joint's reaction and every control's effort: no
  // null vector of A^T moves them (equilibrium.h's test, on A).
  bool determinate() const { return determinate_; }

 private:
  void AddBlocks(const Model& model, const ConstraintSet& set, const Eigen::MatrixXd& J_s, const Eigen::MatrixXd& J_u,
                 const State& s);
  void Factorize(Factorization factorization);
  bool Determinate(int rank) const;

  int n_ = 0;
  std::vector<int> compliant_;           // control indices
  std::vector<int> delta_of_control_;    // per control: its column in delta, or -1
  Eigen::MatrixXd A_, A_u_, S_;
  Eigen::VectorXd k_;
  std::vector<CompliantJointRows> joint_rows_;
  std::vector<int> set_rows_;
  std::vector<std::pair<int, int>> groups_;  // the joints' row groups of A ({row, count})
  MinimumNormSolver cod_;  // of A^T
  Eigen::MatrixXd Z1_, Z0_;
  Eigen::LDLT<Eigen::MatrixXd> K1_;
  bool determinate_ = true;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_COMPLIANT_EQUILIBRIUM_H_
