// The warm paths of the Simbody head-to-head: the base controls that move the
// end-effector once round a circle of radius 5 cm, in 200 steps (~1.6 mm
// each), orientation held (controls in closed form from
// tests/leg_closed_form.h, no solver).
//  * kHorizontal: exactly BM_ForwardTrack's circle (benchmarks/forward_benchmark.cc),
//    so the numbers here and there describe the same motion. On the reference
//    models every base then moves by the end-effector's displacement: the
//    whole mechanism translates without deforming.
//  * kVertical: the same circle in the x-z plane. The end-effector rises and
//    falls, so the legs fold and unfold: the loop closures must be solved
//    at every step, in joint coordinates too (see head_to_head.h).
#ifndef CCMA_BENCHMARKS_SIMBODY_CIRCLE_TRACK_H_
#define CCMA_BENCHMARKS_SIMBODY_CIRCLE_TRACK_H_

#include <vector>

#include <Eigen/Core>

#include "ccma/model.h"

namespace ccma::simbody_benchmark {

enum class CirclePlane { kHorizontal, kVertical };
const char* CirclePlaneName(CirclePlane plane);  // "horizontal", "vertical"

struct CircleTrack {
  // controls[k], k = 0..steps: u (model.h: x [m], y [m], theta [rad] per
  // base); controls[0] is home and controls[steps] equals controls[0], so
  // laps can follow each other without a jump.
  std::vector<Eigen::VectorXd> controls;
  // p_WE_target[k]: where the closed form puts the end-effector point [m, world].
  std::vector<Eigen::Vector3d> p_WE_target;
  int steps() const { return static_cast<int>(controls.size()) - 1; }
};

// Throws std::runtime_error for a model whose legs have no closed form
// (tests/leg_closed_form.h: FRR, RRR, FRS, RRS, FRRU legs).
CircleTrack MakeCircleTrack(const Model& model, CirclePlane plane = CirclePlane::kHorizontal, int steps = 200,
                            double radius_m = 0.05);

}  // namespace ccma::simbody_benchmark

#endif  // CCMA_BENCHMARKS_SIMBODY_CIRCLE_TRACK_H_
