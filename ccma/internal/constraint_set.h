// All constraints C(s, u) of a model: one analytic cost function per joint
// (and its motor if actuated) and the blocks of each mobile base's type
// (ccma/base_kind.h: planar and motor for a wheeled base, one motor block for
// a legged base), built once from the Model.
//
// Row layout of C: the blocks in `blocks()` order (joints in file order, each
// followed by its motor when actuated, then per base its type's blocks);
// block b starts at blocks()[b].row.
// The cost functions are owned here and shared with Ceres problems.
#ifndef CCMA_INTERNAL_CONSTRAINT_SET_H_
#define CCMA_INTERNAL_CONSTRAINT_SET_H_

#include <memory>
#include <string>
#include <vector>

#include <ceres/cost_function.h>
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "ccma/model.h"
#include "ccma/state.h"
#include "cost_functions/body_frame.h"

namespace ccma {

struct ConstraintBlock {
  std::unique_ptr<ceres::CostFunction> cost;
  const FramedCost* framed = nullptr;  // the same object, evaluated at precomputed frames
  std::vector<int> bodies;  // pose blocks it reads, in parameter order (kWorld: the ground)
  int num_poses = 0;        // bodies.size(), for the hot loops
  int frames[2] = {0, 0};   // their entries in BodyFrames (the ground's last); unused: 0
  // The control block it reads, if any: u[control_offset .. + control_size)
  // (a mobile base's motor rows read its type's control block, at most kMaxBaseControls).
  int control_offset = -1;
  int control_size = 0;
  int row = 0;              // first row in C
  int rows = 0;
  std::string label;        // e.g. "joints[3] (revolute base0-post0)"
};

// The world frame of every body at one state, computed once per state
// (ConstraintSet::ComputeFrames) and shared by all the joints a body is in:
// entry b for body b, and the ground's (identity) last. A workspace: reused
// with the same model it is not reallocated.
using BodyFrames = std::vector<BodyFrame>;

using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using SparseColMajor = Eigen::SparseMatrix<double, Eigen::ColMajor>;

// E = 1/2 C^T C and its derivatives at (s, u), over the state tangent (n =
// 6 per body, state.h) and all controls (model.h).
// The matrices are sparse in patterns fixed per model (a constraint block
// touches at most two bodies and one control block), so that their size and
// the cost of filling them grow linearly with the mechanism: nothing here is
// dense n x n or m x n. A workspace reused across calls keeps its patterns
// and only has its values overwritten (no allocation).
struct EnergyDerivatives {
  Eigen::VectorXd C;      // constraints (m)
  SparseRowMajor J_s;     // dC/ds (m x n)
  SparseRowMajor J_u;     // dC/du (m x num_controls)
  Eigen::VectorXd G;      // dE/ds = J_s^T C (n)
  SparseColMajor H;       // d2E/ds2 = J_s^T J_s + sum_i C_i Hess(C_i) (n x n, both triangles), exact
  SparseColMajor dG_du;   // d2E/ds du = J_s^T J_u (n x num_controls), exact
  Eigen::VectorXd dE_du;  // dE/du = J_u^T C (num_controls)
  double energy = 0;
  BodyFrames frames;      // workspace: the bodies' frames at s
};

class ConstraintSet {
 public:
  explicit ConstraintSet(const Model& model);

  const std::vector<ConstraintBlock>& blocks() const { return blocks_; }
  int num_rows() const { return num_rows_; }
  int state_size() const { return state_size_; }
  int num_controls() const { return num_controls_; }

  // C(s, u) into `C` (size num_rows()); and, where not null, the dense
  // Jacobians J_s = dC/ds (num_rows x 6 n_bodies, tangent, see state.h) and
  // J_u = dC/du (num_rows x num_controls). u: the model's controls (model.h).
  void Evaluate(const State& s, const Eigen::VectorXd& u, Eigen::VectorXd* C,
                Eigen::MatrixXd* J_s = nullptr, Eigen::MatrixXd* J_u = nullptr) const;

