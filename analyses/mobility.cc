#include "analyses/mobility.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>


#include "analyses/internal/sparse_mobility.h"
#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/dense_factorizations.h"
#include "ccma/joint_coordinates.h"
#include "analyses/internal/dense_rank.h"

namespace ccma {
namespace {

// The null space of J_s (its last n - rank right singular vectors), split
// body by body as MobilityReport::free_motions describes. The directions
// stay orthonormal: each split is a rotation within the unassigned span.
std::vector<FreeMotion> FreeMotions(const Eigen::MatrixXd& J_s, int rank) {
  const int n = static_cast<int>(J_s.cols());
  const JacobiSvd svd(J_s, Eigen::ComputeFullV);
  Eigen::MatrixXd unassigned = svd.matrixV().rightCols(n - rank);
  std::vector<FreeMotion> motions;
  for (int b = 0; b < n / kPoseTangentSize && unassigned.cols() > 0; ++b) {
    // Right singular vectors of this body's rows: the first `moving` mix the
    // directions into ones that move the body, the others leave it still.
    const JacobiSvd block(unassigned.middleRows(kPoseTangentSize * b, kPoseTangentSize),
                                                  Eigen::ComputeFullV);
    const int moving = RankAbove(block.singularValues(), kMovingBodyTolerance);
    if (moving == 0) continue;
    const Eigen::MatrixXd rotated = unassigned * block.matrixV();
    for (int k = 0; k < moving; ++k) motions.push_back({rotated.col(k), FreeMotionBodies(rotated.col(k)), {}});
    unassigned = rotated.rightCols(rotated.cols() - moving);
  }
  return motions;
}

// The end-effector DOF over the null space of A = [J_s, J_u_eff, ...] (its
// first n columns act on the state): rank of dX/ds over the null space's
// state parts. `free_dof` receives the null space's dimension.
int EndEffectorDof(const Model& model, const State& s, const Eigen::MatrixXd& A, double threshold,
                   double rank_tolerance, int* free_dof) {
  const int n = model.state_size();
  const JacobiSvd svd(A, Eigen::ComputeFullV);
  const int rank = RankAbove(svd.singularValues(), threshold);
  *free_dof = static_cast<int>(A.cols()) - rank;
  const Eigen::MatrixXd X = EndEffectorJacobian(model, s) * svd.matrixV().rightCols(*free_dof).topRows(n);
  return X.cols() > 0 ? RankAbove(JacobiSvd(X).singularValues(), rank_tolerance) : 0;
}

// One row over (ds, du_effective) per differential base that constrains the
// motion: no lateral velocity, -sin(theta) dx + cos(theta) dy = 0. A
// differential base whose heading turns without moving the end-effector (it
// turns on the spot under a revolute post) can face any direction first: it
// constrains nothing. Test: adding its heading column to [J_s; dX/ds] does
// not raise the rank.
Eigen::MatrixXd LateralRows(const Model& model, const State& s, const Eigen::VectorXd& u, const Eigen::MatrixXd& J_s,
                            const Eigen::MatrixXd& J_u, const std::vector<int>& effective, double threshold) {
  const int n = model.state_size(), k = static_cast<int>(effective.size());
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(model.num_bases(), n + k);
  int rows = 0;
  const Eigen::MatrixXd X_s = EndEffectorJacobian(model, s);
  Eigen::MatrixXd held(J_s.rows() + X_s.rows(), n + 1);
  held.setZero();
  held.topLeftCorner(J_s.rows(), n) = J_s;
  held.bottomLeftCorner(X_s.rows(), n) = X_s;
  const int held_rank = RankAbove(JacobiSvd(held.leftCols(n)).singularValues(), threshold);
  for (int b = 0; b < model.num_bases(); ++b) {
    if (model.mobile_bases[b].type != BaseType::kDifferential) continue;
    held.col(n).head(J_s.rows()) = J_u.col(model.base_control(b) + 2);
    if (RankAbove(JacobiSvd(held).singularValues(), threshold) == held_rank) continue;
    const double theta = u[model.base_control(b) + 2];
    for (int c = 0; c < k; ++c) {
      if (effective[c] == model.base_control(b)) L(rows, n + c) = -std::sin(theta);
      if (effective[c] == model.base_control(b) + 1) L(rows, n + c) = std::cos(theta);
    }
    ++rows;
  }
  return L.topRows(rows);
}

// Whether every effective control that cannot move alone (its column of
// dC/du outside the range of dC/ds: the state cannot follow it) is an x, y or
// heading of a wheeled (not legged) base. J = [J_s, J_u_eff].
bool OnlyWheeledBasesDependent(const Model& model, const Eigen::MatrixXd& J_s, const Eigen::MatrixXd& J,
                               int constraint_rank, const std::vector<int>& effective, double threshold) {
  const int n = static_cast<int>(J_s.cols());
  const Eigen::MatrixXd U = JacobiSvd(J_s, Eigen::ComputeThinU).matrixU().leftCols(constraint_rank);
  for (int c = 0; c < static_cast<int>(effective.size()); ++c) {
    const Eigen::VectorXd column = J.col(n + c);
    if ((column - U * (U.transpose() * column)).norm() <= threshold) continue;  // followable alone
    bool wheeled = false;
    for (int b = 0; b < model.num_bases(); ++b) {
      const int first = model.base_control(b);
      wheeled = wheeled || (model.mobile_bases[b].type != BaseType::kLegged && effective[c] >= first &&
                            effective[c] < first + 3);
    }
    if (!wheeled) return false;
  }
  return true;
}

// FreeMotion::joints of each motion: the coordinates' rates along the
// motion by a central difference (exact to about 1e-9 rad or m per unit of
// ds, far below kMovingJointRate).
void AddMovingJoints(const Model& model, const State& s, std::vector<FreeMotion>* motions) {
  constexpr double kStep = 1e-7;
  const double two_pi = 2 * std::acos(-1.0);
  std::vector<double> rate(model.joints.size());
  for (FreeMotion& motion : *motions) {
    State plus = s, minus = s;
    plus.Plus(kStep * motion.direction);
    minus.Plus(-kStep * motion.direction);
    double largest = 0;
    for (std::size_t j = 0; j < model.joints.size(); ++j) {
      const Joint& joint = model.joints[j];
      const double change = JointCoordinate(joint, plus) - JointCoordinate(joint, minus);
      // A revolute coordinate is wrapped into (-pi, pi]: undo a wrap between the two.
      rate[j] = std::abs(joint.type == JointType::kRevolute ? std::remainder(change, two_pi) : change) / (2 * kStep);
      largest = std::max(largest, rate[j]);
    }
    for (std::size_t j = 0; j < model.joints.size(); ++j) {
      if (rate[j] > kMovingJointRate && rate[j] > kMovingBodyTolerance * largest) {
        motion.joints.push_back(static_cast<int>(j));
      }
    }
  }
}

}  // namespace

MobilityReport AnalyzeMobility(const Model& model, const State& s, const Eigen::VectorXd& u,
                               double rank_tolerance) {
  const int n = model.state_size();
  if (n > kMaxMobilityStateSize) {
    throw std::invalid_argument("mobility analysis: state size " + std::to_string(n) + " (" +
                                std::to_string(model.num_bodies()) + " bodies) is above the bound of " +
                                std::to_string(kMaxMobilityStateSize) + " (" +
                                std::to_string(kMaxMobilityStateSize / kPoseTangentSize) + " bodies)");
  }
  const ConstraintSet constraints(model);
  MobilityReport report;
  report.constraint_rows = constraints.num_rows();
  if (n > kDenseMobilityStateSize) {
    Eigen::VectorXd C;
    constraints.Evaluate(s, u, &C);
    report.energy = 0.5 * C.squaredNorm();
    AnalyzeMobilitySparse(model, s, u, rank_tolerance, &report);
    AddMovingJoints(model, s, &report.free_motions);
    report.independent_controls = report.dof_with_controls_free - report.dof_with_controls_fixed;
    return report;
  }
  Eigen::VectorXd C;
  Eigen::MatrixXd J_s, J_u;
  constraints.Evaluate(s, u, &C, &J_s, &J_u);
  report.energy = 0.5 * C.squaredNorm();

  const JacobiSvd svd_s(J_s);
  const Eigen::VectorXd sigma = svd_s.singularValues();
  const double scale = std::max(1.0, sigma.size() > 0 ? sigma[0] : 0.0);
  report.constraint_rank = RankAbove(sigma, rank_tolerance * scale);
  report.dof_with_controls_fixed = n - report.constraint_rank;
  report.rigid_with_controls_fixed = report.dof_with_controls_fixed == 0;
  report.smallest_singular_value =
      sigma.size() >= n ? sigma[n - 1] : 0.0;  // fewer rows than columns: singular
  if (!report.rigid_with_controls_fixed) report.free_motions = FreeMotions(J_s, report.constraint_rank);
  AddMovingJoints(model, s, &report.free_motions);

  // Motions with the effective controls free: null space of [J_s, J_u_eff],
  // and of the same with no lateral velocity of the differential bases.
  const std::vector<int> effective = model.effective_control_indices();
  const int k = static_cast<int>(effective.size());
  Eigen::MatrixXd J(J_s.rows(), n + k);
  J.leftCols(n) = J_s;
  for (int c = 0; c < k; ++c) J.col(n + c) = J_u.col(effective[c]);
  report.end_effector_dof =
      EndEffectorDof(model, s, J, rank_tolerance * scale, rank_tolerance, &report.dof_with_controls_free);
  report.independent_controls = report.dof_with_controls_free - report.dof_with_controls_fixed;
  report.only_wheeled_bases_dependent = report.independent_controls < k &&
      OnlyWheeledBasesDependent(model, J_s, J, report.constraint_rank, effective, rank_tolerance * scale);
  const Eigen::MatrixXd L = LateralRows(model, s, u, J_s, J_u, effective, rank_tolerance * scale);
  if (L.rows() == 0) {
    report.end_effector_dof_nonholonomic = report.end_effector_dof;
  } else {
    Eigen::MatrixXd JL(J.rows() + L.rows(), n + k);
    JL << J, L;
    int free_dof = 0;
    report.end_effector_dof_nonholonomic = EndEffectorDof(model, s, JL, rank_tolerance * scale, rank_tolerance, &free_dof);
  }
  return report;
}

FreeMotionReach ReachOfFreeMotions(const Model& model, const State& s, const MobilityReport& mobility) {
  if (!mobility.free_motions_listed || mobility.free_motions.empty()) return FreeMotionReach::kControlled;
  const Eigen::MatrixXd dX_ds = EndEffectorJacobian(model, s);
  const Eigen::MatrixXd dXc_ds = ControlledRows(model, dX_ds);
  bool idle = true;
  for (const FreeMotion& motion : mobility.free_motions) {
    if ((dXc_ds * motion.direction).norm() > 1e-8) return FreeMotionReach::kControlled;
    idle = idle && (dX_ds * motion.direction).norm() <= 1e-8;
  }
  return idle ? FreeMotionReach::kIdle : FreeMotionReach::kUncontrolled;
}

ControlDependence ClassifyControls(const Model& model, const MobilityReport& mobility) {
  if (mobility.independent_controls >= static_cast<int>(model.effective_control_indices().size())) {
    return ControlDependence::kIndependent;
  }
  int controlled = 0;
  for (int c = 0; c < 6; ++c) controlled += model.end_effector.controlled[c] ? 1 : 0;
  const bool redundant = mobility.independent_controls == mobility.end_effector_dof && mobility.end_effector_dof >= controlled;
  return mobility.only_wheeled_bases_dependent || redundant ? ControlDependence::kRedundantByDesign
                                                            : ControlDependence::kDependent;
}

}  // namespace ccma
