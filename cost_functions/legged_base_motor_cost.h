// Motor constraint of a legged base (docs/model_format.md, "Legged agents"):
// the body frame of a quadruped that stands, walks, raises, lowers and tilts
// its body is driven to the pose its six controls name.
//   u = (x [m], y [m], heading [rad], height [m], roll [rad], pitch [rad])
//   R_t(u) = Rz(heading) Ry(pitch) Rx(roll),  p_t(u) = (x, y, height)
//   r = [ p_WB - p_t ;  R_WB e_x - R_t e_x ;  R_WB e_y - R_t e_y ]     9 rows, 6 independent
// Two body axes rather than a rotation's logarithm: smooth everywhere and
// exactly zero at the target, like the fixed joint's rows. The residual is
// f(pose) - g(u), so no second derivative couples state and controls.
// Parameters: pose of the base body (7, state.h), control block (6).
#ifndef CCMA_COST_FUNCTIONS_LEGGED_BASE_MOTOR_COST_H_
#define CCMA_COST_FUNCTIONS_LEGGED_BASE_MOTOR_COST_H_

#include <cmath>

#include <ceres/sized_cost_function.h>

#include "cost_functions/body_frame.h"

namespace ccma {

// Controls of a legged base, in their order in u.
constexpr int kLeggedControlSize = 6;

// R_t(u) = Rz(heading) Ry(pitch) Rx(roll) of a legged base's control block.
template <typename T>
Eigen::Matrix<T, 3, 3> LeggedBodyRotation(const T* u) {
  using std::cos;
  using std::sin;
  const T ch = cos(u[2]), sh = sin(u[2]), cr = cos(u[4]), sr = sin(u[4]), cp = cos(u[5]), sp = sin(u[5]);
  Eigen::Matrix<T, 3, 3> R;
  R << ch * cp, ch * sp * sr - sh * cr, ch * sp * cr + sh * sr,  //
      sh * cp, sh * sp * sr + ch * cr, sh * sp * cr - ch * sr,   //
      -sp, cp * sr, cp * cr;
  return R;
}

class LeggedBaseMotorCost final : public SizedCost<9, kPoseAmbientSize, kLeggedControlSize> {
 public:
  void EvaluateInFrames(const BodyFrame* const* frames, double const* const* parameters, double* residuals,
                        double** jacobians) const override {
    const BodyFrame& body = *frames[0];
    const double* u = parameters[1];
    const Eigen::Matrix3d R_t = LeggedBodyRotation(u);
    Eigen::Map<Eigen::Matrix<double, 9, 1>> r(residuals);
    r.head<3>() = body.p_WB - Eigen::Vector3d(u[0], u[1], u[3]);
    r.segment<3>(3) = body.R_WB.col(0) - R_t.col(0);
    r.segment<3>(6) = body.R_WB.col(1) - R_t.col(1);
    double* J_pose = JacobianOrNull(jacobians, 0);
    if (J_pose != nullptr) {
      PoseJacobian<kNumResiduals> J(J_pose);
      J.setZero();
      J.block<3, 3>(0, 3).setIdentity();
      J.block<3, 3>(3, 0) = -Skew(Eigen::Vector3d(body.R_WB.col(0)));
      J.block<3, 3>(6, 0) = -Skew(Eigen::Vector3d(body.R_WB.col(1)));
    }
    double* J_u = JacobianOrNull(jacobians, 1);
    if (J_u != nullptr) ControlJacobian(u, R_t, J_u);
  }

  void AddWeightedHessianInFrames(const BodyFrame* const* frames, double const* const* /*parameters*/,
                                  const double* weights, TangentHessian H) const override {
    const BodyFrame& body = *frames[0];
    H.block<3, 3>(0, 0) += RotationHessian(Eigen::Map<const Eigen::Vector3d>(weights + 3), body.R_WB.col(0)) +
                           RotationHessian(Eigen::Map<const Eigen::Vector3d>(weights + 6), body.R_WB.col(1));
  }

