// Fixed joint (0 DOF): welds bodies A and B.
//   r = [ p_B(r_B) - p_A(r_A) ;  d1_B - d1_A ;  d2_B - d2_A ]   9 rows, 6 independent
// d1, d2: two body-fixed directions (world x and y at home) expressed in A's
// and B's frames; equal world directions lock the relative rotation.
// Parameters: pose of A, pose of B (7 each, state.h).
#ifndef CCMA_COST_FUNCTIONS_FIXED_JOINT_COST_H_
#define CCMA_COST_FUNCTIONS_FIXED_JOINT_COST_H_

#include <ceres/sized_cost_function.h>

#include "cost_functions/body_frame.h"

namespace ccma {

class FixedJointCost final : public SizedCost<9, kPoseAmbientSize, kPoseAmbientSize> {
 public:

  FixedJointCost(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B,
                 const Eigen::Vector3d& d1_A, const Eigen::Vector3d& d1_B,
                 const Eigen::Vector3d& d2_A, const Eigen::Vector3d& d2_B)
      : r_A_(r_A), r_B_(r_B), d1_A_(d1_A), d1_B_(d1_B), d2_A_(d2_A), d2_B_(d2_B) {}

  void EvaluateInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/, double* residuals,
                        double** jacobians) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    double* J_A = JacobianOrNull(jacobians, 0);
    double* J_B = JacobianOrNull(jacobians, 1);
    ZeroIfRequested<kNumResiduals>(J_A);
    ZeroIfRequested<kNumResiduals>(J_B);
    PointDifference<kNumResiduals>(A, r_A_, B, r_B_, 0, residuals, J_A, J_B);
    DirectionDifference<kNumResiduals>(A, d1_A_, B, d1_B_, 3, residuals, J_A, J_B);
    DirectionDifference<kNumResiduals>(A, d2_A_, B, d2_B_, 6, residuals, J_A, J_B);
  }

  void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/,
                                  const double* weights, TangentHessian H) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    AddDifferenceHessian(A, r_A_, B, r_B_, Eigen::Map<const Eigen::Vector3d>(weights), H);
    AddDifferenceHessian(A, d1_A_, B, d1_B_, Eigen::Map<const Eigen::Vector3d>(weights + 3), H);
    AddDifferenceHessian(A, d2_A_, B, d2_B_, Eigen::Map<const Eigen::Vector3d>(weights + 6), H);
  }

 private:
  const Eigen::Vector3d r_A_, r_B_, d1_A_, d1_B_, d2_A_, d2_B_;
};


// ---- Autodiff twin (tests and the Jacobian benchmark) ----
// The same residual, templated; ceres::AutoDiffCostFunction differentiates
// it with respect to the ambient parameters (quaternion, translation).
struct FixedJointResidual {
  Eigen::Vector3d r_A, r_B, d1_A, d1_B, d2_A, d2_B;
  template <typename T>
  bool operator()(const T* pose_A, const T* pose_B, T* r) const {
    const BodyFrameT<T> A(pose_A), B(pose_B);
    Vec3Map<T>{r} = B.Point(r_B) - A.Point(r_A);
    Vec3Map<T>{r + 3} = B.Rotate(d1_B) - A.Rotate(d1_A);
    Vec3Map<T>{r + 6} = B.Rotate(d2_B) - A.Rotate(d2_A);
    return true;
  }
};

// Defined in autodiff_twins.cc, the one file that instantiates the twins' Jet code.
ceres::CostFunction* MakeFixedJointAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B, const Eigen::Vector3d& d1_A, const Eigen::Vector3d& d1_B, const Eigen::Vector3d& d2_A, const Eigen::Vector3d& d2_B);

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_FIXED_JOINT_COST_H_
