#include "python/src/pose_types.h"

#include <cmath>
#include <stdexcept>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "ccma/rotation.h"

namespace ccma::python {

bool AtHome(const ForwardProblem& problem) {
  const Model& model = problem.model();
  return problem.controls() == model.home_controls() &&
         problem.state().Minus(State::Home(model)).lpNorm<Eigen::Infinity>() == 0;
}

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
  // Finite and bounded: a quaternion of 1e308 entries would overflow its norm
  // and be stored as zero.
  if (!(a.cwiseAbs().maxCoeff() <= kMaxMagnitude)) {
    throw std::invalid_argument("state: every entry must be a finite number in [-" + FormatG(kMaxMagnitude) + ", " +
                                FormatG(kMaxMagnitude) + "]");
  }
  State s(model.num_bodies());
  for (int b = 0; b < model.num_bodies(); ++b) {
    Eigen::Quaterniond q(a(b, 0), a(b, 1), a(b, 2), a(b, 3));  // (w, x, y, z)
    if (q.norm() < 1e-12) throw std::invalid_argument("state: row " + std::to_string(b) + " has a zero quaternion");
    q.normalize();
    s.SetPose(b, q, Eigen::Vector3d(a(b, 4), a(b, 5), a(b, 6)));
  }
  return s;
}

void CheckControls(const Model& model, const Eigen::VectorXd& u) {
  if (u.size() != model.num_controls()) {
    throw std::invalid_argument("controls: expected " + std::to_string(model.num_controls()) +
                                " values (3 per mobile base, 6 per legged base, then 1 per actuated joint), got " +
                                std::to_string(u.size()));
  }
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    if (!(std::abs(u[i]) <= kMaxMagnitude)) {
      throw std::invalid_argument("controls: entry " + std::to_string(i) + " (" + FormatG(u[i]) +
                                  ") must be a finite number in [-" + FormatG(kMaxMagnitude) + ", " +
                                  FormatG(kMaxMagnitude) + "] (m or rad)");
    }
  }
}

}  // namespace ccma::python
