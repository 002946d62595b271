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

class UniversalJointCost final : public ceres::SizedCostFunction<4, 7, 7> {
 public:
  static constexpr int kNumResiduals = 4;

  UniversalJointCost(const Eigen::Vector3d& r_A, const Eigen::Vector3d& r_B,
                     const Eigen::Vector3d& a_A, const Eigen::Vector3d& b_B)
      : r_A_(r_A), r_B_(r_B), a_A_(a_A), b_B_(b_B) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const BodyFrame A(parameters[0]), B(parameters[1]);
    double* J_A = JacobianOrNull(jacobians, 0);
    double* J_B = JacobianOrNull(jacobians, 1);
    ZeroIfRequested<4>(J_A);
    ZeroIfRequested<4>(J_B);
    PointDifference<4>(A, r_A_, B, r_B_, 0, residuals, J_A, J_B);
    const Eigen::Vector3d a = A.Rotate(a_A_);
    const Eigen::Vector3d b = B.Rotate(b_B_);
    residuals[3] = a.dot(b);
    // d(a.b) = (dphi_A x a).b + a.(dphi_B x b) = dphi_A.(a x b) + dphi_B.(b x a)
    const Eigen::Vector3d a_cross_b = a.cross(b);
    if (J_A != nullptr) PoseJacobian<4>(J_A).block<1, 3>(3, 0) = a_cross_b.transpose();
    if (J_B != nullptr) PoseJacobian<4>(J_B).block<1, 3>(3, 0) = -a_cross_b.transpose();
    return true;
  }

 private:
  const Eigen::Vector3d r_A_, r_B_, a_A_, b_B_;
};

}  // namespace ccma

#endif  // CCMA_COST_FUNCTIONS_UNIVERSAL_JOINT_COST_H_
