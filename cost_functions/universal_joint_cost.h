// Universal joint (2 DOF) between bodies A and B.
//   r = [ p_B(r_B) - p_A(r_A) ;  (R_A a_A) . (R_B b_B) ]   4 rows
// a_A: the first axis, fixed in A; b_B: the second, fixed in B (unit, and
// perpendicular at home). The dot product keeps them perpendicular.
// Parameters: pose of A, pose of B (7 each, state.h).
#ifndef CCMA_COST_FUNCTIONS_UNIVERSAL_JOINT_COST_H_
#define CCMA_COST_FUNCTIONS_UNIVERSAL_JOINT_COST_H_

#include <ceres/sized_cost_function.h>

#include "cost_functions/body_frame.h"

namespace ccma {

class UniversalJointCost final : public SizedCost<4, kPoseAmbientSize, kPoseAmbientSize> {
 public:

  UniversalJointCost(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B,
                     const Eigen::Vector3d& a_A, const Eigen::Vector3d& b_B)
      : r_A_(r_A), r_B_(r_B), a_A_(a_A), b_B_(b_B) {}

  void EvaluateInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/, double* residuals,
                        double** jacobians) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    double* J_A = JacobianOrNull(jacobians, 0);
    double* J_B = JacobianOrNull(jacobians, 1);
    ZeroIfRequested<kNumResiduals>(J_A);
    ZeroIfRequested<kNumResiduals>(J_B);
    PointDifference<kNumResiduals>(A, r_A_, B, r_B_, 0, residuals, J_A, J_B);
    const Eigen::Vector3d a = A.Rotate(a_A_);
    const Eigen::Vector3d b = B.Rotate(b_B_);
    residuals[3] = a.dot(b);
    // d(a.b) = (dphi_A x a).b + a.(dphi_B x b) = dphi_A.(a x b) + dphi_B.(b x a)
    const Eigen::Vector3d a_cross_b = a.cross(b);
    if (J_A != nullptr) PoseJacobian<kNumResiduals>(J_A).block<1, 3>(3, 0) = a_cross_b.transpose();
    if (J_B != nullptr) PoseJacobian<kNumResiduals>(J_B).block<1, 3>(3, 0) = -a_cross_b.transpose();
  }

  void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/,
                                  const double* weights, TangentHessian H) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    AddDifferenceHessian(A, r_A_, B, r_B_, Eigen::Map<const Eigen::Vector3d>(weights), H);
    // c * (a . b): each factor turns with its own body; the cross term is
    // c (dphi_A x a) . (dphi_B x b) = c dphi_A^T [a]x^T [b]x dphi_B.
    const double c = weights[3];
    const Eigen::Vector3d a = A.Rotate(a_A_), b = B.Rotate(b_B_);
    H.block<3, 3>(0, 0) += c * RotationHessian(b, a);
    H.block<3, 3>(6, 6) += c * RotationHessian(a, b);
    const Eigen::Matrix3d cross = c * Skew(a).transpose() * Skew(b);
    H.block<3, 3>(0, 6) += cross;
    H.block<3, 3>(6, 0) += cross.transpose();
  }

 private:
  const Eigen::Vector3d r_A_, r_B_, a_A_, b_B_;
};


// ---- Autodiff twin (tests and the Jacobian benchmark) ----
// The same residual, templated; ceres::AutoDiffCostFunction differentiates
// it with respect to the ambient parameters (quaternion, translation).
struct UniversalJointResidual {
  Eigen::Vector3d r_A, r_B, a_A, b_B;
  template <typename T>
  bool operator()(const T* pose_A, const T* pose_B, T* r) const {
    const BodyFrameT<T> A(pose_A), B(pose_B);
    Vec3Map<T>{r} = B.Point(r_B) - A.Point(r_A);
    r[3] = A.Rotate(a_A).dot(B.Rotate(b_B));
    return true;
  }
};

// Defined in autodiff_twins.cc, the one file that instantiates the twins' Jet code.
ceres::CostFunction* MakeUniversalJointAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B, const Eigen::Vector3d& a_A, const Eigen::Vector3d& b_B);

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_UNIVERSAL_JOINT_COST_H_
