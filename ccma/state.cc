#include "ccma/state.h"

#include "ccma/model.h"
#include "ccma/internal/pose_manifold.h"

namespace ccma {

State::State(int num_bodies) : data_(kPoseAmbientSize * num_bodies, 0.0) {
  for (int i = 0; i < num_bodies; ++i) pose(i)[3] = 1.0;  // identity rotation
}

State State::Home(const Model& model) {
  State s(model.num_bodies());
  for (int i = 0; i < model.num_bodies(); ++i) {
    s.SetPose(i, Eigen::Quaterniond(model.bodies[i].R_WB_home),
              model.bodies[i].p_WB_home);
  }
  return s;
}

Eigen::Quaterniond State::q_WB(int body) const {
  return Eigen::Quaterniond(Eigen::Map<const Eigen::Vector4d>(pose(body)));
}

Eigen::Vector3d State::p_WB(int body) const {
  return Eigen::Map<const Eigen::Vector3d>(pose(body) + 4);
}

void State::SetPose(int body, const Eigen::Quaterniond& q, const Eigen::Vector3d& p) {
  Eigen::Map<Eigen::Vector4d>(pose(body)) = q.normalized().coeffs();
  Eigen::Map<Eigen::Vector3d>(pose(body) + 4) = p;
}

void State::Plus(const Eigen::VectorXd& ds) {
  const PoseManifold manifold;
  for (int i = 0; i < num_bodies(); ++i) {
    double out[kPoseAmbientSize];
    manifold.Plus(pose(i), ds.data() + kPoseTangentSize * i, out);
    std::copy(out, out + kPoseAmbientSize, pose(i));
  }
}

Eigen::VectorXd State::Minus(const State& other) const {
  Eigen::VectorXd ds;
  Minus(other, &ds);
  return ds;
}

void State::Minus(const State& other, Eigen::VectorXd* ds) const {
  const PoseManifold manifold;
  if (ds->size() != tangent_size()) ds->resize(tangent_size());
  for (int i = 0; i < num_bodies(); ++i) {
    manifold.Minus(pose(i), other.pose(i), ds->data() + kPoseTangentSize * i);
  }
}

}  // namespace ccma
