// The Ceres manifold of one body pose (see state.h for the storage).
//
// Plus(x, [dphi, dp]) = (Exp(dphi) * q, p + dp): a left, world-axis rotation
// increment, valid at every orientation (no Euler angles, no gimbal lock).
//
// "Lifted" Jacobian convention: ccma's analytic cost functions write, in the
// 7 columns of a pose's Jacobian block, the derivative with respect to the
// tangent increment (dphi: columns 0-2, dp: columns 3-5) and a zero column 6.
// PlusJacobian is therefore [I6; 0], so Ceres' product J * PlusJacobian is the
// tangent Jacobian itself, at no cost. Only ccma's cost functions may be used
// on blocks carrying this manifold.
#ifndef CCMA_INTERNAL_POSE_MANIFOLD_H_
#define CCMA_INTERNAL_POSE_MANIFOLD_H_

#include <ceres/manifold.h>

namespace ccma {

class PoseManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 7; }
  int TangentSize() const override { return 6; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool RightMultiplyByPlusJacobian(const double* x, int num_rows,
                                   const double* ambient_matrix,
                                   double* tangent_matrix) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

}  // namespace ccma

#endif  // CCMA_INTERNAL_POSE_MANIFOLD_H_
