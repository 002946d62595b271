// The end-effector pose X_EE (model_format.md, "End-effector pose").
#ifndef CCMA_END_EFFECTOR_H_
#define CCMA_END_EFFECTOR_H_

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

struct EndEffectorPose {
  Eigen::Vector3d position;  // p_WE: the controlled point in world [m]
  Eigen::Matrix3d rotation;  // R_EE = R_WB(now) R_WB(home)^T, world axes
  Eigen::Vector3d rpy;       // rotation as [roll, pitch, yaw] [rad]
};

// A target pose for the end-effector: position [m] and the orientation
// R* = RotationFromRpy(rpy) [rad]; components the model does not control are
// ignored.
struct PoseTarget {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
};

EndEffectorPose ComputeEndEffectorPose(const Model& model, const State& s);

// d(X_EE)/ds (6 x state_size): rows 0-2 the position [m], rows 3-5 the
// rotation increment in world axes [rad] (R_EE <- Exp(dtheta) R_EE).
Eigen::MatrixXd EndEffectorJacobian(const Model& model, const State& s);

// The rows of a 6-row end-effector measure (x, y, z, roll, pitch, yaw order,
// as EndEffectorJacobian's) that the model's end_effector.controlled keeps,
// in that order: what held / rigid / stiff is judged on (a spin of the
// end-effector body about an axis nobody controls is not a failure).
Eigen::MatrixXd ControlledRows(const Model& model, const Eigen::MatrixXd& six_rows);

}  // namespace ccma

#endif  // CCMA_END_EFFECTOR_H_
