// The configuration of a CCMA system: one pose per rigid body.
//
// Storage per body (a Ceres parameter block of 7 doubles):
//   [qx, qy, qz, qw, px, py, pz] = unit quaternion of R_WB, then p_WB [m].
// The state has 6 degrees of freedom per body (the paper's s): increments are
//   R_WB <- Exp(dphi) * R_WB   (dphi: rotation vector in world axes, rad)
//   p_WB <- p_WB + dp          (m)
// so ds = [dphi_0, dp_0, dphi_1, dp_1, ...] and no orientation is singular.
#ifndef CCMA_STATE_H_
#define CCMA_STATE_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ccma {

struct Model;

constexpr int kPoseAmbientSize = 7;  // doubles per body in storage
constexpr int kPoseTangentSize = 6;  // degrees of freedom per body

class State {
 public:
  State() = default;
  explicit State(int num_bodies);
  // Every body at its home pose.
  static State Home(const Model& model);

  int num_bodies() const { return static_cast<int>(data_.size()) / kPoseAmbientSize; }
  int tangent_size() const { return kPoseTangentSize * num_bodies(); }

  // The body's 7-double parameter block (stable address for Ceres).
  double* pose(int body) { return data_.data() + kPoseAmbientSize * body; }
  const double* pose(int body) const { return data_.data() + kPoseAmbientSize * body; }

  Eigen::Quaterniond q_WB(int body) const;
  Eigen::Matrix3d R_WB(int body) const { return q_WB(body).toRotationMatrix(); }
  Eigen::Vector3d p_WB(int body) const;
  void SetPose(int body, const Eigen::Quaterniond& q_WB, const Eigen::Vector3d& p_WB);

  // this <- this (+) ds, with ds of size tangent_size().
  void Plus(const Eigen::VectorXd& ds);
  // The tangent vector ds with other (+) ds == this (per body).
  Eigen::VectorXd Minus(const State& other) const;
  // The same into `ds` (resized only when its size differs: no allocation
  // in a loop that reuses it).
  void Minus(const State& other, Eigen::VectorXd* ds) const;

 private:
  std::vector<double> data_;
};

}  // namespace ccma

#endif  // CCMA_STATE_H_
