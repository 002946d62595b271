#include "analyses/configuration_difference.h"

#include <algorithm>

#include <Eigen/Geometry>

#include "analyses/internal/sparse_mobility.h"
#include "analyses/internal/sparse_rank.h"
#include "analyses/mobility.h"
#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/dense_factorizations.h"
#include "ccma/rotation.h"
#include "problems/forward_problem.h"

namespace ccma {
namespace {

// Rank decisions as AnalyzeMobility's default.
constexpr double kRankTolerance = 1e-8;

// An orthonormal basis of the null space of [dC/ds; dX/ds] at s (dense).
Eigen::MatrixXd DenseIdleMotions(const Model& model, const State& s, const Eigen::VectorXd& u) {
  const ConstraintSet constraints(model);
  Eigen::VectorXd C;
  Eigen::MatrixXd J_s, J_u;
  constraints.Evaluate(s, u, &C, &J_s, &J_u);
  const Eigen::MatrixXd X = EndEffectorJacobian(model, s);
  Eigen::MatrixXd M(J_s.rows() + X.rows(), J_s.cols());
  M << J_s, X;
  // Above kRankTolerance * max(1, sigma_max) counts; column-pivoting QR, as
  // the moved components (benchmarks/RESULTS.md, "Rank decisions").
  const double threshold = kRankTolerance * std::max(1.0, LargestSingularValue(SparseMatrixCol(M.sparseView())));
  return RankRevealingDecomposition(M, {threshold, 0.0}, RankRevealingDecomposition::Method::kPivotedQr).nullSpace();
}

// Whether the columns of `basis` move body b.
bool Moves(const Eigen::MatrixXd& basis, int b) {
  return basis.cols() > 0 &&
         basis.middleRows(kPoseTangentSize * b, kPoseTangentSize).cwiseAbs().maxCoeff() > kMovingBodyTolerance;
}

// The velocity of the point p_B of body b (world, [m] per unit motion)
// under each column of `basis`: dp + dtheta x (R_WB p_B) (state.h).
Eigen::MatrixXd PointMotion(const Eigen::MatrixXd& basis, const State& s, int b, const Eigen::Vector3d& p_B) {
  const Eigen::Vector3d r = s.R_WB(b) * p_B;
  Eigen::Matrix3d cross;
  cross << 0, r.z(), -r.y(), -r.z(), 0, r.x(), r.y(), -r.x(), 0;  // dtheta -> dtheta x r
  return cross * basis.middleRows(kPoseTangentSize * b, 3) + basis.middleRows(kPoseTangentSize * b + 3, 3);
}

// The idle motions at s: an orthonormal basis, or none when too many to
// list (then every body is compared in full).
Eigen::MatrixXd IdleMotions(const Model& model, const State& s, const Eigen::VectorXd& u) {
  if (model.state_size() <= kDenseMobilityStateSize) return DenseIdleMotions(model, s, u);
  Eigen::MatrixXd basis;
  if (!SparseIdleMotions(model, s, u, kRankTolerance, &basis)) return Eigen::MatrixXd(model.state_size(), 0);
  return basis;
}

// The largest difference between a and b (ds = b (-) a) that idle motions
// cannot make: whole bodies they leave still; on the bodies they move
// (listed in *idle), the joint points they leave still (a rod's ends).
double NonIdleDifference(const Model& model, const State& a, const State& b, const Eigen::VectorXd& ds,
                         const Eigen::MatrixXd& idle_basis, std::vector<int>* idle) {
  double largest = 0;
  for (int body = 0; body < model.num_bodies(); ++body) {
    const Eigen::VectorXd d = ds.segment(kPoseTangentSize * body, kPoseTangentSize);
    if (!Moves(idle_basis, body)) {
      largest = std::max(largest, d.cwiseAbs().maxCoeff());
      continue;
    }
    idle->push_back(body);
    for (const Joint& joint : model.joints) {
      if (joint.body_a != body && joint.body_b != body) continue;
      const Eigen::Vector3d& p = joint.body_a == body ? joint.p_A : joint.p_B;
      if (PointMotion(idle_basis, a, body, p).cwiseAbs().maxCoeff() > kMovingBodyTolerance) continue;
      const Eigen::Vector3d p_a = a.R_WB(body) * p + a.p_WB(body), p_b = b.R_WB(body) * p + b.p_WB(body);
      largest = std::max(largest, (p_b - p_a).cwiseAbs().maxCoeff());
    }
  }
  return largest;
}

}  // namespace

ConfigurationDifference CompareConfigurations(const Model& model, const State& a, const State& b,
                                              const Eigen::VectorXd& u) {
  ConfigurationDifference out;
  const EndEffectorPose pose_a = ComputeEndEffectorPose(model, a), pose_b = ComputeEndEffectorPose(model, b);
  out.end_effector_distance = (pose_b.position - pose_a.position).norm();
  out.end_effector_rotation =
      QuaternionLog(Eigen::Quaterniond(pose_b.rotation * pose_a.rotation.transpose()).normalized()).norm();
  const Eigen::VectorXd ds = b.Minus(a);
  out.max_state_difference = ds.size() > 0 ? ds.lpNorm<Eigen::Infinity>() : 0.0;
  const bool pose_same = out.end_effector_distance < kSameConfigurationTolerance &&
                         out.end_effector_rotation < kSameConfigurationTolerance;
  if (pose_same && out.max_state_difference >= kSameConfigurationTolerance) {
    out.max_state_difference = NonIdleDifference(model, a, b, ds, IdleMotions(model, a, u), &out.idle_bodies);
  }
  out.same = pose_same && out.max_state_difference < kSameConfigurationTolerance;
  return out;
}

FromHomeCheck CheckFromHome(const Model& model, const State& reached, const Eigen::VectorXd& u) {
  ForwardProblem from_home(model);
  FromHomeCheck check;
  check.assembled = from_home.Assemble(u).assembled;
  check.difference = CompareConfigurations(model, reached, from_home.state(), u);
  check.reproducible = check.assembled && check.difference.same;
  return check;
}

}  // namespace ccma
