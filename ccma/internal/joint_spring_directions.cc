#include "ccma/internal/joint_spring_directions.h"

#include <cmath>

#include "ccma/rotation.h"

namespace ccma {
namespace {

// The world directions of A's constrained translations and rotations (3 x k).
Eigen::Matrix3Xd TranslationDirections(const Joint& joint, const Eigen::Matrix3d& R_A) {
  if (joint.type != JointType::kPrismatic) return R_A;
  const Eigen::Vector3d n1 = FirstNormal(joint.a_A);
  Eigen::Matrix3Xd t(3, 2);
  t.col(0) = R_A * n1;
  t.col(1) = R_A * joint.a_A.cross(n1);
  return t;
}

Eigen::Matrix3Xd RotationDirections(const Joint& joint, const Eigen::Matrix3d& R_A, const Eigen::Matrix3d& R_B) {
  switch (joint.type) {
    case JointType::kRevolute: {
      const Eigen::Vector3d n1 = FirstNormal(joint.a_A);
      Eigen::Matrix3Xd c(3, 2);
      c.col(0) = R_A * n1;
      c.col(1) = R_A * joint.a_A.cross(n1);
      return c;
    }
    case JointType::kUniversal: {
      const Eigen::Vector3d a = R_A * joint.a_A;
      const Eigen::Vector3d axb = a.cross(R_B * joint.b_B);
      // The axes stay perpendicular where the joint holds; parallel ones (a
      // state far from it) leave only a's normals: take the first.
      const double norm = axb.norm();
      Eigen::Matrix3Xd c(3, 1);
      c.col(0) = norm > 1e-12 ? Eigen::Vector3d(axb / norm) : Eigen::Vector3d(R_A * FirstNormal(joint.a_A));
      return c;
    }
    case JointType::kPrismatic:
    case JointType::kFixed: return R_A;
    case JointType::kSpherical: return Eigen::Matrix3Xd(3, 0);
  }
  return Eigen::Matrix3Xd(3, 0);
}

}  // namespace

JointEndFrame JointEndFrameOf(const State& s, int body) {
  JointEndFrame f;
  if (body != kWorld) {
    f.R = s.R_WB(body);
    f.p = s.p_WB(body);
  }
  return f;
}

Eigen::Vector3d FirstNormal(const Eigen::Vector3d& a) {
  const Eigen::Vector3d x = std::abs(a.x()) > 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
  return (x - x.dot(a) * a).normalized();
}

SpringDirections JointSpringDirections(const Joint& joint, const State& s) {
  const JointEndFrame A = JointEndFrameOf(s, joint.body_a), B = JointEndFrameOf(s, joint.body_b);
  const Eigen::Vector3d P = B.R * joint.p_B + B.p;  // the joint's point on B
  const Eigen::Matrix3Xd t = TranslationDirections(joint, A.R);
  const Eigen::Matrix3Xd c = RotationDirections(joint, A.R, B.R);
  SpringDirections out;
  out.translations = static_cast<int>(t.cols());
  out.rotations = static_cast<int>(c.cols());
  const Eigen::Matrix3d lever_A = Skew(Eigen::Vector3d(P - A.p)), lever_B = Skew(Eigen::Vector3d(P - B.p));
  for (int i = 0; i < out.translations; ++i) {
    const Eigen::RowVector3d w = t.col(i).transpose();
    if (joint.body_a != kWorld) {
      out.D.block<1, 3>(i, 0) = w * lever_A;  // (P - p_A) x dphi_A
      out.D.block<1, 3>(i, 3) = -w;
    }
    if (joint.body_b != kWorld) {
      out.D.block<1, 3>(i, 6) = -w * lever_B;  // -(P - p_B) x dphi_B
      out.D.block<1, 3>(i, 9) = w;
    }
  }
  for (int i = 0; i < out.rotations; ++i) {
    const int row = out.translations + i;
    if (joint.body_a != kWorld) out.D.block<1, 3>(row, 0) = -c.col(i).transpose();
    if (joint.body_b != kWorld) out.D.block<1, 3>(row, 6) = c.col(i).transpose();
  }
  return out;
}

}  // namespace ccma
