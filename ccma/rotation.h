// Rotation utilities: the one place for SO(3) maths in ccma.
//
// Conventions (see model_format.md):
//  * R_WB maps body-frame vectors into world: v_W = R_WB * v_B.
//  * rpy = [roll, pitch, yaw] with R = Rz(yaw) * Ry(pitch) * Rx(roll), radians.
//  * Orientation increments are rotation vectors applied on the LEFT, in world
//    axes: R <- Exp(dphi) * R. They never meet gimbal lock.
#ifndef CCMA_ROTATION_H_
#define CCMA_ROTATION_H_

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ccma {

// [w]x, the cross-product matrix: Skew(w) * v == w.cross(v).
template <typename T>
Eigen::Matrix<T, 3, 3> Skew(const Eigen::Matrix<T, 3, 1>& w) {
  Eigen::Matrix<T, 3, 3> S;
  S << T(0), -w.z(), w.y(),  //
      w.z(), T(0), -w.x(),   //
      -w.y(), w.x(), T(0);
  return S;
}

// Exp of a rotation vector (axis * angle, rad) as a unit quaternion.
// Accurate for tiny angles (second-order Taylor branch).
Eigen::Quaterniond QuaternionExp(const Eigen::Vector3d& rotation_vector);

// Log of a unit quaternion: the rotation vector, angle in [0, pi].
Eigen::Vector3d QuaternionLog(const Eigen::Quaterniond& q);

// R = Rz(yaw) * Ry(pitch) * Rx(roll); rpy in rad.
Eigen::Matrix3d RotationFromRpy(const Eigen::Vector3d& rpy);

// Inverse of RotationFromRpy: roll, yaw in (-pi, pi], pitch in [-pi/2, pi/2].
// At pitch = +-pi/2 (gimbal lock) roll is set to 0 and yaw carries the angle.
Eigen::Vector3d RpyFromRotation(const Eigen::Matrix3d& R);

// Rotation about z by `angle` rad.
Eigen::Matrix3d RotationZ(double angle);

// Wraps an angle into (-pi, pi].
double WrapAngle(double angle);

}  // namespace ccma

#endif  // CCMA_ROTATION_H_
