// How far a joint is from holding, along the directions it does not allow:
// the stretch of a compliant joint's springs in the nonlinear loaded
// equilibrium (problems/loaded_equilibrium.h), one value per row of
// JointSpringDirections (ccma/internal/joint_spring_directions.h), in its
// order (ccma/stiffness.h).
//
//   translation along t (fixed in A):  t . (R_A^T (P - p_A) - p_A_joint)  [m]
//     with P = R_B p_B_joint + p_B, B's joint point in world;
//   rotation [rad], the angle of the relative rotation's error:
//     revolute   n . turn(a_A -> R_A^T R_B a_B) for n = n1, n2, where
//                turn(a -> v) is the rotation vector that turns a into v;
//     universal  -asin((R_A a_A) . (R_B b_B)), the axes' departure from square;
//     fixed, prismatic  Log(R_A^T R_B R_rest^T) on A's x, y, z, R_rest the
//                relative rotation at which the reference directions d1, d2
//                (and d1 x d2) of A and B coincide.
//   A bend about one axis by theta is theta exactly: a spring k on it holds
//   k theta.
// All are 0 where the joint holds, and their derivatives there are exactly
// JointSpringDirections' rows (the translations' everywhere).
#ifndef CCMA_INTERNAL_JOINT_DEVIATION_H_
#define CCMA_INTERNAL_JOINT_DEVIATION_H_

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// The joint's deviation at s: TranslationSpringCount + RotationSpringCount
// values (m, then rad-like).
Eigen::VectorXd JointDeviation(const Joint& joint, const State& s);

}  // namespace ccma

#endif  // CCMA_INTERNAL_JOINT_DEVIATION_H_
