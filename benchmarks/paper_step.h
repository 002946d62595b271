// The paper's control step (Section III-C): the end-effector moved 10 mm along
// (1, 1, 1) and turned 0.005 rad (about that axis when roll is controlled,
// else about z), shared by the benchmarks.
#ifndef CCMA_BENCHMARKS_PAPER_STEP_H_
#define CCMA_BENCHMARKS_PAPER_STEP_H_

#include "ccma/ccma.h"

namespace ccma {

inline PoseTarget PaperStep(const Model& m, const PoseTarget& home) {
  const Eigen::Vector3d direction = Eigen::Vector3d(1, 1, 1).normalized();
  PoseTarget t = home;
  t.position += 0.010 * direction;
  const Eigen::Vector3d axis = m.end_effector.controlled[kRoll] ? direction : Eigen::Vector3d::UnitZ();
  t.rpy = RpyFromRotation(QuaternionExp(0.005 * axis).toRotationMatrix() * RotationFromRpy(home.rpy));
  return t;
}

}  // namespace ccma

#endif  // CCMA_BENCHMARKS_PAPER_STEP_H_
