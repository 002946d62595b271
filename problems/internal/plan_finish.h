// Finishing a plan (problems/plan.h). The whole-path optimisation holds each
// step's clearance only to the trial slack of its constraints (1e-6 m), and
// checks consecutive steps only at their ends; the exact solve of each
// waypoint's step may start a hair below the margin and keep that as its
// floor. A finished plan holds:
//  - at every row, every clearance >= its floor (the margin, or the pair's
//    clearance at the row before when that is lower) to 1e-10 m: a row below
//    it is re-solved as a control step whose step constraints begin at the
//    row before (LmLoop::SolveStepFrom), which brings it back to the margin,
//    as a trajectory step would;
//  - half way between two rows (the mean of their controls, assembled from
//    the first), within kMidpointSlack of the floors: where a midpoint falls
//    lower (a base that rounds an obstacle in straight chords), the midpoint,
//    re-solved at the margin, becomes a row of its own, at most
//    kMaxMidpointSplits levels deep. A chord's sag shrinks four-fold with
//    each level; a jump through an obstacle does not, and is reported.
#ifndef CCMA_PROBLEMS_INTERNAL_PLAN_FINISH_H_
#define CCMA_PROBLEMS_INTERNAL_PLAN_FINISH_H_

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/state.h"
#include "problems/control_problem.h"
#include "problems/plan.h"
#include "problems/trajectory.h"

namespace ccma {

// How far [m] a midpoint may fall below its floor: the step constraints'
// trial slack.
constexpr double kMidpointSlack = 1e-6;
// Levels of midpoint rows inserted into one interval between two rows.
constexpr int kMaxMidpointSplits = 4;

// Restores the margin at every row of `rows` (a planned path from (u0, s0)),
// inserting midpoint rows as above; rows whose `leg` ends (the last row of
// a leg) are waypoint rows, solved to their target, the others to the pose
// they have. Returns the worst shortfall left (shortfall_m <= 1e-9 at rows
// and <= kMidpointSlack half way between them when the plan is finished).
// `progress(rows done, rows)` (optional) is called after every row.
PlanShortfall FinishPlan(ControlProblem& problem, const Eigen::VectorXd& u0, const State& s0,
                         double start_time, std::vector<TrajectoryStep>* rows, int* inserted_rows,
                         int* repaired_rows,
                         const std::function<void(int, int)>& progress = nullptr);

// What a shortfall means, for a warning: where (the plan's row, or half way
// between two rows, and the time), the pair, its clearance, and how far
// below the margin (or its floor), or that the midpoint does not assemble.
std::string DescribeShortfall(const PlanShortfall& shortfall, double margin);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_PLAN_FINISH_H_