  // All of EnergyDerivatives at (s, u), written straight into the fixed
  // sparse patterns below: H block by block (a constraint touches at most
  // two bodies), with the second-order terms.
  void EvaluateDerivatives(const State& s, const Eigen::VectorXd& u, EnergyDerivatives* out) const;

  // The fixed sparsity pattern of d2E/ds2 (n x n, both triangles, 6 x 6
  // blocks of bodies that share a constraint; values are placeholders), for
  // a symbolic factorisation done once.
  const SparseColMajor& hessian_pattern() const { return H_pattern_; }

  // The autodiff twin of every block's cost function, in blocks() order
  // (their Jacobians are with respect to the ambient pose parameters; see
  // cost_functions/*.h). For tests and the Jacobian benchmark.
  std::vector<std::unique_ptr<ceres::CostFunction>> MakeAutoDiffTwins(const Model& model) const;

  // The pose block of `body` in s, or the ground's (identity) for kWorld.
  static const double* Pose(const State& s, int body) { return body == kWorld ? kWorldPose : s.pose(body); }
  static const double kWorldPose[kPoseAmbientSize];  // identity rotation, origin

  // Every body's world frame at s into `frames` (see BodyFrames).
  void ComputeFrames(const State& s, BodyFrames* frames) const;

  // The frames of `block`'s pose blocks, in parameter order, from frames
  // computed by ComputeFrames for this model (the ground's for kWorld).
  static void BlockFrames(const ConstraintBlock& block, const BodyFrames& frames, const BodyFrame* out[2]) {
    out[0] = &frames[block.frames[0]];
    out[1] = &frames[block.frames[1]];
  }

  // E(s, u) = 1/2 C^T C [m^2], residuals only; `frames` is a workspace
  // (BodyFrames). The overload without one allocates it.
  double Energy(const State& s, const Eigen::VectorXd& u, BodyFrames* frames) const;
  double Energy(const State& s, const Eigen::VectorXd& u) const;

  // Adds sum_i w_i Hess_s(C_i) (s.tangent_size() squared, dense) into H, for
  // row weights w (num_rows(); a multiplier per row): the constraints'
  // curvature in a Lagrangian's Hessian (problems/loaded_equilibrium.h).
  void AddWeightedHessian(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& w, Eigen::MatrixXd* H) const;

  // h = d^2/dt^2 C(s (+) t ds, u + t du) at t = 0 (num_rows()): the
  // constraints' curvature along a motion (ds over the state tangent, du over
  // the controls), exact from the cost functions' second-order terms (no
  // term couples s and u at second order). Along an assembled motion
  // J_s s'' + J_u u'' + h(s', u') = 0 (analyses/dynamics.h). `frames` is a
  // workspace (BodyFrames). In constraint_curvature.cc.
  void CurvatureAlong(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& ds, const Eigen::VectorXd& du,
                      Eigen::VectorXd* h, BodyFrames* frames) const;

  // Where block b's derivatives land in the value arrays of the patterns
  // (indices into valuePtr()), computed once in the constructor. Public only
  // for the accumulation helper in constraint_set.cc.
  struct BlockOffsets {
    int J_s[2] = {-1, -1};        // row 0, first column of body p; rows step by J_s_row_stride
    int J_s_row_stride = 0;
    int J_u = -1;                 // row 0, first control; rows step by control_size
    int H[2][2] = {{-1, -1}, {-1, -1}};  // (6 a, 6 b) for bodies p, q; columns step by H_column_stride[q]
    int H_column_stride[2] = {0, 0};
    std::vector<int> dG_du[2];    // (6 a, control c) for body p, c < control_size
  };

 private:
  void BuildPatterns();

  std::vector<ConstraintBlock> blocks_;
  std::vector<BlockOffsets> offsets_;
  SparseRowMajor J_s_pattern_, J_u_pattern_;
  SparseColMajor H_pattern_, dG_du_pattern_;
  int num_rows_ = 0;
  int state_size_ = 0;
  int num_controls_ = 0;
};

}  // namespace ccma

#endif  // CCMA_INTERNAL_CONSTRAINT_SET_H_
