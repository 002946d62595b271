// A closed-loop replay of the paper's experiments (Section IV), simulated:
// the control solution of every path step is fed forward as base set-points
// (linear in time between steps; a differential-drive base's set pose moves
// along the step's arc, ArcBetween, at constant speed and turn rate), each
// base tracks its set-point from simulated motion capture with its own kind
// of controller (omni: the PI BaseTracker; differential: the unicycle
// DifferentialTracker, the arc's speed and turn rate fed forward), actuated
// joints hold their set-points, and the passive chain follows the bases'
// true poses by forward simulation. "Commanded" is the end-effector of
// the control solution (the paper's "simulated"), "tracked" the one the
// driven mechanism reaches (the paper's "tracked").
//
// Honest reporting: a replay can fail in two ways, and both are in the result.
//  * The plan: a waypoint the control solution cannot reach (`converged`
//    false, `warning`, `failed_step_time`); the replay then ends there.
//  * The chain: bases that lag, oscillate or drift apart leave the chain
//    unable to assemble at their true poses (`torn`, per sample and overall:
//    residual energy above ReplayOptions::torn_residual_energy); its
//    "tracked" end-effector is then not a pose of the mechanism.
// Only a trustworthy() result's RMSE says how well the bases track.
#ifndef CCMA_PROBLEMS_REPLAY_H_
#define CCMA_PROBLEMS_REPLAY_H_

#include <array>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "execution/base_tracking.h"
#include "execution/gait.h"
#include "formats/waypoints.h"
#include "problems/control_problem.h"

namespace ccma {

struct ReplayOptions {
  TrackingGains gains;
  SimulationNoise noise;
  ControlOptions control;
  double output_hz = 20.0;  // samples of the end-effector and bases, [0.1, 1000] Hz
  double settle_s = 1.0;    // kept running after the last waypoint, [0, kMaxTime] s
  // A sample whose chain residual energy E = |C|^2 / 2 exceeds this [m^2] is
  // torn: the chain could not follow the bases (1e-5: constraints violated by
  // ~4.5 mm). It is far above the forward problem's assembly tolerance
  // (1e-16) on purpose: bases that track with sensing noise never sit exactly
  // where an over-constrained chain closes, so the chain is always strained a
  // little (E ~ 1e-7 with the default noise on the 4-DOF models and 48
  // agents), while a chain that cannot follow ends with E ~ 1e-2 or more
  // (0.2 s latency on 4dof_reduced). In (0, 1] m^2.
  double torn_residual_energy = 1e-5;
  // A legged base's body bobs and sways while it walks (execution/gait.h);
  // no effect on a model without legged bases.
  Gait gait;
  // Called after every solve of the chain with the solves done and their
  // total (the output samples, or with legged bases every controller tick):
  // a long replay's progress and its work bound (it may throw to stop it).
  std::function<void(long done, long total)> on_solve;

  // gains.IsValid, noise.IsValid, gait.IsValid, and output_hz, settle_s and
  // torn_residual_energy in range.
  // Otherwise false, with `why` (if not null) naming the field and its unit.
  bool IsValid(std::string* why) const;
  static constexpr double kMinOutputHz = 0.1;
  // With legged bases the gait is evaluated at every controller tick, at
  // least this many a gait period: gait.hz * 4 <= gains.rate_hz (Replay).
  static constexpr int kMinTicksPerGaitPeriod = 4;
  static constexpr double kMaxOutputHz = 1000.0;
};

struct ReplaySample {
  double time = 0;                     // s
  Eigen::Matrix<double, 6, 1> commanded;  // x y z [m], roll pitch yaw [rad]
  Eigen::Matrix<double, 6, 1> tracked;
  Eigen::VectorXd set_controls;        // the bases' set poses (their controls, then the joints')
  Eigen::VectorXd true_controls;       // where the bases really are
  double residual_energy = 0;          // of the chain at the true base poses [m^2]
  // residual_energy at most the forward problem's assembly tolerance: the
  // chain closes exactly (rare with tracking bases: even without noise their
  // lag leaves E ~ 1e-12).
  bool assembled = false;
  // residual_energy above ReplayOptions::torn_residual_energy (or not a
  // number): the chain could not follow the bases, `tracked` is no pose of it.
  bool torn = false;
  // Models with legged bases: the chain's end-effector at the same true
  // controls without the gait (the error due to tracking alone).
  Eigen::Matrix<double, 6, 1> tracked_without_gait = Eigen::Matrix<double, 6, 1>::Zero();
};

struct ReplayResult {
  bool converged = true;    // every waypoint reached by the control solution
  std::string warning;      // why not (the plan's message); empty if converged
  // Time [s] of the first plan step that did not reach its target; NaN if none.
  double failed_step_time = std::numeric_limits<double>::quiet_NaN();
  bool torn = false;        // some sample torn (see ReplaySample::torn)
  int torn_samples = 0;
  double first_torn_time = std::numeric_limits<double>::quiet_NaN();  // s; NaN if never torn
  double max_residual_energy = 0;  // over the samples [m^2]
  double torn_residual_energy = 0; // the E above which a sample is torn [m^2]
  std::vector<ReplaySample> samples;
  std::array<double, 6> rmse{};  // tracked vs commanded, per component (m, rad)
  // Models with legged bases (`gait` true): the RMSE of tracked against
  // tracked_without_gait (the gait's share) and of tracked_without_gait
  // against commanded (tracking's share), per component (m, rad). These and
  // `rmse` are then taken over every controller tick, the chain solved at
  // each (the output samples alone would alias the gait).
  bool gait = false;
  std::array<double, 6> gait_rmse{}, tracking_rmse{};
  double duration_s = 0;

  // Converged, never torn, with samples: only then does the RMSE measure tracking.
  bool trustworthy() const { return converged && !torn && !samples.empty(); }
};

// Whether `waypoints` and `options` make a bounded replay: options.IsValid,
// at least one waypoint, finite non-decreasing times in [-kMaxTime, kMaxTime],
// and a duration (waypoints plus settle_s) of at most kMaxReplayTicks
// controller ticks, kMaxReplayTicks plant steps and kMaxReplaySamples output
// samples (ccma/limits.h). Otherwise false, with `why` (if not null).
bool IsValidReplay(const std::vector<Waypoint>& waypoints, const ReplayOptions& options, std::string* why);

// The same for a replay of `model`: with legged bases also a controller rate
// of at least kMinTicksPerGaitPeriod times the gait's, and at most
// kMaxReplaySamples controller ticks (the chain is solved at each).
bool IsValidReplay(const Model& model, const std::vector<Waypoint>& waypoints, const ReplayOptions& options,
                   std::string* why);

// Throws std::invalid_argument (the message of IsValidReplay(model, ...))
// when the input is not valid; everything else is reported in the result.
ReplayResult Replay(const Model& model, const std::vector<Waypoint>& waypoints,
                    const ReplayOptions& options);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_REPLAY_H_
