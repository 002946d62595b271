#include "analyses/precision.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "problems/internal/end_effector_error.h"
#include "problems/internal/hessian_solver.h"
#include "problems/internal/sensitivity.h"

namespace ccma {

Eigen::MatrixXd EndEffectorStateJacobian(const Model& model, const State& s) {
  // All six components, at the current pose: e = [p - p*, Log(R R*^T)] and
  // de/ds there is dX/ds.
  Model all = model;
  all.end_effector.controlled.fill(true);
  const EndEffectorError error(all);
  const EndEffectorPose pose = ComputeEndEffectorPose(all, s);
  Eigen::VectorXd e;
  Eigen::MatrixXd de_ds;
  error.Evaluate(s, {pose.position, pose.rpy}, &e, &de_ds);
  return de_ds;
}

Eigen::MatrixXd StateControlSensitivity(const Model& model, const State& s, const Eigen::VectorXd& u) {
  const ConstraintSet constraints(model);
  std::vector<int> controls(static_cast<size_t>(model.num_controls()));
  std::iota(controls.begin(), controls.end(), 0);
  HessianSolver solver(constraints);
  const Sensitivity sensitivity(constraints, s, u, controls, &solver);
  if (sensitivity.singular()) return Eigen::MatrixXd();  // ds/du is not defined
  return sensitivity.StateSensitivity();
}

Eigen::MatrixXd EndEffectorControlJacobian(const Model& model, const State& s, const Eigen::VectorXd& u) {
  const Eigen::MatrixXd ds_du = StateControlSensitivity(model, s, u);
  if (ds_du.size() == 0 && model.num_controls() > 0) return Eigen::MatrixXd();
  return EndEffectorStateJacobian(model, s) * ds_du;
}

Eigen::Matrix<double, 6, 6> EndEffectorCovariance(const Model& model, const State& s, const Eigen::VectorXd& u,
                                                  const BasePoseNoise& noise) {
  const Eigen::MatrixXd J = EndEffectorControlJacobian(model, s, u);
  if (J.size() == 0) return Eigen::Matrix<double, 6, 6>::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::VectorXd variance = Eigen::VectorXd::Zero(model.num_controls());
  for (int k = 0; k < model.num_bases(); ++k) {
    variance.segment<3>(model.base_control(k)) << noise.position_sigma * noise.position_sigma,
        noise.position_sigma * noise.position_sigma, noise.heading_sigma * noise.heading_sigma;
  }
  return J * variance.asDiagonal() * J.transpose();
}

double EndEffectorPositionStd(const Model& model, const State& s, const Eigen::VectorXd& u) {
  const Eigen::Matrix<double, 6, 6> sigma = EndEffectorCovariance(model, s, u, BasePoseNoise());
  return sigma.allFinite() ? std::sqrt(std::max(0.0, sigma.topLeftCorner<3, 3>().trace())) : 0.0;
}

}  // namespace ccma
