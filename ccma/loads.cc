#include "ccma/loads.h"

#include "ccma/internal/masses.h"
#include "ccma/rotation.h"

namespace ccma {
namespace {

// Every point force on a body: fn(body, lever r = p - p_WB [m], F [N]).
template <typename Fn>
void ForEachPointForce(const Model& model, const State& s, const ExternalWrench& wrench, const Fn& fn) {
  internal::ForEachMass(model, [&](int b, const MassProperties& m) {
    fn(b, Eigen::Vector3d(s.R_WB(b) * m.com_B), Eigen::Vector3d(m.mass * model.gravity));
  });
  const int ee = model.end_effector.body;
  fn(ee, Eigen::Vector3d(s.R_WB(ee) * model.end_effector.p_B), wrench.force);
}

}  // namespace

Eigen::VectorXd GeneralizedLoads(const Model& model, const State& s, const ExternalWrench& wrench) {
  Eigen::VectorXd Q = Eigen::VectorXd::Zero(s.tangent_size());
  ForEachPointForce(model, s, wrench, [&Q](int b, const Eigen::Vector3d& r, const Eigen::Vector3d& F) {
    Q.segment<3>(kPoseTangentSize * b) += r.cross(F);
    Q.segment<3>(kPoseTangentSize * b + 3) += F;
  });
  Q.segment<3>(kPoseTangentSize * model.end_effector.body) += wrench.moment;
  return Q;
}

std::vector<Eigen::Matrix3d> GeneralizedLoadsJacobianBlocks(const Model& model, const State& s,
                                                            const ExternalWrench& wrench) {
  std::vector<Eigen::Matrix3d> blocks(static_cast<size_t>(s.num_bodies()), Eigen::Matrix3d::Zero());
  ForEachPointForce(model, s, wrench, [&blocks](int b, const Eigen::Vector3d& r, const Eigen::Vector3d& F) {
    // d(r x F) = (dphi x r) x F = [F]x [r]x dphi; the force and the world
    // moment do not change.
    blocks[static_cast<size_t>(b)] += Skew(F) * Skew(r);
  });
  return blocks;
}

Eigen::MatrixXd GeneralizedLoadsJacobian(const Model& model, const State& s, const ExternalWrench& wrench) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(s.tangent_size(), s.tangent_size());
  const std::vector<Eigen::Matrix3d> blocks = GeneralizedLoadsJacobianBlocks(model, s, wrench);
  for (size_t b = 0; b < blocks.size(); ++b) {
    K.block<3, 3>(kPoseTangentSize * static_cast<Eigen::Index>(b), kPoseTangentSize * static_cast<Eigen::Index>(b)) = blocks[b];
  }
  return K;
}

}  // namespace ccma
