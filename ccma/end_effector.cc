#include "ccma/end_effector.h"

#include "ccma/rotation.h"

namespace ccma {

EndEffectorPose ComputeEndEffectorPose(const Model& model, const State& s) {
  const int body = model.end_effector.body;
  const Eigen::Matrix3d R_WB = s.R_WB(body);
  EndEffectorPose pose;
  pose.position = R_WB * model.end_effector.p_B + s.p_WB(body);
  pose.rotation = R_WB * model.bodies[body].R_WB_home.transpose();
  pose.rpy = RpyFromRotation(pose.rotation);
  return pose;
}

Eigen::MatrixXd EndEffectorJacobian(const Model& model, const State& s) {
  const int body = model.end_effector.body;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, model.state_size());
  const Eigen::Vector3d lever = s.R_WB(body) * model.end_effector.p_B;
  J.block<3, 3>(0, kPoseTangentSize * body) = -Skew(lever);
  J.block<3, 3>(0, kPoseTangentSize * body + 3).setIdentity();
  J.block<3, 3>(3, kPoseTangentSize * body).setIdentity();
  return J;
}

Eigen::MatrixXd ControlledRows(const Model& model, const Eigen::MatrixXd& six_rows) {
  int count = 0;
  for (int c = 0; c < 6; ++c) count += model.end_effector.controlled[c] ? 1 : 0;
  Eigen::MatrixXd rows(count, six_rows.cols());
  for (int c = 0, r = 0; c < 6; ++c) {
    if (model.end_effector.controlled[c]) rows.row(r++) = six_rows.row(c);
  }
  return rows;
}

}  // namespace ccma
