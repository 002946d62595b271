// The spring directions of joints (ccma/internal/joint_spring_directions.h)
// against central differences of the relative pose of between[1] in
// between[0] at seeded random states (not only where the joints hold), for
// every joint type and with the ground at either end; the directions
// themselves against the contract's order; and the checker failing on a
// wrong map.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "ccma/internal/joint_spring_directions.h"
#include "ccma/rotation.h"

namespace ccma {
namespace spring_directions_test {

Eigen::Matrix3d FrameR(const State& s, int body) { return body == kWorld ? Eigen::Matrix3d::Identity() : s.R_WB(body); }
Eigen::Vector3d FrameP(const State& s, int body) { return body == kWorld ? Eigen::Vector3d::Zero() : s.p_WB(body); }

// n1, n2 of the contract for the axis a (in A's frame).
Eigen::Matrix3Xd Normals(const Eigen::Vector3d& a) {
  const Eigen::Vector3d x = std::abs(a.x()) > 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d n1 = (x - x.dot(a) * a).normalized();
  Eigen::Matrix3Xd t(3, 2);
  t << n1, a.cross(n1);
  return t;
}

// The contract's translation directions, in A's frame.
Eigen::Matrix3Xd ExpectedTranslations(const Joint& j) {
  if (j.type != JointType::kPrismatic) return Eigen::Matrix3d::Identity();
  return Normals(j.a_A);
}

// World rotation directions at s.
Eigen::Matrix3Xd ExpectedRotations(const Joint& j, const State& s) {
  const Eigen::Matrix3d R_A = FrameR(s, j.body_a);
  switch (j.type) {
    case JointType::kRevolute: return R_A * Normals(j.a_A);
    case JointType::kUniversal: {
      const Eigen::Vector3d c = (R_A * j.a_A).cross(FrameR(s, j.body_b) * j.b_B).normalized();
      return c;
    }
    case JointType::kSpherical: return Eigen::Matrix3Xd(3, 0);
    default: return R_A;
  }
}

// The relative pose: B's joint point in A's frame, and R_A^T R_B.
struct Relative {
  Eigen::Vector3d t;
  Eigen::Matrix3d R;
};
Relative RelativePose(const Joint& j, const State& s) {
  const Eigen::Matrix3d R_A = FrameR(s, j.body_a), R_B = FrameR(s, j.body_b);
  const Eigen::Vector3d P = R_B * j.p_B + FrameP(s, j.body_b);
  return {R_A.transpose() * (P - FrameP(s, j.body_a)), R_A.transpose() * R_B};
}

// max |D - numeric| over the used rows, numeric from central differences of
// the relative pose along each tangent coordinate of the two bodies.
double DirectionError(const Joint& j, const State& s, const SpringDirections& d) {
  const Eigen::Matrix3d R_A = FrameR(s, j.body_a);
  const Eigen::Matrix3Xd t = ExpectedTranslations(j), c = ExpectedRotations(j, s);
  EXPECT_EQ(d.translations, t.cols());
  EXPECT_EQ(d.rotations, c.cols());
  double error = 0;
  const double h = 1e-6;
  for (int end = 0; end < 2; ++end) {
    const int body = end == 0 ? j.body_a : j.body_b;
    for (int k = 0; k < 6; ++k) {
      Eigen::VectorXd ds = Eigen::VectorXd::Zero(s.tangent_size());
      Eigen::VectorXd numeric = Eigen::VectorXd::Zero(d.rows());
      if (body != kWorld) {
        ds[6 * body + k] = h;
        State plus = s, minus = s;
        plus.Plus(ds);
        minus.Plus(-ds);
        const Relative p = RelativePose(j, plus), m = RelativePose(j, minus);
        const Eigen::Vector3d dt = (p.t - m.t) / (2 * h);
        const Eigen::Vector3d omega_W = R_A * QuaternionLog(Eigen::Quaterniond(p.R * m.R.transpose())) / (2 * h);
        for (int i = 0; i < d.translations; ++i) numeric[i] = t.col(i).dot(dt);
        for (int i = 0; i < d.rotations; ++i) numeric[d.translations + i] = c.col(i).dot(omega_W);
      }
      for (int i = 0; i < d.rows(); ++i) error = std::max(error, std::abs(d.D(i, 6 * end + k) - numeric[i]));
    }
  }
  return error;
}

Joint RandomJoint(JointType type, int a, int b, std::mt19937* rng) {
  std::uniform_real_distribution<double> U(-1, 1);
  auto vec = [&] { return Eigen::Vector3d(U(*rng), U(*rng), U(*rng)); };
  Joint j;
  j.type = type;
  j.body_a = a;
  j.body_b = b;
  j.p_A = vec();
  j.p_B = vec();
  j.a_A = vec().normalized();
  j.b_B = vec().normalized();
  return j;
}

State RandomState(std::mt19937* rng) {
  std::uniform_real_distribution<double> U(-1, 1);
  State s(2);
  for (int b = 0; b < 2; ++b) {
    s.SetPose(b, Eigen::Quaterniond(U(*rng), U(*rng), U(*rng), U(*rng)).normalized(),
              Eigen::Vector3d(U(*rng), U(*rng), U(*rng)));
  }
  return s;
}

TEST(SpringDirections, MatchTheRelativePoseAtRandomStates) {
  std::mt19937 rng(36);
  for (const JointType type : {JointType::kRevolute, JointType::kUniversal, JointType::kPrismatic, JointType::kFixed,
                               JointType::kSpherical}) {
    for (const auto& [a, b] : {std::pair{0, 1}, std::pair{kWorld, 1}, std::pair{0, kWorld}}) {
      for (int trial = 0; trial < 5; ++trial) {
        const Joint j = RandomJoint(type, a, b, &rng);
        const State s = RandomState(&rng);
        const SpringDirections d = JointSpringDirections(j, s);
        EXPECT_EQ(d.translations, TranslationSpringCount(type));
        EXPECT_EQ(d.rotations, RotationSpringCount(type));
        EXPECT_LT(DirectionError(j, s, d), 1e-8) << JointTypeName(type) << " " << a << " " << b << " " << trial;
      }
    }
  }
}

TEST(SpringDirections, TheCheckerFailsOnAWrongMap) {
  std::mt19937 rng(7);
  const Joint j = RandomJoint(JointType::kFixed, 0, 1, &rng);
  const State s = RandomState(&rng);
  const SpringDirections right = JointSpringDirections(j, s);
  // The lever about A's own joint point instead of the current point P: the
  // same where the joint holds, wrong elsewhere.
  SpringDirections wrong = right;
  const Eigen::Vector3d P_A = s.R_WB(0) * j.p_A + s.p_WB(0);
  for (int i = 0; i < 3; ++i) {
    wrong.D.block<1, 3>(i, 0) = -(s.R_WB(0).col(i).transpose() * Skew(Eigen::Vector3d(P_A - s.p_WB(0))).transpose());
  }
  EXPECT_LT(DirectionError(j, s, right), 1e-8);
  EXPECT_GT(DirectionError(j, s, wrong), 1e-3);
  SpringDirections sign = right;  // one rotation row of the wrong sign
  sign.D.row(4) = -sign.D.row(4);
  EXPECT_GT(DirectionError(j, s, sign), 1e-3);
}

TEST(SpringDirections, FirstNormalFollowsTheContract) {
  EXPECT_LT((FirstNormal(Eigen::Vector3d::UnitZ()) - Eigen::Vector3d::UnitX()).norm(), 1e-15);
  EXPECT_LT((FirstNormal(Eigen::Vector3d::UnitX()) - Eigen::Vector3d::UnitY()).norm(), 1e-15);  // |x.a| > 0.9
  const Eigen::Vector3d a = Eigen::Vector3d(1, 1, 0).normalized();  // x.a = 0.707: x projected
  EXPECT_LT((FirstNormal(a) - Eigen::Vector3d(1, -1, 0).normalized()).norm(), 1e-15);
}

}  // namespace
}  // namespace ccma
