// A change of controls that moves the whole mechanism rigidly.
//
// A mechanism without a joint to the ground (`world`) has constraints that
// are all relative (joint between two bodies) or tie a base body to its own
// control frame (x, y, theta) on the ground plane. Every one of them keeps
// its residual norm when the bodies and the control frames are moved by the
// same rigid motion T_W'W = (rotation about world z by dtheta, then a
// horizontal translation t). So when the new controls are the old ones moved
// by such a T (the bases drive in formation: the payload carried sideways or
// turned about a vertical axis), moving every body by T turns an assembled
// state into an assembled state for the new controls, exactly: the forward
// solve then ends without an iteration. The secant predictor only
// extrapolates, off by O(step^2 / radius) on a curved path.
#ifndef CCMA_PROBLEMS_INTERNAL_PLANAR_RIGID_MOTION_H_
#define CCMA_PROBLEMS_INTERNAL_PLANAR_RIGID_MOTION_H_

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// E [m^2] up to which the rigid image of a converged, assembled state counts
// as converged without an iteration. Each move adds the rounding of the
// moved poses (~1e-16 m per body), which piles up over thousands of moves;
// 1e-26 (constraint rows ~1e-13 m, far below the 1e-24 a reachable solve
// must end under) lets a long formation move run at a check per step, and
// the solver's iteration returns E to rounding level (~1e-31) past it.
constexpr double kRigidImageEnergy = 1e-26;

struct PlanarRigidMotion {
  double dtheta = 0;                          // rotation about world z [rad]
  Eigen::Vector2d t = Eigen::Vector2d::Zero();  // then translation in the ground plane [m]
};

// Whether no joint of `model` ends at the ground: only then does a rigid
// motion of everything keep every constraint (see above).
bool MovesRigidlyWithItsBases(const Model& model);

// Whether u_new = T(u_old) for one planar rigid motion T: every base's
// (x, y) mapped by T and its heading turned by dtheta (modulo 2 pi), every
// actuated joint's control unchanged, each to within 1e-10 times the largest
// change of a control plus the rounding of the controls (8 eps (1 + |u|)).
// The tolerance is relative to the change because a tiny change that is not
// rigid (an outer solver's last steps, ~1e-13) must not pass for one: near a
// singular configuration it moves the state far more than its size.
// Sets *motion. False for a model without bases, for u_new == u_old
// (nothing to predict) and for any non-finite control.
bool PlanarRigidMotionBetween(const Model& model, const Eigen::VectorXd& u_old, const Eigen::VectorXd& u_new,
                              PlanarRigidMotion* motion);

// Moves every body of `s` by `motion`: R_WB <- R_z(dtheta) R_WB,
// p_WB <- R_z(dtheta) p_WB + (t, 0).
void ApplyPlanarRigidMotion(const PlanarRigidMotion& motion, State* s);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_PLANAR_RIGID_MOTION_H_
