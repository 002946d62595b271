// Revolute joint (1 DOF) between bodies A and B: the paper's C_rev.
//   r = [ p_B(r_B) - p_A(r_A) ;  a_B - a_A ]          6 rows, 5 independent
// r_A, r_B: the joint point in A's and B's frames [m]; a_A, a_B: the unit
// axis in each frame. Parameters: pose of A, pose of B (7 each, state.h).
#ifndef CCMA_COST_FUNCTIONS_REVOLUTE_JOINT_COST_H_
#define CCMA_COST_FUNCTIONS_REVOLUTE_JOINT_COST_H_

#include <ceres/sized_cost_function.h>

#include "cost_functions/body_frame.h"

namespace ccma {

class RevoluteJointCost final : public SizedCost<6, kPoseAmbientSize, kPoseAmbientSize> {
 public:

  RevoluteJointCost(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B,
                    const Eigen::Vector3d& a_A, const Eigen::Vector3d& a_B)
      : r_A_(r_A), r_B_(r_B), a_A_(a_A), a_B_(a_B) {}

  void EvaluateInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/, double* residuals,
                        double** jacobians) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    double* J_A = JacobianOrNull(jacobians, 0);
    double* J_B = JacobianOrNull(jacobians, 1);
    ZeroIfRequested<kNumResiduals>(J_A);
    ZeroIfRequested<kNumResiduals>(J_B);
    PointDifference<kNumResiduals>(A, r_A_, B, r_B_, 0, residuals, J_A, J_B);
    DirectionDifference<kNumResiduals>(A, a_A_, B, a_B_, 3, residuals, J_A, J_B);
  }

  void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/,
                                  const double* weights, TangentHessian H) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    AddDifferenceHessian(A, r_A_, B, r_B_, Eigen::Map<const Eigen::Vector3d>(weights), H);
    AddDifferenceHessian(A, a_A_, B, a_B_, Eigen::Map<const Eigen::Vector3d>(weights + 3), H);
  }

 private:
  const Eigen::Vector3d r_A_, r_B_, a_A_, a_B_;
};


// ---- Autodiff twin (tests and the Jacobian benchmark) ----
// The same residual, templated; ceres::AutoDiffCostFunction differentiates
// it with respect to the ambient parameters (quaternion, translation).
struct RevoluteJointResidual {
  Eigen::Vector3d r_A, r_B, a_A, a_B;
  template <typename T>
  bool operator()(const T* pose_A, const T* pose_B, T* r) const {
    const BodyFrameT<T> A(pose_A), B(pose_B);
    Vec3Map<T>{r} = B.Point(r_B) - A.Point(r_A);
    Vec3Map<T>{r + 3} = B.Rotate(a_B) - A.Rotate(a_A);
    return true;
  }
};

// Defined in autodiff_twins.cc, the one file that instantiates the twins' Jet code.
ceres::CostFunction* MakeRevoluteJointAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B, const Eigen::Vector3d& a_A, const Eigen::Vector3d& a_B);

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_REVOLUTE_JOINT_COST_H_
