// Prismatic joint (1 DOF): no relative rotation, relative translation only
// along the axis a (fixed in body A).
//   r = [ d1_B - d1_A ;  d2_B - d2_A ;  (I - a a^T) (p_B(r_B) - p_A(r_A)) ]
// 9 rows (3 + 3 + 3), 5 independent. d1, d2 as in fixed_joint_cost.h;
// a = R_A a_A, unit. Parameters: pose of A, pose of B (7 each, state.h).
#ifndef CCMA_COST_FUNCTIONS_PRISMATIC_JOINT_COST_H_
#define CCMA_COST_FUNCTIONS_PRISMATIC_JOINT_COST_H_

#include <ceres/sized_cost_function.h>

#include "cost_functions/body_frame.h"

namespace ccma {

class PrismaticJointCost final : public SizedCost<9, kPoseAmbientSize, kPoseAmbientSize> {
 public:

  PrismaticJointCost(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B,
                     const Eigen::Vector3d& a_A, const Eigen::Vector3d& d1_A,
                     const Eigen::Vector3d& d1_B, const Eigen::Vector3d& d2_A,
                     const Eigen::Vector3d& d2_B)
      : r_A_(r_A), r_B_(r_B), a_A_(a_A), d1_A_(d1_A), d1_B_(d1_B), d2_A_(d2_A),
        d2_B_(d2_B) {}

  void EvaluateInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/, double* residuals,
                        double** jacobians) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    double* J_A = JacobianOrNull(jacobians, 0);
    double* J_B = JacobianOrNull(jacobians, 1);
    ZeroIfRequested<kNumResiduals>(J_A);
    ZeroIfRequested<kNumResiduals>(J_B);
    DirectionDifference<kNumResiduals>(A, d1_A_, B, d1_B_, 0, residuals, J_A, J_B);
    DirectionDifference<kNumResiduals>(A, d2_A_, B, d2_B_, 3, residuals, J_A, J_B);

    // d = p_B - p_A (with its Jacobians in rows 6-8, scratch), then project.
    PointDifference<kNumResiduals>(A, r_A_, B, r_B_, 6, residuals, J_A, J_B);
    const Eigen::Vector3d d(residuals[6], residuals[7], residuals[8]);
    const Eigen::Vector3d a = A.Rotate(a_A_);
    const double a_dot_d = a.dot(d);
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - a * a.transpose();
    Eigen::Map<Eigen::Vector3d>(residuals + 6) = d - a_dot_d * a;
    // r = P d: dr = P dd + (-(a.d) I - a d^T) da, with da = -[a]x dphi_A.
    if (J_A != nullptr) {
      PoseJacobian<kNumResiduals> J(J_A);
      const Eigen::Matrix<double, 3, 6> dd = J.block<3, 6>(6, 0);
      J.block<3, 6>(6, 0) = P * dd;
      J.block<3, 3>(6, 0) +=
          (a_dot_d * Eigen::Matrix3d::Identity() + a * d.transpose()) * Skew(a);
    }
    if (J_B != nullptr) {
      PoseJacobian<kNumResiduals> J(J_B);
      const Eigen::Matrix<double, 3, 6> dd = J.block<3, 6>(6, 0);
      J.block<3, 6>(6, 0) = P * dd;
    }
  }

  void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/,
                                  const double* weights, TangentHessian H) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    AddDifferenceHessian(A, d1_A_, B, d1_B_, Eigen::Map<const Eigen::Vector3d>(weights), H);
    AddDifferenceHessian(A, d2_A_, B, d2_B_, Eigen::Map<const Eigen::Vector3d>(weights + 3), H);
    // w . (d - a (a . d)) = w . d - alpha beta, alpha = w . a, beta = a . d.
    const Eigen::Vector3d w = Eigen::Map<const Eigen::Vector3d>(weights + 6);
    AddDifferenceHessian(A, r_A_, B, r_B_, w, H);  // w . d
    const Eigen::Vector3d l_A = A.Rotate(r_A_), l_B = B.Rotate(r_B_);
    const Eigen::Vector3d d = (l_B + B.p_WB) - (l_A + A.p_WB);
    const Eigen::Vector3d a = A.Rotate(a_A_);
    const double alpha = w.dot(a), beta = a.dot(d);
    // Gradients over [dphi_A, dp_A, dphi_B, dp_B] (12).
    Eigen::Matrix<double, 12, 1> g_alpha = Eigen::Matrix<double, 12, 1>::Zero();
    g_alpha.segment<3>(0) = a.cross(w);
    Eigen::Matrix<double, 12, 1> g_beta;
    g_beta << a.cross(d) + a.cross(l_A), -a, l_B.cross(a), a;
    // Hessians: alpha only through a (rotation of A); beta through a and d.
    Eigen::Matrix<double, 12, 12> h_beta = Eigen::Matrix<double, 12, 12>::Zero();
    const Eigen::Matrix3d ax = Skew(a);
    const Eigen::Matrix3d aa = ax * Skew(l_A);
    h_beta.block<3, 3>(0, 0) = RotationHessian(d, a) - RotationHessian(a, l_A) + aa + aa.transpose();
    h_beta.block<3, 3>(0, 3) = ax.transpose();
    h_beta.block<3, 3>(0, 6) = ax.transpose() * Skew(l_B);
    h_beta.block<3, 3>(0, 9) = -ax.transpose();
    h_beta.block<3, 3>(6, 6) = RotationHessian(a, l_B);
    h_beta.block<3, 3>(3, 0) = h_beta.block<3, 3>(0, 3).transpose();
    h_beta.block<3, 3>(6, 0) = h_beta.block<3, 3>(0, 6).transpose();
    h_beta.block<3, 3>(9, 0) = h_beta.block<3, 3>(0, 9).transpose();
    Eigen::Matrix<double, 12, 12> h = g_alpha * g_beta.transpose() + g_beta * g_alpha.transpose() +
                                      alpha * h_beta;
    h.block<3, 3>(0, 0) += beta * RotationHessian(w, a);
    H -= h;
  }

 private:
  const Eigen::Vector3d r_A_, r_B_, a_A_, d1_A_, d1_B_, d2_A_, d2_B_;
};


// ---- Autodiff twin (tests and the Jacobian benchmark) ----
// The same residual, templated; ceres::AutoDiffCostFunction differentiates
// it with respect to the ambient parameters (quaternion, translation).
struct PrismaticJointResidual {
  Eigen::Vector3d r_A, r_B, a_A, d1_A, d1_B, d2_A, d2_B;
  template <typename T>
  bool operator()(const T* pose_A, const T* pose_B, T* r) const {
    const BodyFrameT<T> A(pose_A), B(pose_B);
    Vec3Map<T>{r} = B.Rotate(d1_B) - A.Rotate(d1_A);
    Vec3Map<T>{r + 3} = B.Rotate(d2_B) - A.Rotate(d2_A);
    const Eigen::Matrix<T, 3, 1> d = B.Point(r_B) - A.Point(r_A);
    const Eigen::Matrix<T, 3, 1> a = A.Rotate(a_A);
    Vec3Map<T>{r + 6} = d - a * a.dot(d);
    return true;
  }
};

// Defined in autodiff_twins.cc, the one file that instantiates the twins' Jet code.
ceres::CostFunction* MakePrismaticJointAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B, const Eigen::Vector3d& a_A, const Eigen::Vector3d& d1_A, const Eigen::Vector3d& d1_B, const Eigen::Vector3d& d2_A, const Eigen::Vector3d& d2_B);

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_PRISMATIC_JOINT_COST_H_
