// Motor constraints of an omnidirectional mobile base (paper: C_mx, C_my,
// C_mz), for both actuation schemes.
//   r = [ x_B - u_x ;  y_B - u_y ;  R_WB e_x - (cos u_theta, sin u_theta, 0) ]
// 5 rows. u = (u_x [m], u_y [m], u_theta [rad]) is the base's control block:
// the base frame's origin is driven to (u_x, u_y) and its x axis (heading) to
// u_theta. With reduced actuation the same rows hold the heading at the
// value in u, which the control solver then never changes (model.h).
// Parameters: pose of the base body (7, state.h), control block (3).
#ifndef CCMA_COST_FUNCTIONS_OMNI_BASE_MOTOR_COST_H_
#define CCMA_COST_FUNCTIONS_OMNI_BASE_MOTOR_COST_H_

#include <cmath>

#include <ceres/sized_cost_function.h>

#include "ccma/model.h"
#include "cost_functions/body_frame.h"

namespace ccma {

// Controls of a wheeled (omni or differential) base: x, y, theta.
constexpr int kWheeledControlSize = 3;

class OmniBaseMotorCost final : public SizedCost<5, kPoseAmbientSize, kWheeledControlSize> {
 public:

  void EvaluateInFrames(const BodyFrame* const* frames, double const* const* parameters, double* residuals,
                        double** jacobians) const override {
    const BodyFrame& base = *frames[0];
    const double* u = parameters[1];
    const Eigen::Vector3d heading_W = base.R_WB.col(0);
    const double c = std::cos(u[2]), s = std::sin(u[2]);
    residuals[0] = base.p_WB.x() - u[0];
    residuals[1] = base.p_WB.y() - u[1];
    residuals[2] = heading_W.x() - c;
    residuals[3] = heading_W.y() - s;
    residuals[4] = heading_W.z();
    double* J_base = JacobianOrNull(jacobians, 0);
    if (J_base != nullptr) {
      PoseJacobian<kNumResiduals> J(J_base);
      J.setZero();
      J(0, 3) = 1.0;
      J(1, 4) = 1.0;
      J.block<3, 3>(2, 0) = -Skew(heading_W);
    }
    double* J_u = JacobianOrNull(jacobians, 1);
    if (J_u != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 5, 3, Eigen::RowMajor>> J(J_u);
      J.setZero();
      J(0, 0) = -1.0;
      J(1, 1) = -1.0;
      J(2, 2) = s;
      J(3, 2) = -c;
    }
  }

  void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/,
                                  const double* weights, TangentHessian H) const override {
    const BodyFrame& base = *frames[0];
    H.block<3, 3>(0, 0) += RotationHessian(Eigen::Map<const Eigen::Vector3d>(weights + 2), base.R_WB.col(0));
  }

  // Rows 2-3 are (...) - (cos u_theta, sin u_theta); x and y enter linearly.
  void AddControlCurvature(double const* const* parameters, const double* du, double* out) const override {
    const double theta = parameters[1][2], dtheta2 = du[2] * du[2];
    out[2] += std::cos(theta) * dtheta2;
    out[3] += std::sin(theta) * dtheta2;
  }
};


// ---- Autodiff twin (tests and the Jacobian benchmark) ----
// The same residual, templated; ceres::AutoDiffCostFunction differentiates
// it with respect to the ambient parameters (quaternion, translation).
struct OmniBaseMotorResidual {
  template <typename T>
  bool operator()(const T* pose, const T* u, T* r) const {
    using std::cos;
    using std::sin;
    const BodyFrameT<T> base(pose);
    r[0] = base.p_WB.x() - u[0];
    r[1] = base.p_WB.y() - u[1];
    r[2] = base.R_WB(0, 0) - cos(u[2]);
    r[3] = base.R_WB(1, 0) - sin(u[2]);
    r[4] = base.R_WB(2, 0);
    return true;
  }
};

// Defined in autodiff_twins.cc, the one file that instantiates the twins' Jet code.
ceres::CostFunction* MakeOmniBaseMotorAutoDiff();

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_OMNI_BASE_MOTOR_COST_H_
