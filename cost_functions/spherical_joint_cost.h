// Spherical joint (3 DOF) between bodies A and B: the paper's C_sph.
//   r = p_B(r_B) - p_A(r_A)                           3 rows
// r_A, r_B: the joint centre in A's and B's frames [m].
// Parameters: pose of A, pose of B (7 each, state.h).
#ifndef CCMA_COST_FUNCTIONS_SPHERICAL_JOINT_COST_H_
#define CCMA_COST_FUNCTIONS_SPHERICAL_JOINT_COST_H_

#include <ceres/sized_cost_function.h>

#include "cost_functions/body_frame.h"

namespace ccma {

class SphericalJointCost final : public SizedCost<3, kPoseAmbientSize, kPoseAmbientSize> {
 public:

  SphericalJointCost(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B)
      : r_A_(r_A), r_B_(r_B) {}

  void EvaluateInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/, double* residuals,
                        double** jacobians) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    double* J_A = JacobianOrNull(jacobians, 0);
    double* J_B = JacobianOrNull(jacobians, 1);
    ZeroIfRequested<kNumResiduals>(J_A);
    ZeroIfRequested<kNumResiduals>(J_B);
    PointDifference<kNumResiduals>(A, r_A_, B, r_B_, 0, residuals, J_A, J_B);
  }

  void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/,
                                  const double* weights, TangentHessian H) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    AddDifferenceHessian(A, r_A_, B, r_B_, Eigen::Map<const Eigen::Vector3d>(weights), H);
  }

 private:
  const Eigen::Vector3d r_A_, r_B_;
};


// ---- Autodiff twin (tests and the Jacobian benchmark) ----
// The same residual, templated; ceres::AutoDiffCostFunction differentiates
// it with respect to the ambient parameters (quaternion, translation).
struct SphericalJointResidual {
  Eigen::Vector3d r_A, r_B;
  template <typename T>
  bool operator()(const T* pose_A, const T* pose_B, T* r) const {
    const BodyFrameT<T> A(pose_A), B(pose_B);
    Vec3Map<T>{r} = B.Point(r_B) - A.Point(r_A);
    return true;
  }
};

// Defined in autodiff_twins.cc, the one file that instantiates the twins' Jet code.
ceres::CostFunction* MakeSphericalJointAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B);

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_SPHERICAL_JOINT_COST_H_
