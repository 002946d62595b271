// One model, three solvers, the same warm path in the same process: for each
// step of the circle track (circle_track.h) the base controls move, then
//   (a) Simbody System::projectQ: prescribe the bases' q at the step's time,
//       realize to Position, project the free q's (Newton on the constraint
//       equations, Simbody's pseudo-inverse for redundant ones) until the
//       largest constraint error is <= tolerance (infinity norm);
//   (b) Simbody Assembler::track(time): the Assembler study's repeated
//       assembly, constraint errors <= tolerance (infinity norm, its default),
//       on the same mechanism with its redundant equations disabled (its
//       optimiser needs independent ones: simbody_mechanism.h);
//   (c) ccma ForwardProblem::Solve(u): the default native solver, warm (and
//       the same without its predictors, secant and rigid-motion, for
//       reference),
// each from its own previous solution, on two schedules:
//  * interleaved step by step, so that all see the same machine load, in an
//    order that rotates from step to step (the first to run finds the caches
//    filled by the others): the end-effector point of (a) and (b) is
//    compared with ccma's at every step (outside the timed region);
//  * then alone: all laps of (c), then of (a), then of (b), each in its own
//    loop with its code and data left in the caches, as in a program that
//    runs one solver (end-effectors compared once more at the end).
// Each call is timed alone with steady_clock.
//
// What the two paths measure (circle_track.h): on the horizontal circle the
// reference models translate rigidly, so Simbody's joint coordinates do not
// change and both Simbody solvers only check the constraints (0 iterations);
// ccma, whose state is every body's absolute pose, recognises the bases'
// common rigid motion and moves every body by it (0 iterations as well).
// The vertical circle folds the legs: every solver has to iterate.
#ifndef CCMA_BENCHMARKS_SIMBODY_HEAD_TO_HEAD_H_
#define CCMA_BENCHMARKS_SIMBODY_HEAD_TO_HEAD_H_

#include <string>

#include "benchmarks/simbody/circle_track.h"
#include "benchmarks/simbody/step_samples.h"
#include "ccma/model.h"

namespace ccma::simbody_benchmark {

struct HeadToHeadOptions {
  CirclePlane plane = CirclePlane::kHorizontal;  // kHorizontal: BM_ForwardTrack's path
  int steps = 200;           // per lap of the circle (as BM_ForwardTrack)
  int laps = 10;             // the circle is closed: laps follow each other warm
  double radius_m = 0.05;    // circle radius [m]
  double tolerance = 1e-12;  // Simbody: largest constraint error [m, or cos for angles]
};

struct HeadToHeadResult {
  std::string model;
  std::string path;  // CirclePlaneName
  int steps = 0, laps = 0;
  double tolerance = 0;
  // Sizes: ccma's state (6 per body); Simbody's free mobilities (the bases'
  // are prescribed) and loop-closure equations.
  int ccma_state_size = 0, ccma_constraint_rows = 0;
  int simbody_free_mobilities = 0, simbody_tree_joints = 0, simbody_loop_joints = 0, simbody_constraint_equations = 0;
  int assembler_disabled_equations = 0;  // redundant ConstantAngle equations left out for (b)
  bool assembler_run = true;   // false: dependent equations remain, (b) not run
  std::string assembler_note;  // why (b) was not run

  StepSamples ccma, ccma_no_predictor, project_q, assembler_track;  // interleaved
  StepSamples ccma_alone, project_q_alone, assembler_track_alone;  // each in its own loop

  // Largest |p_WE(Simbody) - p_WE(ccma)| over all steps [m].
  double max_ee_difference_project_q_m = 0, max_ee_difference_track_m = 0;
  // Largest |p_WE(ccma) - closed-form target| over all steps [m] (the track's own check).
  double max_ee_error_ccma_m = 0;
  // Worst constraint error at the end of a step: ccma's sqrt(2 E) (the
  // 2-norm of its residual rows), Simbody's infinity norm as it reports it.
  double worst_residual_ccma = 0, worst_error_project_q = 0, worst_error_track = 0;
};

// Throws std::runtime_error if the model cannot be built in Simbody or has no
// closed-form track (prismatic or actuated joints, other leg shapes).
// Models whose loop closures stay dependent once the redundant ConstantAngle
// equations are disabled (4dof_complete: whole Ball rows) run without (b).
HeadToHeadResult RunHeadToHead(const Model& model, const HeadToHeadOptions& options);

}  // namespace ccma::simbody_benchmark

#endif  // CCMA_BENCHMARKS_SIMBODY_HEAD_TO_HEAD_H_
