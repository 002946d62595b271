// Are two assembled configurations of a mechanism at the same controls the
// same, up to idle motions? (`ccma control`'s check that its controls,
// assembled from home, give its configuration: apps/control_command.cc.)
//
// An idle motion changes the state but nothing the constraints or the
// end-effector see: a rod spinning about its own axis between two ball
// joints, or between two stacks of revolute joints (problems/internal/
// idle_motions.h). Two configurations that differ only by one are not two
// assembly branches. The bodies idle motions move are found at the first
// configuration: the null space of [dC/ds; dX/ds] (the constraints held,
// the controls and the end-effector pose fixed); a body counts as moved when
// its six rows of that orthonormal basis exceed kMovingBodyTolerance
// (analyses/mobility.h). Of those bodies only the joint points the idle
// motions leave still are compared (a spinning rod's two ends); every other
// body, and the end-effector pose, in full.
#ifndef CCMA_ANALYSES_CONFIGURATION_DIFFERENCE_H_
#define CCMA_ANALYSES_CONFIGURATION_DIFFERENCE_H_

#include <vector>

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// Two configurations are the same when every difference below is under
// this [m, rad]: far above the solver's assembly tolerance (about 1e-12 m),
// far below a distinct assembly branch.
constexpr double kSameConfigurationTolerance = 1e-6;

struct ConfigurationDifference {
  double end_effector_distance = 0;  // |p_WE(a) - p_WE(b)| [m]
  double end_effector_rotation = 0;  // angle of R_EE(b) R_EE(a)^T [rad]
  // Largest component of b (-) a (state.h) over the bodies no idle motion
  // moves, and of the differences of the joint points idle motions leave
  // still on the others [m, rad].
  double max_state_difference = 0;
  // The bodies idle motions move at a, ascending (indices into
  // Model::bodies); found only when the raw state difference reaches the
  // tolerance and the end-effector poses agree (else empty).
  std::vector<int> idle_bodies;
  bool same = false;  // all three differences under kSameConfigurationTolerance
};

// a and b: states of `model` at the controls u (b's assembly is the
// caller's to check). Dense column-pivoting QR up to kDenseMobilityStateSize,
// sparse QR beyond; when the idle motions are too many to list there
// (kMaxFreeMotionWork), no body is left out.
ConfigurationDifference CompareConfigurations(const Model& model, const State& a, const State& b,
                                              const Eigen::VectorXd& u);

// Whether controls u that a path reached in configuration `reached` give the
// same configuration when assembled from home (`ccma simulate --controls`):
// not always, a path can lead to another assembly branch of the same
// controls. Idle motions (a rod spinning about its axis) are not branches.
struct FromHomeCheck {
  bool assembled = false;     // the assembly from home
  bool reproducible = false;  // assembled and the same configuration
  ConfigurationDifference difference;  // reached against the assembly from home
};
// One assembly from home (as long as a `ccma simulate`).
FromHomeCheck CheckFromHome(const Model& model, const State& reached, const Eigen::VectorXd& u);

}  // namespace ccma

#endif  // CCMA_ANALYSES_CONFIGURATION_DIFFERENCE_H_
