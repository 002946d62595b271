// A closed-loop replay of the paper's experiments (Section IV), simulated:
// the control solution of every path step is fed forward as base set-points
// (linear in time between steps), each base tracks its set-point with the PI
// controller from simulated motion capture, and the passive chain follows the
// bases' true poses by forward simulation. "Commanded" is the end-effector of
// the control solution (the paper's "simulated"), "tracked" the one the
// driven mechanism reaches (the paper's "tracked").
#ifndef CCMA_PROBLEMS_REPLAY_H_
#define CCMA_PROBLEMS_REPLAY_H_

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/base_tracking.h"
#include "ccma/waypoints.h"
#include "problems/control_problem.h"

namespace ccma {

struct ReplayOptions {
  TrackingGains gains;
  SimulationNoise noise;
  ControlOptions control;
  double output_hz = 20.0;  // samples of the end-effector and bases
  double settle_s = 1.0;    // kept running after the last waypoint
};

struct ReplaySample {
  double time = 0;                     // s
  Eigen::Matrix<double, 6, 1> commanded;  // x y z [m], roll pitch yaw [rad]
  Eigen::Matrix<double, 6, 1> tracked;
  Eigen::VectorXd set_controls;        // the bases' set poses (3 per base)
  Eigen::VectorXd true_controls;       // where the bases really are
  double residual_energy = 0;          // of the chain at the true base poses
};

struct ReplayResult {
  bool converged = true;    // every waypoint reached by the control solution
  std::string warning;
  std::vector<ReplaySample> samples;
  std::array<double, 6> rmse{};  // tracked vs commanded, per component
  double duration_s = 0;
};

ReplayResult Replay(const Model& model, const std::vector<Waypoint>& waypoints,
                    const ReplayOptions& options);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_REPLAY_H_
