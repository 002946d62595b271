// Precision of the end-effector (cli.md, `ccma statics`): its pose
// covariance from the bases' pose noise (the motion-capture model of the
// replay, execution/base_tracking.h SimulationNoise: sigma on each base's x,
// y and heading, independent), propagated to first order through
// dX/du = dX/ds ds/du (the implicit sensitivities):
//   Sigma_X = (dX/du) Sigma_u (dX/du)^T.
// X = [p_WE (m); rotation vector of the orientation change, world axes (rad)],
// the same 6 numbers as `ee_covariance`'s rows and columns. Actuated joints'
// controls carry no noise.
#ifndef CCMA_ANALYSES_PRECISION_H_
#define CCMA_ANALYSES_PRECISION_H_

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

struct BasePoseNoise {
  double position_sigma = 0.001;  // m, on x and y
  double heading_sigma = 0.003;   // rad
};

// ds/du over all controls (state tangent x num_controls) at an assembled
// (s, u); empty when dG/ds is singular there.
Eigen::MatrixXd StateControlSensitivity(const Model& model, const State& s, const Eigen::VectorXd& u);
// dX/ds (6 x state tangent) at s: position rows [m], rotation rows [rad].
Eigen::MatrixXd EndEffectorStateJacobian(const Model& model, const State& s);

// dX/du over all controls (6 x num_controls) at an assembled (s, u); empty
// when dG/ds is singular there.
Eigen::MatrixXd EndEffectorControlJacobian(const Model& model, const State& s, const Eigen::VectorXd& u);

// Sigma_X (6 x 6) [m^2, m rad, rad^2] at an assembled (s, u); NaN when dG/ds
// is singular there.
Eigen::Matrix<double, 6, 6> EndEffectorCovariance(const Model& model, const State& s, const Eigen::VectorXd& u,
                                                  const BasePoseNoise& noise);

// The end-effector's position standard deviation sqrt(trace Sigma_p) [m] at
// an assembled (s, u) under the bases' default pose noise (BasePoseNoise(),
// the replay's defaults); 0 where dG/ds is singular (`ccma workspace`'s
// ee_std_m).
double EndEffectorPositionStd(const Model& model, const State& s, const Eigen::VectorXd& u);

}  // namespace ccma

#endif  // CCMA_ANALYSES_PRECISION_H_
