#include "ccma/inertial_loads.h"

#include "ccma/internal/masses.h"

namespace ccma {

Eigen::VectorXd InertialLoads(const Model& model, const State& s, const Eigen::VectorXd& velocity,
                              const Eigen::VectorXd& acceleration) {
  Eigen::VectorXd Q = Eigen::VectorXd::Zero(s.tangent_size());
  internal::ForEachMass(model, [&](int b, const MassProperties& m) {
    const int i = kPoseTangentSize * b;
    const Eigen::Matrix3d R_WB = s.R_WB(b);
    const Eigen::Vector3d r = R_WB * m.com_B;
    const Eigen::Matrix3d I_W = R_WB * m.inertia_B * R_WB.transpose();
    const Eigen::Vector3d omega = velocity.segment<3>(i), alpha = acceleration.segment<3>(i);
    const Eigen::Vector3d a_c = acceleration.segment<3>(i + 3) + alpha.cross(r) + omega.cross(omega.cross(r));
    const Eigen::Vector3d F = -m.mass * a_c;
    Q.segment<3>(i) += r.cross(F) - (I_W * alpha + omega.cross(I_W * omega));
    Q.segment<3>(i + 3) += F;
  });
  return Q;
}

double KineticEnergy(const Model& model, const State& s, const Eigen::VectorXd& velocity) {
  double energy = 0;
  internal::ForEachMass(model, [&](int b, const MassProperties& m) {
    const int i = kPoseTangentSize * b;
    const Eigen::Matrix3d R_WB = s.R_WB(b);
    const Eigen::Vector3d omega = velocity.segment<3>(i);
    const Eigen::Vector3d v_c = velocity.segment<3>(i + 3) + omega.cross(R_WB * m.com_B);
    const Eigen::Matrix3d I_W = R_WB * m.inertia_B * R_WB.transpose();
    energy += 0.5 * m.mass * v_c.squaredNorm() + 0.5 * omega.dot(I_W * omega);
  });
  return energy;
}

double PotentialEnergy(const Model& model, const State& s) {
  double energy = 0;
  internal::ForEachMass(model, [&](int b, const MassProperties& m) {
    energy -= m.mass * model.gravity.dot(s.p_WB(b) + s.R_WB(b) * m.com_B);
  });
  return energy;
}

}  // namespace ccma
