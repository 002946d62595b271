// The directions a joint does not allow, as linear rows over the tangents of
// its two bodies (ccma/stiffness.h gives their order): the springs of a
// compliant joint (model_format.md, "Compliance").
//
// Each row is the derivative of the relative pose of between[1] (B) with
// respect to between[0] (A), at the joint's current point P on B:
//   translation along a direction t fixed in A (t_W = R_A t_A):
//     t_A . d(R_A^T (P - p_A)),  P = R_B r_B + p_B
//     = t_W . (dp_B - (P - p_B) x dphi_B - dp_A + (P - p_A) x dphi_A)
//   rotation about a direction c (world):
//     c . (dphi_B - dphi_A), the relative rotation's increment
//     (R_A^T R_B <- Exp(R_A^T (dphi_B - dphi_A)) R_A^T R_B) on c.
// A rotation direction is fixed in A (n1, n2, A's axes) except a universal
// joint's, c = a x b / |a x b| with a = R_A a_A and b = R_B b_B at s.
// Exact at every state (not only where the joint holds); analytic, no
// finite differences.
#ifndef CCMA_INTERNAL_JOINT_SPRING_DIRECTIONS_H_
#define CCMA_INTERNAL_JOINT_SPRING_DIRECTIONS_H_

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

struct SpringDirections {
  int translations = 0;  // the first rows
  int rotations = 0;     // the next rows
  // rows() x 12 used; columns [dphi_A, dp_A, dphi_B, dp_B] (state.h); a
  // world end's columns are zero.
  Eigen::Matrix<double, 6, 12> D = Eigen::Matrix<double, 6, 12>::Zero();
  int rows() const { return translations + rotations; }
};

// The world pose of a joint's end: body b's frame, or the identity for the
// ground (kWorld).
struct JointEndFrame {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};
JointEndFrame JointEndFrameOf(const State& s, int body);

// n1 = x - (x.a)a normalised, x = (1, 0, 0) (or (0, 1, 0) where |x.a| > 0.9),
// for a unit axis a: the first direction normal to a, in a's frame.
Eigen::Vector3d FirstNormal(const Eigen::Vector3d& a);

// The joint's spring directions at s (all the directions it does not allow).
SpringDirections JointSpringDirections(const Joint& joint, const State& s);

}  // namespace ccma

#endif  // CCMA_INTERNAL_JOINT_SPRING_DIRECTIONS_H_
