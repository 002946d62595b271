// The motor of an actuated prismatic joint between A and B: holds the joint
// coordinate q = q_home + a . (p_B(r_B) - p_A(r_A)) at its control u,
//   r = a . d - (u - q_home),   a = R_A a_A (unit, fixed in A),  d = p_B(r_B) - p_A(r_A)
// q_home [m]: the coordinate's value at home (model.h).
// 1 row. Parameters: pose of A, pose of B (7 each, state.h), control u (1, m).
// Linear in u: no control curvature (FramedCost::AddControlCurvature's default).
#ifndef CCMA_COST_FUNCTIONS_ACTUATED_PRISMATIC_COST_H_
#define CCMA_COST_FUNCTIONS_ACTUATED_PRISMATIC_COST_H_

#include "cost_functions/body_frame.h"

namespace ccma {

class ActuatedPrismaticCost final : public SizedCost<1, kPoseAmbientSize, kPoseAmbientSize, 1> {
 public:
  ActuatedPrismaticCost(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B, const Eigen::Vector3d& a_A,
                        double q_home = 0.0)
      : r_A_(r_A), r_B_(r_B), a_A_(a_A), q_home_(q_home) {}

  void EvaluateInFrames(const BodyFrame* const* frames, double const* const* parameters, double* residuals,
                        double** jacobians) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    const Eigen::Vector3d l_A = A.Rotate(r_A_), l_B = B.Rotate(r_B_);
    const Eigen::Vector3d d = (l_B + B.p_WB) - (l_A + A.p_WB);
    const Eigen::Vector3d a = A.Rotate(a_A_);
    residuals[0] = a.dot(d) - (parameters[2][0] - q_home_);
    double* J_A = JacobianOrNull(jacobians, 0);
    double* J_B = JacobianOrNull(jacobians, 1);
    double* J_u = JacobianOrNull(jacobians, 2);
    // d(a . d) = dphi_A . (a x d + a x l_A) - a . dp_A + dphi_B . (l_B x a) + a . dp_B
    if (J_A != nullptr) {
      PoseJacobian<kNumResiduals> J(J_A);
      J.setZero();
      J.block<1, 3>(0, 0) = (a.cross(d) + a.cross(l_A)).transpose();
      J.block<1, 3>(0, 3) = -a.transpose();
    }
    if (J_B != nullptr) {
      PoseJacobian<kNumResiduals> J(J_B);
      J.setZero();
      J.block<1, 3>(0, 0) = l_B.cross(a).transpose();
      J.block<1, 3>(0, 3) = a.transpose();
    }
    if (J_u != nullptr) J_u[0] = -1.0;
  }

  void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/,
                                  const double* weights, TangentHessian H) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    const double c = weights[0];
    const Eigen::Vector3d l_A = A.Rotate(r_A_), l_B = B.Rotate(r_B_);
    const Eigen::Vector3d d = (l_B + B.p_WB) - (l_A + A.p_WB);
    const Eigen::Vector3d a = A.Rotate(a_A_);
    // Hessian of a . d over [dphi_A, dp_A, dphi_B, dp_B] (as beta in prismatic_joint_cost.h).
    const Eigen::Matrix3d ax = Skew(a);
    const Eigen::Matrix3d aa = ax * Skew(l_A);
    H.block<3, 3>(0, 0) += c * (RotationHessian(d, a) - RotationHessian(a, l_A) + aa + aa.transpose());
    H.block<3, 3>(0, 3) += c * ax.transpose();
    H.block<3, 3>(3, 0) += c * ax;
    H.block<3, 3>(0, 6) += c * ax.transpose() * Skew(l_B);
    H.block<3, 3>(6, 0) += c * (ax.transpose() * Skew(l_B)).transpose();
    H.block<3, 3>(0, 9) += -c * ax.transpose();
    H.block<3, 3>(9, 0) += -c * ax;
    H.block<3, 3>(6, 6) += c * RotationHessian(a, l_B);
  }

 private:
  const Eigen::Vector3d r_A_, r_B_, a_A_;
  const double q_home_;
};

// ---- Autodiff twin (tests and the Jacobian benchmark) ----
struct ActuatedPrismaticResidual {
  Eigen::Vector3d r_A, r_B, a_A;
  double q_home = 0.0;
  template <typename T>
  bool operator()(const T* pose_A, const T* pose_B, const T* u, T* r) const {
    const BodyFrameT<T> A(pose_A), B(pose_B);
    r[0] = A.Rotate(a_A).dot(B.Point(r_B) - A.Point(r_A)) - (u[0] - q_home);
    return true;
  }
};

// Defined in autodiff_twins.cc, the one file that instantiates the twins' Jet code.
ceres::CostFunction* MakeActuatedPrismaticAutoDiff(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B,
                                                   const Eigen::Vector3d& a_A, double q_home = 0.0);

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_ACTUATED_PRISMATIC_COST_H_