  // Rows 3-8 are (...) - R_t(u) e for e = e_x, e_y; position rows are
  // linear. Along u(t), R_t' = [w]x R_t with the angular velocity w = h' e_z
  // + p' a_pitch + r' a_roll (ControlJacobian's axes), so (R_t e)'' = w' x v +
  // w x (w x v), v = R_t e, where the axes turn: a_pitch' = h' e_z x a_pitch,
  // a_roll' = (h' e_z + p' a_pitch) x a_roll.
  void AddControlCurvature(double const* const* parameters, const double* du, double* out) const override {
    const double* u = parameters[1];
    const Eigen::Matrix3d R_t = LeggedBodyRotation(u);
    const double ch = std::cos(u[2]), sh = std::sin(u[2]), cp = std::cos(u[5]), sp = std::sin(u[5]);
    const Eigen::Vector3d e_z = Eigen::Vector3d::UnitZ(), a_pitch(-sh, ch, 0.0), a_roll(ch * cp, sh * cp, -sp);
    const double dh = du[2], dr = du[4], dp = du[5];
    const Eigen::Vector3d w = dh * e_z + dp * a_pitch + dr * a_roll;
    const Eigen::Vector3d w_dot = dp * (dh * e_z).cross(a_pitch) + dr * (dh * e_z + dp * a_pitch).cross(a_roll);
    for (int c = 0; c < 2; ++c) {
      const Eigen::Vector3d v = R_t.col(c);
      Eigen::Map<Eigen::Vector3d>(out + 3 + 3 * c) -= w_dot.cross(v) + w.cross(w.cross(v));
    }
  }

 private:
  // dr/du: -1 on x, y, height; a rotation's column v = R_t e turns about the
  // axis of each angle: d(R_t e)/d(angle) = axis x (R_t e), with the axes
  // e_z (heading), Rz e_y (pitch) and Rz Ry e_x (roll), all in world axes.
  static void ControlJacobian(const double* u, const Eigen::Matrix3d& R_t, double* out) {
    Eigen::Map<Eigen::Matrix<double, 9, kLeggedControlSize, Eigen::RowMajor>> J(out);
    J.setZero();
    J(0, 0) = J(1, 1) = J(2, 3) = -1.0;
    const double ch = std::cos(u[2]), sh = std::sin(u[2]), cp = std::cos(u[5]), sp = std::sin(u[5]);
    const Eigen::Vector3d axis_heading = Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d axis_pitch(-sh, ch, 0.0);
    const Eigen::Vector3d axis_roll(ch * cp, sh * cp, -sp);
    for (int c = 0; c < 2; ++c) {
      const Eigen::Vector3d v = R_t.col(c);
      J.block<3, 1>(3 + 3 * c, 2) = -axis_heading.cross(v);
      J.block<3, 1>(3 + 3 * c, 4) = -axis_roll.cross(v);
      J.block<3, 1>(3 + 3 * c, 5) = -axis_pitch.cross(v);
    }
  }
};

// ---- Autodiff twin (tests and the Jacobian benchmark) ----
struct LeggedBaseMotorResidual {
  template <typename T>
  bool operator()(const T* pose, const T* u, T* r) const {
    const BodyFrameT<T> body(pose);
    const Eigen::Matrix<T, 3, 3> R_t = LeggedBodyRotation(u);
    r[0] = body.p_WB.x() - u[0];
    r[1] = body.p_WB.y() - u[1];
    r[2] = body.p_WB.z() - u[3];
    for (int i = 0; i < 3; ++i) {
      r[3 + i] = body.R_WB(i, 0) - R_t(i, 0);
      r[6 + i] = body.R_WB(i, 1) - R_t(i, 1);
    }
    return true;
  }
};

// Defined in autodiff_twins.cc, the one file that instantiates the twins' Jet code.
ceres::CostFunction* MakeLeggedBaseMotorAutoDiff();

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_LEGGED_BASE_MOTOR_COST_H_
