#include "benchmarks/simbody/circle_track.h"

#include <cmath>

#include "tests/leg_closed_form.h"

namespace ccma::simbody_benchmark {

const char* CirclePlaneName(CirclePlane plane) {
  return plane == CirclePlane::kHorizontal ? "horizontal" : "vertical";
}

CircleTrack MakeCircleTrack(const Model& model, CirclePlane plane, int steps, double radius_m) {
  // Copied from BM_ForwardTrack (benchmarks/forward_benchmark.cc): keep the two
  // identical so the Simbody comparison runs on the path the other benchmark times.
  CircleTrack track;
  const std::vector<testing::Leg> legs = testing::FindLegs(model);
  for (int k = 0; k <= steps; ++k) {
    const double angle = 2 * M_PI * k / steps;
    const Eigen::Vector3d offset = plane == CirclePlane::kHorizontal
                                       ? Eigen::Vector3d(std::cos(angle) - 1, std::sin(angle), 0)
                                       : Eigen::Vector3d(std::cos(angle) - 1, 0, std::sin(angle));
    const Eigen::Vector3d p_WE = model.end_effector.p_W_home + radius_m * offset;
    Eigen::VectorXd u = model.home_controls();
    for (const testing::Leg& leg : legs) {
      u.segment<3>(3 * leg.base) =
          testing::BasePoseForLeg(model, leg, p_WE, Eigen::Matrix3d::Identity(), 0.0);
    }
    track.controls.push_back(u);
    track.p_WE_target.push_back(p_WE);
  }
  return track;
}

}  // namespace ccma::simbody_benchmark
