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

StateArray StateToArray(const State& s) {
  StateArray a(s.num_bodies(), 7);
  for (int b = 0; b < s.num_bodies(); ++b) {
    const double* pose = s.pose(b);  // storage: qx qy qz qw px py pz
    a.row(b) << pose[3], pose[0], pose[1], pose[2], pose[4], pose[5], pose[6];
  }
  return a;
}

State StateFromArray(const Model& model, const Eigen::Ref<const StateArray>& a) {
  if (a.rows() != model.num_bodies()) {
    throw std::invalid_argument("state: expected " + std::to_string(model.num_bodies()) +
                                " rows (one per body), got " + std::to_string(a.rows()));
  }
  if (!a.allFinite()) throw std::invalid_argument("state: every entry must be finite");
  State s(model.num_bodies());
  for (int b = 0; b < model.num_bodies(); ++b) {
    Eigen::Quaterniond q(a(b, 0), a(b, 1), a(b, 2), a(b, 3));  // (w, x, y, z)
    if (q.norm() < 1e-12) throw std::invalid_argument("state: row " + std::to_string(b) + " has a zero quaternion");
    q.normalize();
    s.SetPose(b, q, Eigen::Vector3d(a(b, 4), a(b, 5), a(b, 6)));
  }
  return s;
}

}  // namespace ccma::python
