// The paper's control step (Section III-C): the end-effector moved 10 mm along
// (1, 1, 1) and turned 0.005 rad (about that axis when roll is controlled,
// else about z), shared by the benchmarks, and the benchmark loop over it.
#ifndef CCMA_BENCHMARKS_PAPER_STEP_H_
#define CCMA_BENCHMARKS_PAPER_STEP_H_

#include <benchmark/benchmark.h>

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

// Times control steps out to the paper step and back from the current pose,
// one per benchmark iteration; returns the fraction of steps reached.
inline double TimePaperStepsOutAndBack(benchmark::State& state, ControlProblem* control) {
  const PoseTarget targets[2] = {control->CurrentPose(),
                                 PaperStep(control->forward().model(), control->CurrentPose())};
  int which = 1;
  long steps = 0, reached = 0;
  for (auto _ : state) {
    reached += control->SolveStep(targets[which]).reached;
    which ^= 1;
    ++steps;
  }
  return steps > 0 ? double(reached) / steps : 0.0;
}

}  // namespace ccma

#endif  // CCMA_BENCHMARKS_PAPER_STEP_H_
