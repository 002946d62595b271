#include "problems/internal/end_effector_error.h"

#include <cmath>

#include "ccma/end_effector.h"
#include "ccma/rotation.h"

namespace ccma {
namespace {

// Inverse left Jacobian of SO(3): d Log(Exp(d) Exp(phi)) / dd at d = 0.
Eigen::Matrix3d InverseLeftJacobian(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  const Eigen::Matrix3d K = Skew(phi);
  if (theta < 1e-6) return Eigen::Matrix3d::Identity() - 0.5 * K + K * K / 12.0;
  const double c = 1.0 / (theta * theta) - (1.0 + std::cos(theta)) / (2.0 * theta * std::sin(theta));
  return Eigen::Matrix3d::Identity() - 0.5 * K + c * K * K;
}

}  // namespace

EndEffectorError::EndEffectorError(const Model& model) : model_(model) {
  const auto& c = model.end_effector.controlled;
  for (int k = 0; k < 3; ++k) {
    if (c[k]) position_.push_back(k);
  }
  full_rotation_ = c[kRoll] && c[kPitch] && c[kYaw];
  for (int k = 0; k < 3 && !full_rotation_; ++k) {
    if (c[3 + k]) angles_.push_back(k);
  }
  size_ = static_cast<int>(position_.size()) + (full_rotation_ ? 3 : static_cast<int>(angles_.size()));
}

void EndEffectorError::Evaluate(const State& s, const PoseTarget& target, Eigen::VectorXd* e,
                                Eigen::MatrixXd* de_ds) const {
  const EndEffectorPose pose = ComputeEndEffectorPose(model_, s);
  e->resize(size_);
  Eigen::MatrixXd X;  // d(position, rotation increment)/ds, 6 x n
  if (de_ds != nullptr) {
    X = EndEffectorJacobian(model_, s);
    de_ds->resize(size_, model_.state_size());
  }
  int row = 0;
  for (int k : position_) {
    (*e)[row] = pose.position[k] - target.position[k];
    if (de_ds != nullptr) de_ds->row(row) = X.row(k);
    ++row;
  }
  if (full_rotation_) {
    const Eigen::Matrix3d R_target = RotationFromRpy(target.rpy);
    const Eigen::Vector3d phi = QuaternionLog(Eigen::Quaterniond(pose.rotation * R_target.transpose()));
    e->segment<3>(row) = phi;
    // A coefficient-wise product: 3 x 3 by 3 x n is too small for the
    // blocked matrix product (its packing cost more than the arithmetic).
    if (de_ds != nullptr) de_ds->middleRows(row, 3).noalias() = InverseLeftJacobian(phi).lazyProduct(X.bottomRows(3));
  } else if (!angles_.empty()) {
    // World angular velocity w = E * d(rpy)/dt for R = Rz Ry Rx.
    const Eigen::Vector3d& rpy = pose.rpy;
    Eigen::Matrix3d E;
    E.col(0) = RotationZ(rpy.z()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
               Eigen::Vector3d::UnitX();
    E.col(1) = RotationZ(rpy.z()) * Eigen::Vector3d::UnitY();
    E.col(2) = Eigen::Vector3d::UnitZ();
    Eigen::Matrix3d E_inv = Eigen::Matrix3d::Zero();
    if (de_ds != nullptr) E_inv = E.inverse();
    for (int k : angles_) {
      (*e)[row] = WrapAngle(rpy[k] - target.rpy[k]);
      if (de_ds != nullptr) de_ds->row(row).noalias() = E_inv.row(k).lazyProduct(X.bottomRows(3));
      ++row;
    }
  }
}

}  // namespace ccma
