// The motor of an actuated revolute joint between A and B: holds the joint
// coordinate q = q_home + (motion since home) (joint_coordinates.h) at its
// control u, in the cos/sin form of the bases' heading rows (smooth, no wrap):
//   r = [ (R_A e1_A) . (R_B w_B) - cos(u - q_home) ;  (R_A e2_A) . (R_B w_B) - sin(u - q_home) ]
// 2 rows. e1_A, e2_A = a_A x e1_A: directions perpendicular to the axis,
// fixed in A; w_B: B's copy of e1 at home, fixed in B. When the revolute
// joint itself holds, the two dot products are the cosine and sine of the
// motion since home. q_home [rad]: the coordinate's value at home (model.h).
// Parameters: pose of A, pose of B (7 each, state.h), control u (1, rad).
#ifndef CCMA_COST_FUNCTIONS_ACTUATED_REVOLUTE_COST_H_
#define CCMA_COST_FUNCTIONS_ACTUATED_REVOLUTE_COST_H_

#include <cmath>

#include "cost_functions/body_frame.h"

namespace ccma {

class ActuatedRevoluteCost final : public SizedCost<2, kPoseAmbientSize, kPoseAmbientSize, 1> {
 public:
  ActuatedRevoluteCost(const Eigen::Vector3d& e1_A, const Eigen::Vector3d& e2_A, const Eigen::Vector3d& w_B,
                       double q_home = 0.0)
      : e_A_{e1_A, e2_A}, w_B_(w_B), q_home_(q_home) {}

  void EvaluateInFrames(const BodyFrame* const* frames, double const* const* parameters, double* residuals,
                        double** jacobians) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    const double u = parameters[2][0] - q_home_;  // the motion since home the motor asks for
    const Eigen::Vector3d w = B.Rotate(w_B_);
    const double target[2] = {std::cos(u), std::sin(u)};
    double* J_A = JacobianOrNull(jacobians, 0);
    double* J_B = JacobianOrNull(jacobians, 1);
    double* J_u = JacobianOrNull(jacobians, 2);
    ZeroIfRequested<kNumResiduals>(J_A);
    ZeroIfRequested<kNumResiduals>(J_B);
    for (int row = 0; row < 2; ++row) {
      const Eigen::Vector3d e = A.Rotate(e_A_[row]);
      residuals[row] = e.dot(w) - target[row];
      // d(e . w) = dphi_A . (e x w) + dphi_B . (w x e)
      const Eigen::Vector3d e_cross_w = e.cross(w);
      if (J_A != nullptr) PoseJacobian<kNumResiduals>(J_A).block<1, 3>(row, 0) = e_cross_w.transpose();
      if (J_B != nullptr) PoseJacobian<kNumResiduals>(J_B).block<1, 3>(row, 0) = -e_cross_w.transpose();
    }
    if (J_u != nullptr) {
      J_u[0] = std::sin(u);   // d(-cos u)/du
      J_u[1] = -std::cos(u);  // d(-sin u)/du
    }
  }

  void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/,
                                  const double* weights, TangentHessian H) const override {
    const BodyFrame &A = *frames[0], &B = *frames[1];
    const Eigen::Vector3d w = B.Rotate(w_B_);
    for (int row = 0; row < 2; ++row) {
      // c (e . w), each factor turning with its own body (as the universal joint's dot product).
      const double c = weights[row];
      const Eigen::Vector3d e = A.Rotate(e_A_[row]);
      H.block<3, 3>(0, 0) += c * RotationHessian(w, e);
      H.block<3, 3>(6, 6) += c * RotationHessian(e, w);
      const Eigen::Matrix3d cross = c * Skew(e).transpose() * Skew(w);
      H.block<3, 3>(0, 6) += cross;
      H.block<3, 3>(6, 0) += cross.transpose();
    }
  }

  // r = (...) - (cos v, sin v) with v = u - q_home: (cos v, sin v) dv^2.
  void AddControlCurvature(double const* const* parameters, const double* du, double* out) const override {
    const double v = parameters[2][0] - q_home_, dv2 = du[0] * du[0];
    out[0] += std::cos(v) * dv2;
    out[1] += std::sin(v) * dv2;
  }

 private:
  const Eigen::Vector3d e_A_[2];
  const Eigen::Vector3d w_B_;
  const double q_home_;
};

// ---- Autodiff twin (tests and the Jacobian benchmark) ----
struct ActuatedRevoluteResidual {
  Eigen::Vector3d e1_A, e2_A, w_B;
  double q_home = 0.0;
  template <typename T>
  bool operator()(const T* pose_A, const T* pose_B, const T* u, T* r) const {
    using std::cos;
    using std::sin;
    const BodyFrameT<T> A(pose_A), B(pose_B);
    const Eigen::Matrix<T, 3, 1> w = B.Rotate(w_B);
    r[0] = A.Rotate(e1_A).dot(w) - cos(u[0] - q_home);
    r[1] = A.Rotate(e2_A).dot(w) - sin(u[0] - q_home);
    return true;
  }
};

// Defined in autodiff_twins.cc, the one file that instantiates the twins' Jet code.
ceres::CostFunction* MakeActuatedRevoluteAutoDiff(const Eigen::Vector3d& e1_A, const Eigen::Vector3d& e2_A,
                                                  const Eigen::Vector3d& w_B, double q_home = 0.0);

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_ACTUATED_REVOLUTE_COST_H_
