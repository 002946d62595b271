#include "python/src/pose_types.h"

#include <cmath>
#include <stdexcept>

#include "ccma/rotation.h"

namespace ccma::python {

BodyPose PoseOfBody(const Model& model, const State& s, int body) {
  BodyPose pose;
  pose.name = model.bodies[body].name;
  const Eigen::Quaterniond q = s.q_WB(body);
  pose.position = s.p_WB(body);
  pose.rotation = q.toRotationMatrix();
  pose.quaternion << q.w(), q.x(), q.y(), q.z();
  pose.rpy = RpyFromRotation(pose.rotation);
  return pose;
}

Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor> StateToArray(const State& s) {
  Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor> a(s.num_bodies(), 7);
  for (int b = 0; b < s.num_bodies(); ++b) {
    for (int i = 0; i < kPoseAmbientSize; ++i) a(b, i) = s.pose(b)[i];
  }
  return a;
}

State StateFromArray(const Model& model,
                     const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>>& a) {
  if (a.rows() != model.num_bodies()) {
    throw std::invalid_argument("state: expected " + std::to_string(model.num_bodies()) +
                                " rows (one per body), got " + std::to_string(a.rows()));
  }
  if (!a.allFinite()) throw std::invalid_argument("state: every entry must be finite");
  State s(model.num_bodies());
  for (int b = 0; b < model.num_bodies(); ++b) {
    Eigen::Quaterniond q(a(b, 3), a(b, 0), a(b, 1), a(b, 2));
    if (q.norm() < 1e-12) throw std::invalid_argument("state: row " + std::to_string(b) + " has a zero quaternion");
    q.normalize();
    s.SetPose(b, q, Eigen::Vector3d(a(b, 4), a(b, 5), a(b, 6)));
  }
  return s;
}

}  // namespace ccma::python
