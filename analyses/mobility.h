// Numerical mobility of a CCMA system at a configuration (`ccma check`).
#ifndef CCMA_MOBILITY_H_
#define CCMA_MOBILITY_H_

#include <vector>

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// A body counts as moving in a free motion when one of its six state
// components (rad, m) exceeds this fraction of the motion's largest
// component: far above the rounding left in a null-space direction
// (~1e-13 relative), far below any motion a joint allows.
constexpr double kMovingBodyTolerance = 1e-6;

// Up to this state size (100 bodies) the analysis uses dense SVDs of the
// Jacobians (exact singular values; time ~ rows x columns^2); beyond it,
// sparse rank-revealing QR (SuiteSparseQR; time and memory ~ the
// Jacobians' nonzeros and the factor's fill: 1000 agents in seconds).
constexpr int kDenseMobilityStateSize = 600;
// The largest state size analysed (20,000 bodies): beyond it AnalyzeMobility
// refuses, as a work bound.
constexpr int kMaxMobilityStateSize = 120000;
// Beyond the dense size, the free motions with the controls fixed are listed
// only when state_size * dof_with_controls_fixed^2 stays below this (their
// basis is a dense state_size x dof matrix, rotated once per body that
// moves): e.g. up to 288 free motions at 1000 agents.
constexpr double kMaxFreeMotionWork = 1e9;

// A revolute or prismatic joint counts as moving in a free motion when its
// coordinate's rate along the motion (rad or m per unit of ds) exceeds this,
// and kMovingBodyTolerance times the motion's largest joint rate.
constexpr double kMovingJointRate = 1e-6;

// One free motion with the controls fixed: a direction ds of the state
// (state.h: 6 per body, rotation increment [rad] then translation [m], unit
// norm) with dC/ds ds = 0.
struct FreeMotion {
  Eigen::VectorXd direction;  // ds, size state_size
  std::vector<int> bodies;    // indices into Model::bodies of the bodies it moves, ascending
  // Indices into Model::joints of the revolute and prismatic joints whose
  // coordinate it changes (kMovingBodyTolerance times the largest rate, and
  // kMovingJointRate), ascending; a motion of spherical or universal joints
  // alone has none.
  std::vector<int> joints;
};

struct MobilityReport {
  int constraint_rows = 0;  // rows of C (cost_functions/: sizes stated there)
  int constraint_rank = 0;  // rank of dC/ds (controls fixed)
  // state_size - constraint_rank: free motions with the controls fixed.
  int dof_with_controls_fixed = 0;
  bool rigid_with_controls_fixed = false;
  // Free motions (ds, du_effective) when the effective controls move too.
  int dof_with_controls_free = 0;
  // Rank of dX_EE over those motions: how many end-effector DOF the bases drive.
  int end_effector_dof = 0;
  // The same when differential bases may only move along their heading
  // (instantaneously: no lateral velocity), except those whose heading turns
  // without moving the end-effector (they can face any direction first);
  // equals end_effector_dof without differential bases. Fewer than the controlled components: the
  // differential bases leave the end-effector no feasible motion in some
  // directions (e.g. posts welded to the bases).
  int end_effector_dof_nonholonomic = 0;
  double smallest_singular_value = 0;  // of dC/ds; ~0 means singular
  double energy = 0;                   // E(s, u)
  // A basis of the null space of dC/ds (dof_with_controls_fixed motions;
  // empty when rigid), chosen to name few bodies: body by body in file
  // order, the directions not yet assigned are rotated so that as few as
  // possible move that body; those become motions, the rest leave it still.
  // A leg whose post spins (carrying its link) and whose link also swings
  // alone gives the motions [post, link] and [link].
  std::vector<FreeMotion> free_motions;
  // False when free motions exist but were too many to list (above
  // kMaxFreeMotionWork): free_motions is then empty.
  bool free_motions_listed = true;
  // The control directions the mechanism can follow at home:
  // dof_with_controls_free - dof_with_controls_fixed. Fewer than the
  // effective controls: most control vectors cannot be assembled.
  int independent_controls = 0;
  // When some controls depend on others: true when only the planar controls
  // (x, y, heading) of wheeled bases do (moving any other effective control
  // alone can be followed): agents on the floor that carry one rigid frame,
  // over-actuated by design as the paper's systems are. Found up to
  // kDenseMobilityStateSize; false beyond.
  bool only_wheeled_bases_dependent = false;
};

// The mobility of `model` at state s and controls u (model.h). Ranks use
// singular values above rank_tolerance * max(1, largest singular value of
// dC/ds): dense SVDs up to kDenseMobilityStateSize, sparse QR beyond (then
// smallest_singular_value is found by inverse iteration, and is 0 when not
// rigid). Meant for analysis (`ccma check`), not for a control loop.
// Throws std::invalid_argument above kMaxMobilityStateSize.
MobilityReport AnalyzeMobility(const Model& model, const State& s, const Eigen::VectorXd& u,
                               double rank_tolerance = 1e-8);

// What the free motions of `mobility` (analysed at s) move of the
// end-effector, judged on |dX/ds * direction| <= 1e-8 over all listed motions.
enum class FreeMotionReach {
  kIdle,          // nothing: idle motions, such as a rod spinning about its
                  // axis (problems/internal/idle_motions.h)
  kUncontrolled,  // only components the model does not control (a tripod's
                  // apex spinning on its ball joints): what is controlled is
                  // determined by the controls
  kControlled,    // some controlled component: simulation and control are
                  // ill-posed; also when the motions are not listed
};
FreeMotionReach ReachOfFreeMotions(const Model& model, const State& s, const MobilityReport& mobility);

// How the effective controls relate at home (`ccma check`'s note or warning).
enum class ControlDependence {
  kIndependent,  // every effective control can move alone
  // Over-actuated by design: only wheeled bases' floor positions depend on
  // each other (the frame they carry ties them), or every independent
  // direction moves the end-effector and they drive all its controlled
  // components (redundant actuation, e.g. a motor beside the agents).
  kRedundantByDesign,
  // Anything else (a Stewart platform with UPU legs, legged bases under one
  // platform): most control vectors cannot be assembled.
  kDependent,
};
ControlDependence ClassifyControls(const Model& model, const MobilityReport& mobility);

}  // namespace ccma

#endif  // CCMA_MOBILITY_H_
