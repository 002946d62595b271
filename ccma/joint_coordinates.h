// Joint coordinates q of revolute and prismatic joints (docs/model_format.md,
// "Joint coordinates"): q_home (model.h, default 0) plus the motion since home:
//  * revolute between A and B with axis a: the angle [rad] by which B has
//    turned relative to A about a since home, right-handed about a as written
//    in the file; q_home plus that angle is reported in (-pi, pi];
//  * prismatic between A and B with axis a (fixed in A): the displacement
//    [m] of B's copy of the joint point relative to A's copy along a.
#ifndef CCMA_JOINT_COORDINATES_H_
#define CCMA_JOINT_COORDINATES_H_

#include <string>
#include <vector>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// q of `joint` at state s; 0 for joints without a coordinate.
double JointCoordinate(const Joint& joint, const State& s);

// q_home + motion, with a revolute joint's value wrapped into (-pi, pi].
double WrapJointCoordinate(const Joint& joint, double q);

// The coordinate q as limits compare it: a limited revolute joint's angle is
// taken within pi of the middle of its limits, so limits that straddle +-pi
// (possible once q_home moves them) stay one interval. Unchanged otherwise.
double LimitCoordinate(const Joint& joint, double q);

struct JointCoordinateReport {
  int joint = -1;    // index into Model::joints
  double q = 0;      // rad or m
  bool within_limits = true;  // lower - tolerance <= q <= upper + tolerance (or no limits)
};

// Every revolute and prismatic joint of the model, in file order. Limits are
// met within `tolerance` (rad or m).
std::vector<JointCoordinateReport> JointCoordinates(const Model& model, const State& s,
                                                    double tolerance = 1e-9);

// Names of the joints whose coordinate is outside its limits (within `tolerance`).
std::vector<std::string> LimitsViolated(const Model& model, const State& s, double tolerance = 1e-9);

}  // namespace ccma

#endif  // CCMA_JOINT_COORDINATES_H_
