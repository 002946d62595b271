#include "ccma/internal/joint_deviation.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "ccma/internal/joint_spring_directions.h"
#include "ccma/rotation.h"

namespace ccma {
namespace {

// The translation directions in A (3 x count), as JointSpringDirections.
Eigen::Matrix3Xd TranslationAxes(const Joint& joint) {
  if (joint.type != JointType::kPrismatic) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d n1 = FirstNormal(joint.a_A);
  Eigen::Matrix3Xd t(3, 2);
  t << n1, joint.a_A.cross(n1);
  return t;
}

// The rotation that turns unit vector a into unit vector v (rotation vector).
Eigen::Vector3d Turning(const Eigen::Vector3d& a, const Eigen::Vector3d& v) {
  const Eigen::Vector3d w = a.cross(v);
  const double sine = w.norm();
  if (sine < 1e-300) return w;
  return w * (std::atan2(sine, a.dot(v)) / sine);
}

// The rotation deviation [rad], R_AB = R_A^T R_B.
Eigen::VectorXd RotationDeviation(const Joint& joint, const JointEndFrame& A, const JointEndFrame& B) {
  const Eigen::Matrix3d R_AB = A.R.transpose() * B.R;
  switch (joint.type) {
    case JointType::kRevolute: {
      const Eigen::Vector3d n1 = FirstNormal(joint.a_A);
      const Eigen::Vector3d turn = Turning(joint.a_A, R_AB * joint.a_B);
      return Eigen::Vector2d(n1.dot(turn), joint.a_A.cross(n1).dot(turn));
    }
    case JointType::kUniversal: {
      const double cosine = (A.R * joint.a_A).dot(B.R * joint.b_B);
      return Eigen::VectorXd::Constant(1, -std::asin(std::clamp(cosine, -1.0, 1.0)));
    }
    case JointType::kFixed:
    case JointType::kPrismatic: {
      // R_err d_iA = R_AB d_iB for the reference directions: the identity
      // where the joint holds.
      const Eigen::Vector3d d3_A = joint.d1_A.cross(joint.d2_A), d3_B = joint.d1_B.cross(joint.d2_B);
      const Eigen::Matrix3d rest = joint.d1_B * joint.d1_A.transpose() + joint.d2_B * joint.d2_A.transpose() +
                                   d3_B * d3_A.transpose();
      return QuaternionLog(Eigen::Quaterniond(R_AB * rest).normalized());
    }
    case JointType::kSpherical: return Eigen::VectorXd(0);
  }
  return Eigen::VectorXd(0);
}

}  // namespace

Eigen::VectorXd JointDeviation(const Joint& joint, const State& s) {
  const JointEndFrame A = JointEndFrameOf(s, joint.body_a), B = JointEndFrameOf(s, joint.body_b);
  const Eigen::Vector3d P = B.R * joint.p_B + B.p;
  const Eigen::Vector3d offset_A = A.R.transpose() * (P - A.p) - joint.p_A;
  const Eigen::VectorXd translation = TranslationAxes(joint).transpose() * offset_A;
  const Eigen::VectorXd rotation = RotationDeviation(joint, A, B);
  Eigen::VectorXd e(translation.size() + rotation.size());
  e << translation, rotation;
  return e;
}

}  // namespace ccma
