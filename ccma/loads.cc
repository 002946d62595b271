#include "ccma/loads.h"

namespace ccma {
namespace {

// [M; F] of a force F at world point p on body b (moment about its origin).
void AddForce(const State& s, int body, const Eigen::Vector3d& p, const Eigen::Vector3d& F, Eigen::VectorXd* Q) {
  Q->segment<3>(kPoseTangentSize * body) += (p - s.p_WB(body)).cross(F);
  Q->segment<3>(kPoseTangentSize * body + 3) += F;
}

}  // namespace

Eigen::VectorXd GeneralizedLoads(const Model& model, const State& s, const ExternalWrench& wrench) {
  Eigen::VectorXd Q = Eigen::VectorXd::Zero(s.tangent_size());
  for (int b = 0; b < model.num_bodies(); ++b) {
    const MassProperties& m = model.bodies[static_cast<size_t>(b)].inertia;
    if (m.mass > 0) AddForce(s, b, s.R_WB(b) * m.com_B + s.p_WB(b), m.mass * model.gravity, &Q);
  }
  const int ee = model.end_effector.body;
  const MassProperties& payload = model.end_effector.payload;
  if (payload.mass > 0) AddForce(s, ee, s.R_WB(ee) * payload.com_B + s.p_WB(ee), payload.mass * model.gravity, &Q);
  const Eigen::Vector3d p_WE = s.R_WB(ee) * model.end_effector.p_B + s.p_WB(ee);
  AddForce(s, ee, p_WE, wrench.force, &Q);
  Q.segment<3>(kPoseTangentSize * ee) += wrench.moment;
  return Q;
}

}  // namespace ccma
