// Control that compensates the deflection (cli.md, `ccma control
// --compensate`): the controls whose *loaded* end-effector (the nonlinear
// loaded equilibrium, problems/loaded_equilibrium.h) reaches the target; the
// rigid end-effector is then off target by about the deflection.
//
// Method: first the rigid control problem toward an aim (the target plus
// options.aim_offset), so that the large move gets a control step's limits,
// branch checks and conditioning; then Newton's method on the loaded
// equilibrium and the loaded end-effector error together, over the
// configuration and the effective controls
// (problems/internal/compensated_newton.h), from where the last loaded
// equilibrium's deflection puts the new rigid assembly: 3 to 4
// factorisations, the controls then taken by ControlProblem::CorrectTo
// (refused on differential bases, under a secondary objective, at a limit).
// Where that fails, rounds: the rigid control problem toward an aim moved
// by what the loaded end-effector missed (controlled components only, angles
// wrapped), each followed by the loaded equilibrium at its controls. The
// aim's correction is the deflection, whose change with the controls is
// small against the controls' own effect, so each round shrinks the miss by
// that ratio; Broyden updates of the aim's correction make the rounds
// converge superlinearly (5 to 10 rounds to 1e-10 m on a 6-DOF CCMA that
// deflects by centimetres). A later round the rigid problem does not reach
// from the previous round's controls is solved again from those the call
// began with (differential bases: the heading of a tiny move is ill-defined).
// Units: m, rad, N, N*m.
#ifndef CCMA_PROBLEMS_COMPENSATED_CONTROL_H_
#define CCMA_PROBLEMS_COMPENSATED_CONTROL_H_

#include <memory>
#include <optional>
#include <string>

#include "ccma/end_effector.h"
#include "ccma/loads.h"
#include "problems/control_problem.h"
#include "problems/loaded_equilibrium.h"

namespace ccma {

struct CompensationOptions {
  int max_rounds = 20;
  // The loaded end-effector within this of the target on every controlled
  // component [m or rad].
  double tolerance = 1e-10;
  // The first round's aim is target + aim_offset (position [m], rpy [rad]):
  // a path's previous step's correction starts the next step near its aim.
  Eigen::Matrix<double, 6, 1> aim_offset = Eigen::Matrix<double, 6, 1>::Zero();
  // Decide the returned loaded equilibrium's `held` (one dense
  // decomposition, several times a round's cost): a report wants it, a path's
  // steps do not.
  bool check_held = true;
  // The first round's loaded equilibrium starts from this one (a path's
  // previous step's) instead of the rigid assembly; later rounds start from
  // the round before.
  std::optional<LoadedEquilibrium> start;
  // The loaded equilibria's workspace (NewLoadedWorkspace), shared by a
  // path's steps; each call makes its own when not given.
  std::shared_ptr<LoadedWorkspace> workspace;
};

struct CompensatedResult {
  bool converged = false;      // the loaded end-effector reached the target
  int rounds = 0;              // rigid control problems solved, and the Newton finish (one round)
  ControlResult control;       // the last rigid round's (its error is the rigid end-effector's, to its aim)
  PoseTarget aim;              // the rigid end-effector's pose the returned controls aim at (controlled components)
  LoadedEquilibrium loaded;    // at the returned controls
  // max |target - loaded end-effector| over the controlled components [m or
  // rad]; where it did not converge, that of `loaded` as it is (at the
  // fraction of the loads it held when loaded.converged is false).
  double miss = 0;
  std::string warning;         // why it did not converge (empty when it did)
};

// target - reached on the controlled components [m, rad] (angles wrapped to
// (-pi, pi]); 0 on the others.
Eigen::Matrix<double, 6, 1> ControlledMiss(const Model& model, const PoseTarget& target, const EndEffectorPose& reached);

// Drives `control` (from its current controls) so that the loaded
// end-effector under gravity, the payload and `wrench` reaches `target`.
CompensatedResult MoveToCompensated(ControlProblem* control, const PoseTarget& target, const ExternalWrench& wrench = {},
                                    const CompensationOptions& options = {});

}  // namespace ccma

#endif  // CCMA_PROBLEMS_COMPENSATED_CONTROL_H_
