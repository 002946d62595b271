// Round-trip and property tests of the SO(3) helpers (ccma/rotation.h), the
// pose manifold and State::Plus/Minus, in the style of Sophus' tests: one
// generic check per property, run over hard cases (angles 0, 1e-300, on both
// sides of the small-angle branches, pi - 1e-9, pi; pitch at and near +-pi/2;
// quaternions with w = 0 and w < 0) and seeded random samples. Each generic
// check returns an AssertionResult naming the first sample that fails, and
// HelpersDetectWrongFormulas proves that every one of them rejects a
// deliberately wrong formula, so none of them passes vacuously.
//
// Tolerances: 1e-12 (absolute on O(1) quantities, or relative to the size of
// the vector compared) unless a comment says why the maths allows no better.
#include <cfloat>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "ccma/rotation.h"
#include "ccma/state.h"
#if __has_include("ccma/internal/pose_manifold.h")
#include "ccma/internal/pose_manifold.h"
#else
#include "ccma/pose_manifold.h"
#endif

namespace ccma {
namespace rotation_test {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;
using ::testing::AssertionFailure;
using ::testing::AssertionResult;
using ::testing::AssertionSuccess;

constexpr double kTol = 1e-12;
constexpr int kRandomSamples = 1000;
constexpr double kPi = M_PI;

using ExpFn = std::function<Quaterniond(const Vector3d&)>;
using LogFn = std::function<Vector3d(const Quaterniond&)>;
using FromRpyFn = std::function<Matrix3d(const Vector3d&)>;
using ToRpyFn = std::function<Vector3d(const Matrix3d&)>;
using WrapFn = std::function<double(double)>;
using SkewFn = std::function<Matrix3d(const Vector3d&)>;
using PlusFn = std::function<void(const double* x, const double* delta, double* x_plus_delta)>;

// ------------------------------------------------------------ samples ---

Vector3d RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Vector3d v;
  do v = Vector3d{n(rng), n(rng), n(rng)};
  while (v.norm() < 1e-3);
  return v.normalized();
}
Vector3d RandomVector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}
// Uniform on SO(3) (normalised 4D Gaussian).
Quaterniond RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Quaterniond{n(rng), n(rng), n(rng), n(rng)}.normalized();
}

const std::vector<Vector3d>& Axes() {
  static const std::vector<Vector3d> axes = {Vector3d::UnitX(),
                                             Vector3d::UnitY(),
                                             Vector3d::UnitZ(),
                                             -Vector3d::UnitX(),
                                             -Vector3d::UnitY(),
                                             -Vector3d::UnitZ(),
                                             Vector3d(1, 1, 1).normalized(),
                                             Vector3d(-0.3, 0.5, -0.8).normalized()};
  return axes;
}

// Rotation vectors with angle in [0, pi): every magnitude below on every
// axis, then random axes and angles. The magnitudes sit on both sides of
// QuaternionExp's Taylor branch (theta^2 < 1e-16, theta < 1e-8) and of
// QuaternionLog's (sin(theta/2) < 1e-12, theta < 2e-12).
std::vector<Vector3d> RotationVectorsBelowPi(std::mt19937& rng) {
  const std::vector<double> angles = {
      0.0,  1e-300, 1e-20, 1e-12, 1.999e-12, 2.001e-12, 1e-10, 9.999e-9,   1e-8,      1.0001e-8,
      1e-6, 1e-4,   0.1,   0.5,   1.0,       2.0,       3.0,   kPi - 1e-6, kPi - 1e-9};
  std::vector<Vector3d> out;
  for (const Vector3d& axis : Axes()) {
    for (double a : angles) out.push_back(a * axis);
  }
  for (double a : angles) out.push_back(a * RandomUnit(rng));
  std::uniform_real_distribution<double> angle(0.0, kPi);
  for (int i = 0; i < kRandomSamples; ++i) {
    const double a = angle(rng);  // drawn before the axis, on every compiler
    out.push_back(a * RandomUnit(rng));
  }
  return out;
}

// Unit quaternions, including both signs, w = 0 (angle pi), |w| tiny.
std::vector<Quaterniond> Quaternions(std::mt19937& rng) {
  std::vector<Quaterniond> out = {Quaterniond(1, 0, 0, 0), Quaterniond(-1, 0, 0, 0)};
  for (const Vector3d& axis : Axes()) {
    for (double w : {0.0, 1e-17, -1e-17, 1e-9, -1e-9, 0.5, -0.5, 1 - 1e-15, -(1 - 1e-15)}) {
      const double s = std::sqrt(1.0 - w * w);
      out.emplace_back(w, s * axis.x(), s * axis.y(), s * axis.z());
    }
  }
  for (int i = 0; i < kRandomSamples; ++i) out.push_back(RandomRotation(rng));
  return out;
}

// ------------------------------------------------------ comparisons ---

std::string Str(const Eigen::MatrixXd& m) {
  std::ostringstream s;
  s.precision(17);
  s << m.transpose();
  return s.str();
}

// |a - b|_inf <= tol.
AssertionResult Near(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double tol) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return AssertionFailure() << "size mismatch";
  const double err = (a - b).cwiseAbs().maxCoeff();
  if (err <= tol) return AssertionSuccess();
  return AssertionFailure() << "|a - b| = " << err << " > " << tol << "\n  a = " << Str(a)
                            << "\n  b = " << Str(b);
}

// The same rotation: q and -q are equal.
AssertionResult SameRotation(const Quaterniond& a, const Quaterniond& b, double tol) {
  const double err = std::min((a.coeffs() - b.coeffs()).cwiseAbs().maxCoeff(),
                              (a.coeffs() + b.coeffs()).cwiseAbs().maxCoeff());
  if (err <= tol) return AssertionSuccess();
  return AssertionFailure() << "quaternions differ by " << err << " > " << tol
                            << "\n  a = " << Str(a.coeffs()) << "\n  b = " << Str(b.coeffs());
}

// Distance between two angles on the circle.
double AngleDistance(double a, double b) {
  const double d = std::fabs(a - b);
  return std::min(d, std::fabs(d - 2 * kPi));
}

// ---------------------------------------------------- generic checks ---
// Each takes the functions under test, so HelpersDetectWrongFormulas can run
// it on a wrong one.

// Log(Exp(v)) == v for |v| < pi, relative to |v| (exactly 0 at v = 0): the
// formulas lose no relative precision for tiny angles.
AssertionResult LogOfExpIsIdentity(const std::vector<Vector3d>& vs, const ExpFn& exp,
                                   const LogFn& log) {
  for (std::size_t i = 0; i < vs.size(); ++i) {
    const Vector3d& v = vs[i];
    const Vector3d back = log(exp(v));
    const double err = (back - v).norm();
    if (!(err <= kTol * v.norm())) {
      return AssertionFailure() << "sample " << i << ", |v| = " << v.norm()
                                << ": |Log(Exp(v)) - v| = " << err << "\n  v    = " << Str(v)
                                << "\n  back = " << Str(back);
    }
  }
  return AssertionSuccess();
}

// Exp(Log(q)) is the rotation q.
AssertionResult ExpOfLogIsIdentity(const std::vector<Quaterniond>& qs, const ExpFn& exp,
                                   const LogFn& log) {
  for (std::size_t i = 0; i < qs.size(); ++i) {
    const Vector3d v = log(qs[i]);
    if (!(v.norm() <= kPi + kTol)) {
      return AssertionFailure() << "sample " << i << ": |Log(q)| = " << v.norm() << " > pi";
    }
    const AssertionResult same = SameRotation(exp(v), qs[i], kTol);
    if (!same) return AssertionFailure() << "sample " << i << ": " << same.message();
  }
  return AssertionSuccess();
}

// Exp agrees with Eigen's independent AngleAxis -> Quaternion conversion.
// 4 ulp: both round sin/cos once or twice.
AssertionResult ExpMatchesAngleAxis(const std::vector<Vector3d>& vs, const ExpFn& exp) {
  for (std::size_t i = 0; i < vs.size(); ++i) {
    const double angle = vs[i].norm();
    if (angle == 0.0) continue;
    const Quaterniond expected(Eigen::AngleAxisd(angle, vs[i] / angle));
    const Quaterniond q = exp(vs[i]);
    if (std::fabs(q.norm() - 1.0) > 4 * DBL_EPSILON) {
      return AssertionFailure() << "sample " << i << ": |Exp(v)| - 1 = " << q.norm() - 1.0;
    }
    const AssertionResult same = Near(q.coeffs(), expected.coeffs(), 4 * DBL_EPSILON);
    if (!same) return AssertionFailure() << "sample " << i << ": " << same.message();
  }
  return AssertionSuccess();
}

// RotationFromRpy(RpyFromRotation(R)) == R, entrywise, and the angles are in
// their documented ranges.
AssertionResult RotationSurvivesRpy(const std::vector<Matrix3d>& Rs, const FromRpyFn& from_rpy,
                                    const ToRpyFn& to_rpy) {
  for (std::size_t i = 0; i < Rs.size(); ++i) {
    const Vector3d rpy = to_rpy(Rs[i]);
    if (!(rpy.x() > -kPi && rpy.x() <= kPi && rpy.z() > -kPi && rpy.z() <= kPi &&
          std::fabs(rpy.y()) <= kPi / 2)) {
      return AssertionFailure() << "sample " << i << ": rpy out of range: " << Str(rpy);
    }
    const AssertionResult same = Near(from_rpy(rpy), Rs[i], kTol);
    if (!same) {
      return AssertionFailure() << "sample " << i << ", rpy " << Str(rpy)
                                << ", pi/2 - |pitch| = " << kPi / 2 - std::fabs(rpy.y()) << ": "
                                << same.message();
    }
  }
  return AssertionSuccess();
}

// RpyFromRotation(RotationFromRpy(rpy)) == rpy (as angles), for rpy in the
// canonical ranges and away from gimbal lock.
AssertionResult AnglesSurviveRpy(const std::vector<Vector3d>& rpys, const FromRpyFn& from_rpy,
                                 const ToRpyFn& to_rpy) {
  for (std::size_t i = 0; i < rpys.size(); ++i) {
    const Vector3d back = to_rpy(from_rpy(rpys[i]));
    for (int k = 0; k < 3; ++k) {
      if (!(AngleDistance(back[k], rpys[i][k]) <= kTol)) {
        return AssertionFailure() << "sample " << i << ": rpy " << Str(rpys[i]) << " came back as "
                                  << Str(back);
      }
    }
  }
  return AssertionSuccess();
}

// WrapAngle(a) lies in (-pi, pi], differs from a by a multiple of 2 pi, and
// is left unchanged when it already lies there.
AssertionResult WrapsIntoRange(const std::vector<double>& angles, const WrapFn& wrap) {
  for (double a : angles) {
    const double w = wrap(a);
    if (!(w > -kPi && w <= kPi)) {
      return AssertionFailure() << "WrapAngle(" << a << ") = " << w << " not in (-pi, pi]";
    }
    if (wrap(w) != w) return AssertionFailure() << "WrapAngle not idempotent at " << a;
    if (std::fabs(a) < 1e6) {
      // a - w is rounded once: an error of up to ulp(a).
      const double turns = (a - w) / (2 * kPi);
      if (!(std::fabs(turns - std::round(turns)) <= 1e-15 * (1 + std::fabs(a)))) {
        return AssertionFailure() << "WrapAngle(" << a << ") = " << w
                                  << " is not a whole number of turns away";
      }
    }
  }
  return AssertionSuccess();
}

AssertionResult SkewIsCrossProduct(std::mt19937& rng, const SkewFn& skew) {
  for (int i = 0; i < kRandomSamples; ++i) {
    const Vector3d w = RandomVector(rng, 10.0), v = RandomVector(rng, 10.0);
    const Matrix3d S = skew(w);
    // Two products and one sum per entry, in the same order: exact.
    AssertionResult r = Near(S * v, w.cross(v), 0.0);
    if (!r) return AssertionFailure() << "Skew(w) v != w x v: " << r.message();
    r = Near(S.transpose(), -S, 0.0);
    if (!r) return AssertionFailure() << "Skew(w) is not antisymmetric: " << r.message();
  }
  return AssertionSuccess();
}

// A pose as 7 doubles [qx, qy, qz, qw, px, py, pz].
using Pose = Eigen::Matrix<double, 7, 1>;
using Tangent = Eigen::Matrix<double, 6, 1>;
Pose MakePose(const Quaterniond& q, const Vector3d& p) {
  Pose x;
  x << q.coeffs(), p;
  return x;
}
Quaterniond RotationOf(const Pose& x) { return Quaterniond(x.head<4>()); }

// Poses: identity, q = -1, rotations by pi (w = 0), far positions, random.
std::vector<Pose> Poses(std::mt19937& rng) {
  std::vector<Pose> out = {MakePose(Quaterniond::Identity(), Vector3d::Zero()),
                           MakePose(Quaterniond(-1, 0, 0, 0), Vector3d(1, -2, 3)),
                           MakePose(Quaterniond(0, 1, 0, 0), Vector3d::Zero()),
                           MakePose(Quaterniond(0, 0, 0.6, 0.8), Vector3d(1e3, -1e3, 5e2))};
  for (int i = 0; i < kRandomSamples / 4; ++i) {
    const Quaterniond q = RandomRotation(rng);
    out.push_back(MakePose(q, RandomVector(rng, 10.0)));
  }
  return out;
}

// Minus(Plus(x, d), x) == d. Rotation part: kTol relative to |dphi|, plus an
// absolute 1e-15 because Exp(dphi) * q_x * conj(q_x) rounds at the level of
// the O(1) quaternion entries, not of dphi. Position part: (p + dp) - p is
// exact up to one rounding of p + dp, i.e. eps * |p|.
AssertionResult MinusUndoesPlus(const std::vector<Pose>& xs, const std::vector<Tangent>& ds,
                                const PlusFn& plus) {
  const PoseManifold manifold;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    for (std::size_t j = 0; j < ds.size(); ++j) {
      Pose y;
      Tangent back;
      plus(xs[i].data(), ds[j].data(), y.data());
      manifold.Minus(y.data(), xs[i].data(), back.data());
      const double rot_err = (back.head<3>() - ds[j].head<3>()).norm();
      const double pos_err = (back.tail<3>() - ds[j].tail<3>()).cwiseAbs().maxCoeff();
      if (!(rot_err <= kTol * ds[j].head<3>().norm() + 1e-15) ||
          !(pos_err <= 2 * DBL_EPSILON * (1 + xs[i].tail<3>().cwiseAbs().maxCoeff()))) {
        return AssertionFailure() << "pose " << i << ", delta " << j << ": rotation error "
                                  << rot_err << ", position error " << pos_err
                                  << "\n  d    = " << Str(ds[j]) << "\n  back = " << Str(back);
      }
    }
  }
  return AssertionSuccess();
}

// The lifted convention (ccma/internal/pose_manifold.h): a cost function
// writes [dr/d(dphi), dr/d(dp), 0] for a pose block, and Ceres multiplies it
// by PlusJacobian. For the body point r(x) = R_WB r_B + p_WB that block is
// [-Skew(R_WB r_B), I, 0]; the product must be the derivative of
// r(Plus(x, delta)) at delta = 0, which is taken here numerically. This ties
// Plus (left, world-axis increment; dphi first, dp second) to the columns the
// cost functions fill. Five-point central differences with h = 1e-3:
// truncation ~h^4/30 |r^(5)| and rounding ~eps/h keep the error near 1e-12,
// so 1e-10 is the tightest safe bound here.
AssertionResult LiftedJacobianMatchesPlus(const std::vector<Pose>& xs, const PlusFn& plus,
                                          std::mt19937& rng) {
  const PoseManifold manifold;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const Vector3d r_B = RandomVector(rng, 1.0);
    const auto point = [&](const Tangent& delta) {
      Pose y;
      plus(xs[i].data(), delta.data(), y.data());
      return Vector3d(RotationOf(y).toRotationMatrix() * r_B + y.tail<3>());
    };
    Eigen::Matrix<double, 3, 6> numeric;
    const double h = 1e-3;
    for (int k = 0; k < 6; ++k) {
      const Tangent e = Tangent::Unit(k);
      numeric.col(k) =
          (8 * (point(h * e) - point(-h * e)) - (point(2 * h * e) - point(-2 * h * e))) / (12 * h);
    }
    Eigen::Matrix<double, 3, 7, Eigen::RowMajor> lifted = Eigen::Matrix<double, 3, 7>::Zero();
    lifted.block<3, 3>(0, 0) = -Skew<double>(RotationOf(xs[i]).toRotationMatrix() * r_B);
    lifted.block<3, 3>(0, 3).setIdentity();
    Eigen::Matrix<double, 7, 6, Eigen::RowMajor> plus_jacobian;
    manifold.PlusJacobian(xs[i].data(), plus_jacobian.data());
    const AssertionResult r = Near(lifted * plus_jacobian, numeric, 1e-10);
    if (!r) return AssertionFailure() << "pose " << i << ": " << r.message();
  }
  return AssertionSuccess();
}

// The right-multiplied increment q * Exp(dphi) (body axes): a plausible slip.
void PlusInBodyAxes(const double* x, const double* delta, double* out) {
  const Quaterniond q{Eigen::Map<const Eigen::Vector4d>{x}};
  Eigen::Map<Eigen::Vector4d>{out} =
      (q * QuaternionExp(Eigen::Map<const Vector3d>{delta})).normalized().coeffs();
  for (int i = 0; i < 3; ++i) out[4 + i] = x[4 + i] + delta[3 + i];
}

PlusFn RealPlus() {
  return [](const double* x, const double* d, double* out) { PoseManifold().Plus(x, d, out); };
}

// ----------------------------------------------------------- Exp / Log ---

TEST(QuaternionExpLog, LogOfExpIsTheIdentityBelowPi) {
  std::mt19937 rng(1);
  EXPECT_TRUE(LogOfExpIsIdentity(RotationVectorsBelowPi(rng), QuaternionExp, QuaternionLog));
}

TEST(QuaternionExpLog, ExpOfLogIsTheSameRotation) {
  std::mt19937 rng(2);
  EXPECT_TRUE(ExpOfLogIsIdentity(Quaternions(rng), QuaternionExp, QuaternionLog));
}

TEST(QuaternionExpLog, ExpMatchesEigenAngleAxis) {
  std::mt19937 rng(3);
  EXPECT_TRUE(ExpMatchesAngleAxis(RotationVectorsBelowPi(rng), QuaternionExp));
}

TEST(QuaternionExpLog, AngleExactlyPi) {
  // The rotation by pi about a is the rotation by pi about -a, and Log may
  // return either: |pi a| rounds to M_PI or a neighbour, and cos(|v| / 2) to
  // +6e-17 or -1.6e-16, so w is +-1e-16 and Log picks the w >= 0 sign.
  std::mt19937 rng(4);
  std::vector<Vector3d> axes = Axes();
  for (int i = 0; i < 100; ++i) axes.push_back(RandomUnit(rng));
  for (const Vector3d& a : axes) {
    const Quaterniond q = QuaternionExp(kPi * a);
    const Vector3d log_q = QuaternionLog(q);
    EXPECT_TRUE(Near(log_q, kPi * a, kTol) || Near(log_q, -kPi * a, kTol)) << Str(log_q);
    EXPECT_TRUE(SameRotation(QuaternionExp(-kPi * a), q, kTol));
    // w = 0 exactly: both representatives have w >= 0, so Log may return
    // either +pi a or -pi a; the angle is pi and the axis is +-a.
    const Quaterniond q0(0.0, a.x(), a.y(), a.z());
    const Vector3d v = QuaternionLog(q0);
    EXPECT_NEAR(v.norm(), kPi, kTol);
    EXPECT_NEAR(std::fabs(v.normalized().dot(a)), 1.0, kTol);
    EXPECT_TRUE(SameRotation(QuaternionExp(v), q0, kTol));
  }
}

TEST(QuaternionExpLog, LogPicksTheShortWayAndIgnoresTheSign) {
  std::mt19937 rng(5);
  for (const Quaterniond& q : Quaternions(rng)) {
    if (q.w() == 0.0) continue;  // two valid answers, see AngleExactlyPi
    EXPECT_TRUE(Near(QuaternionLog(Quaterniond(-q.coeffs())), QuaternionLog(q), kTol));
  }
  // Past pi, Log returns the equivalent rotation vector of length 2 pi - |v|.
  std::uniform_real_distribution<double> angle(kPi + 0.01, 2 * kPi - 0.01);
  for (int i = 0; i < kRandomSamples; ++i) {
    const Vector3d a = RandomUnit(rng);
    const double t = angle(rng);
    EXPECT_TRUE(Near(QuaternionLog(QuaternionExp(t * a)), (t - 2 * kPi) * a, kTol)) << t;
  }
}

TEST(QuaternionExpLog, ExpIsAHomomorphismAlongOneAxis) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> angle(-2.0, 2.0);
  for (int i = 0; i < kRandomSamples; ++i) {
    const Vector3d a = RandomUnit(rng);
    const double s = angle(rng), t = angle(rng);
    EXPECT_TRUE(SameRotation(QuaternionExp(s * a) * QuaternionExp(t * a),
                             QuaternionExp((s + t) * a), kTol));
    EXPECT_TRUE(
        SameRotation(QuaternionExp(s * a) * QuaternionExp(-s * a), Quaterniond::Identity(), kTol));
    // The axis is fixed by the rotation.
    EXPECT_TRUE(Near(QuaternionExp(s * a).toRotationMatrix() * a, a, kTol));
  }
}

// ------------------------------------------------------------ RPY -------

Matrix3d Rx(double a) {
  Matrix3d R;
  R << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return R;
}
Matrix3d Ry(double a) {
  Matrix3d R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}
Matrix3d Rz(double a) {
  Matrix3d R;
  R << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return R;
}

TEST(Rpy, ConventionIsRzRyRx) {
  std::mt19937 rng(10);
  for (int i = 0; i < kRandomSamples; ++i) {
    const Vector3d rpy = RandomVector(rng, 4.0);
    EXPECT_TRUE(Near(RotationFromRpy(rpy), Rz(rpy.z()) * Ry(rpy.y()) * Rx(rpy.x()), kTol));
    EXPECT_TRUE(Near(RotationZ(rpy.z()), Rz(rpy.z()), kTol));
  }
}

TEST(Rpy, AnglesRoundTripAwayFromGimbalLock) {
  // |pitch| <= pi/2 - 0.1: the angles are determined to ~eps / cos(pitch).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-kPi, kPi), pitch(-kPi / 2 + 0.1, kPi / 2 - 0.1);
  std::vector<Vector3d> rpys = {Vector3d::Zero(), Vector3d(kPi, 0, 0), Vector3d(0, 0, kPi),
                                Vector3d(kPi, 0.3, kPi), Vector3d(-3.1, -1.4, 3.1)};
  for (int i = 0; i < kRandomSamples; ++i) rpys.push_back(Vector3d{angle(rng), pitch(rng), angle(rng)});
  EXPECT_TRUE(AnglesSurviveRpy(rpys, RotationFromRpy, RpyFromRotation));
}

TEST(Rpy, RotationRoundTripsForRandomRotations) {
  std::mt19937 rng(12);
  std::vector<Matrix3d> Rs;
  for (int i = 0; i < kRandomSamples; ++i) Rs.push_back(RandomRotation(rng).toRotationMatrix());
  EXPECT_TRUE(RotationSurvivesRpy(Rs, RotationFromRpy, RpyFromRotation));
}

TEST(Rpy, GimbalLockRotationRoundTripsWithRollZero) {
  // pitch = +-pi/2: only yaw -+ roll is defined; the documented answer puts
  // it all in yaw, and the rotation must come back.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::vector<Matrix3d> Rs;
  for (double pitch : {kPi / 2, -kPi / 2}) {
    for (int i = 0; i < kRandomSamples / 2; ++i) {
      const Vector3d rpy{angle(rng), pitch, angle(rng)};
      Rs.push_back(RotationFromRpy(rpy));
      const Vector3d back = RpyFromRotation(Rs.back());
      EXPECT_EQ(back.x(), 0.0);
      EXPECT_NEAR(back.y(), pitch, 1e-8);  // atan2(1, |cos| ~ 1e-16)
      // Rz(y) Ry(pi/2) Rx(r) depends on y - r; Rz(y) Ry(-pi/2) Rx(r) on y + r.
      EXPECT_LE(AngleDistance(back.z(), pitch > 0 ? rpy.z() - rpy.x() : rpy.z() + rpy.x()), kTol);
    }
  }
  EXPECT_TRUE(RotationSurvivesRpy(Rs, RotationFromRpy, RpyFromRotation));
}

TEST(Rpy, NearGimbalLockRotationRoundTrips) {
  // pitch = +-(pi/2 - c): the angles are ill-conditioned (~eps / c) but the
  // rotation is not, and must round-trip to kTol at every c.
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::vector<Matrix3d> Rs;
  for (double c : {1e-3, 1e-5, 1e-7, 1e-8, 1e-9, 3e-10, 1.1e-10, 9e-11, 1e-11, 1e-13, 1e-15}) {
    for (double sign : {1.0, -1.0}) {
      for (int i = 0; i < 50; ++i) {
        Rs.push_back(RotationFromRpy(Vector3d{angle(rng), sign * (kPi / 2 - c), angle(rng)}));
      }
    }
  }
  EXPECT_TRUE(RotationSurvivesRpy(Rs, RotationFromRpy, RpyFromRotation));
}

// ------------------------------------------------------- WrapAngle -----

TEST(WrapAngle, RangeIsMinusPiExclusiveToPiInclusive) {
  std::mt19937 rng(20);
  std::vector<double> angles = {0.0,
                                -0.0,
                                kPi,
                                -kPi,
                                std::nextafter(kPi, 4.0),
                                std::nextafter(-kPi, -4.0),
                                std::nextafter(-kPi, 0.0),
                                2 * kPi,
                                -2 * kPi,
                                3 * kPi,
                                -3 * kPi,
                                1e-300,
                                DBL_TRUE_MIN,
                                1e300,
                                -1e300,
                                DBL_MAX,
                                -DBL_MAX};
  std::uniform_real_distribution<double> wide(-1e3, 1e3);
  for (int i = 0; i < kRandomSamples; ++i) angles.push_back(wide(rng));
  EXPECT_TRUE(WrapsIntoRange(angles, WrapAngle));
  EXPECT_EQ(WrapAngle(kPi), kPi);
  EXPECT_EQ(WrapAngle(-kPi), kPi);
  EXPECT_EQ(WrapAngle(0.5), 0.5);
  EXPECT_EQ(WrapAngle(-0.5), -0.5);
}

TEST(WrapAngle, IsTwoPiPeriodic) {
  // a + 2 pi k is rounded once: up to ~eps * 2 pi |k| ~ 7e-14 at |k| = 50.
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (int i = 0; i < kRandomSamples; ++i) {
    const double a = angle(rng);
    for (int k = -50; k <= 50; ++k) {
      EXPECT_LE(AngleDistance(WrapAngle(a + 2 * kPi * k), WrapAngle(a)), kTol) << a << " " << k;
    }
  }
}

TEST(WrapAngle, NotANumberStaysNotANumber) {
  EXPECT_TRUE(std::isnan(WrapAngle(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_TRUE(std::isnan(WrapAngle(std::numeric_limits<double>::infinity())));
  EXPECT_TRUE(std::isnan(WrapAngle(-std::numeric_limits<double>::infinity())));
}

// ------------------------------------------------------------ Skew -----

TEST(Skew, IsTheCrossProductMatrix) {
  std::mt19937 rng(30);
  EXPECT_TRUE(SkewIsCrossProduct(rng, Skew<double>));
  const Eigen::Vector3f w(1.5f, -2.f, 0.25f), v(-0.5f, 3.f, 2.f);
  EXPECT_EQ(Skew<float>(w) * v, w.cross(v));
  for (int i = 0; i < 100; ++i) {
    const Vector3d a = RandomVector(rng, 3.0);
    // [a]x [a]x = a a^T - |a|^2 I; the entries are O(10).
    EXPECT_TRUE(Near(Skew<double>(a) * Skew<double>(a),
                     a * a.transpose() - a.squaredNorm() * Matrix3d::Identity(), 1e-13 * 10));
  }
}

// --------------------------------------------------- PoseManifold -------

std::vector<Tangent> Deltas(std::mt19937& rng) {
  std::vector<Tangent> out;
  Tangent d;
  d.setZero();
  out.push_back(d);
  for (double scale : {1e-12, 1e-8, 1e-4, 1e-2, 0.5, 1.5, 3.0}) {
    for (int i = 0; i < 4; ++i) {
      // Rotation part of length <= scale < pi.
      const Vector3d axis = RandomUnit(rng);
      d << scale * axis * std::uniform_real_distribution<double>(0.0, 1.0)(rng), RandomVector(rng, scale);
      out.push_back(d);
    }
  }
  d << (kPi - 1e-9) * Vector3d(0.6, 0, 0.8), 1, 2, 3;
  out.push_back(d);
  return out;
}

TEST(PoseManifold, Sizes) {
  const PoseManifold m;
  EXPECT_EQ(m.AmbientSize(), 7);
  EXPECT_EQ(m.TangentSize(), 6);
  EXPECT_EQ(kPoseAmbientSize, 7);
  EXPECT_EQ(kPoseTangentSize, 6);
}

TEST(PoseManifold, MinusUndoesPlus) {
  std::mt19937 rng(40);
  const auto poses = Poses(rng);
  EXPECT_TRUE(MinusUndoesPlus(poses, Deltas(rng), RealPlus()));
}

TEST(PoseManifold, PlusUndoesMinus) {
  // Plus(x, Minus(y, x)) == y, the rotation up to the sign of q.
  std::mt19937 rng(41);
  const PoseManifold m;
  const std::vector<Pose> xs = Poses(rng);
  const std::vector<Pose> ys = Poses(rng);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    for (std::size_t j = 0; j < ys.size(); j += 7) {
      Tangent d;
      Pose back;
      ASSERT_TRUE(m.Minus(ys[j].data(), xs[i].data(), d.data()));
      ASSERT_TRUE(m.Plus(xs[i].data(), d.data(), back.data()));
      EXPECT_LE(d.head<3>().norm(), kPi + kTol);
      EXPECT_TRUE(SameRotation(RotationOf(back), RotationOf(ys[j]), kTol)) << i << " " << j;
      const double scale = 1 + std::max(xs[i].tail<3>().cwiseAbs().maxCoeff(),
                                        ys[j].tail<3>().cwiseAbs().maxCoeff());
      EXPECT_TRUE(Near(back.tail<3>(), ys[j].tail<3>(), 2 * DBL_EPSILON * scale)) << i << " " << j;
    }
  }
}

TEST(PoseManifold, PlusZeroAndMinusSelf) {
  std::mt19937 rng(42);
  const PoseManifold m;
  const Tangent zero = Tangent::Zero();
  for (const Pose& x : Poses(rng)) {
    Pose y;
    Tangent d;
    m.Plus(x.data(), zero.data(), y.data());
    EXPECT_TRUE(Near(y, x, 2 * DBL_EPSILON));  // Plus renormalises q
    m.Minus(x.data(), x.data(), d.data());
    EXPECT_TRUE(Near(d, Tangent::Zero(), 0.0));  // q conj(q) cancels exactly
  }
}

TEST(PoseManifold, LiftedJacobianConvention) {
  std::mt19937 rng(43);
  const PoseManifold m;
  const std::vector<Pose> xs = Poses(rng);
  for (const Pose& x : xs) {
    Eigen::Matrix<double, 7, 6, Eigen::RowMajor> plus_j;
    Eigen::Matrix<double, 6, 7, Eigen::RowMajor> minus_j;
    ASSERT_TRUE(m.PlusJacobian(x.data(), plus_j.data()));
    ASSERT_TRUE(m.MinusJacobian(x.data(), minus_j.data()));
    Eigen::Matrix<double, 7, 6> expected_plus = Eigen::Matrix<double, 7, 6>::Zero();
    expected_plus.topRows<6>().setIdentity();
    EXPECT_TRUE(Near(plus_j, expected_plus, 0.0));
    EXPECT_TRUE(Near(minus_j, expected_plus.transpose(), 0.0));
    // Ceres requires MinusJacobian(x) * PlusJacobian(x) == I.
    EXPECT_TRUE(Near(minus_j * plus_j, Eigen::Matrix<double, 6, 6>::Identity(), 0.0));
    // RightMultiplyByPlusJacobian is the product with PlusJacobian.
    for (int rows : {0, 1, 3, 12}) {
      const Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor> A =
          Eigen::MatrixXd::Random(rows, 7);
      Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> out(rows, 6);
      ASSERT_TRUE(m.RightMultiplyByPlusJacobian(x.data(), rows, A.data(), out.data()));
      if (rows > 0) {
        EXPECT_TRUE(Near(out, A * plus_j, 0.0));
      }
    }
  }
  // In the lifted sense, Minus(Plus(x, e), x) has derivative I at e = 0, as
  // MinusJacobian * PlusJacobian says. Central differences, h = 1e-5: the map
  // is the identity up to rounding, so the error is rounding over h, ~eps / h
  // for the rotation and ~eps |p| / h for the position ((p + h) - p).
  for (const Pose& x : xs) {
    Eigen::Matrix<double, 6, 6> numeric;
    const double h = 1e-5;
    for (int k = 0; k < 6; ++k) {
      Pose xp, xm;
      Tangent dp, dm;
      const Tangent e = h * Tangent::Unit(k);
      const Tangent me = -e;
      m.Plus(x.data(), e.data(), xp.data());
      m.Plus(x.data(), me.data(), xm.data());
      m.Minus(xp.data(), x.data(), dp.data());
      m.Minus(xm.data(), x.data(), dm.data());
      numeric.col(k) = (dp - dm) / (2 * h);
    }
    const double position_scale = 1 + x.tail<3>().cwiseAbs().maxCoeff();
    EXPECT_TRUE(Near(numeric.topRows<3>(), Eigen::Matrix<double, 3, 6>::Identity(), 1e-10));
    EXPECT_TRUE(Near(numeric.bottomRows<3>(),
                     Eigen::Matrix<double, 6, 6>::Identity().bottomRows<3>(),
                     2 * DBL_EPSILON * position_scale / h));
  }
  EXPECT_TRUE(LiftedJacobianMatchesPlus(xs, RealPlus(), rng));
}

// ------------------------------------------------------------ State ----

TEST(State, PlusMinusRoundTrip) {
  std::mt19937 rng(50);
  const int n = 5;
  for (int trial = 0; trial < 100; ++trial) {
    State s(n), t(n);
    EXPECT_EQ(s.num_bodies(), n);
    EXPECT_EQ(s.tangent_size(), 6 * n);
    for (int b = 0; b < n; ++b) {
      const Quaterniond q_s = RandomRotation(rng);
      s.SetPose(b, q_s, RandomVector(rng, 5.0));
      const Quaterniond q_t = RandomRotation(rng);
      t.SetPose(b, q_t, RandomVector(rng, 5.0));
    }
    Eigen::VectorXd ds(6 * n);
    for (int b = 0; b < n; ++b) {
      const Vector3d axis = RandomUnit(rng);
      ds.segment<3>(6 * b) = 2.5 * axis * std::uniform_real_distribution<double>(0, 1)(rng);
      ds.segment<3>(6 * b + 3) = RandomVector(rng, 1.0);
    }
    State s_plus = s;
    s_plus.Plus(ds);
    const Eigen::VectorXd back = s_plus.Minus(s);
    ASSERT_EQ(back.size(), 6 * n);
    EXPECT_TRUE(Near(back, ds, 1e-13 * 10));  // entries O(1), positions O(5)
    for (int b = 0; b < n; ++b) {
      EXPECT_TRUE(
          SameRotation(s_plus.q_WB(b), QuaternionExp(ds.segment<3>(6 * b)) * s.q_WB(b), kTol));
    }
    // s (+) (t (-) s) == t.
    State u = s;
    u.Plus(t.Minus(s));
    for (int b = 0; b < n; ++b) {
      EXPECT_TRUE(SameRotation(u.q_WB(b), t.q_WB(b), kTol));
      EXPECT_TRUE(Near(u.p_WB(b), t.p_WB(b), kTol));
      EXPECT_TRUE(Near(u.R_WB(b), t.R_WB(b), kTol));
    }
  }
}

TEST(State, SetPoseNormalisesAndBodiesAreIndependent) {
  State s(3);
  for (int b = 0; b < 3; ++b) {
    EXPECT_TRUE(SameRotation(s.q_WB(b), Quaterniond::Identity(), 0.0));
    EXPECT_TRUE(Near(s.p_WB(b), Vector3d::Zero(), 0.0));
  }
  s.SetPose(1, Quaterniond(2, 0, 0, 2), Vector3d(1, 2, 3));
  EXPECT_NEAR(s.q_WB(1).norm(), 1.0, 2 * DBL_EPSILON);
  EXPECT_TRUE(SameRotation(s.q_WB(1), Quaterniond(std::sqrt(0.5), 0, 0, std::sqrt(0.5)), kTol));
  Eigen::VectorXd ds = Eigen::VectorXd::Zero(18);
  ds.segment<6>(6) << 0.1, 0.2, 0.3, 1, 1, 1;
  State before = s;
  s.Plus(ds);
  for (int b : {0, 2}) {
    EXPECT_TRUE(SameRotation(s.q_WB(b), before.q_WB(b), DBL_EPSILON));
    EXPECT_TRUE(Near(s.p_WB(b), before.p_WB(b), 0.0));
  }
  EXPECT_TRUE(Near(s.p_WB(1), Vector3d(2, 3, 4), 0.0));
}

// ------------------------------------------- the checks can fail --------

TEST(RotationTestHelpers, HelpersDetectWrongFormulas) {
  std::mt19937 rng(99);
  const std::vector<Vector3d> vs = RotationVectorsBelowPi(rng);

  // Log off by a relative 1e-11: within reach of the tolerance.
  const LogFn log_slightly_off = [](const Quaterniond& q) {
    return Vector3d((1 + 1e-11) * QuaternionLog(q));
  };
  EXPECT_FALSE(LogOfExpIsIdentity(vs, QuaternionExp, log_slightly_off));
  // The classic slip: Exp with the full angle instead of the half angle.
  const ExpFn exp_full_angle = [](const Vector3d& v) {
    const double t = v.norm();
    if (t == 0) return Quaterniond::Identity();
    const Vector3d axis = v / t;
    return Quaterniond(std::cos(t), std::sin(t) * axis.x(), std::sin(t) * axis.y(),
                       std::sin(t) * axis.z());
  };
  EXPECT_FALSE(ExpMatchesAngleAxis(vs, exp_full_angle));
  EXPECT_FALSE(ExpOfLogIsIdentity(Quaternions(rng), exp_full_angle, QuaternionLog));

  // RPY composed in the wrong order (Rx Ry Rz).
  const FromRpyFn xyz = [](const Vector3d& rpy) -> Matrix3d {
    return Rx(rpy.x()) * Ry(rpy.y()) * Rz(rpy.z());
  };
  std::vector<Matrix3d> Rs;
  std::vector<Vector3d> rpys;
  for (int i = 0; i < 50; ++i) {
    Rs.push_back(RandomRotation(rng).toRotationMatrix());
    rpys.push_back(RandomVector(rng, 1.0));
  }
  EXPECT_FALSE(RotationSurvivesRpy(Rs, xyz, RpyFromRotation));
  EXPECT_FALSE(AnglesSurviveRpy(rpys, xyz, RpyFromRotation));

  // Wrapping into [-pi, pi) instead of (-pi, pi], and a wrap off by a turn.
  const WrapFn half_open_wrong_end = [](double a) {
    const double w = WrapAngle(a);
    return w == kPi ? -kPi : w;
  };
  EXPECT_FALSE(WrapsIntoRange({kPi}, half_open_wrong_end));
  EXPECT_FALSE(WrapsIntoRange({1.0}, [](double a) { return WrapAngle(a) - 1e-9; }));

  // Skew transposed.
  EXPECT_FALSE(SkewIsCrossProduct(
      rng, [](const Vector3d& w) -> Matrix3d { return Skew<double>(w).transpose(); }));

  // Plus with the increment in body axes: Minus still undoes it at identity,
  // but the lifted Jacobian the cost functions write no longer matches.
  const std::vector<Pose> xs = Poses(rng);
  EXPECT_FALSE(LiftedJacobianMatchesPlus(xs, PlusInBodyAxes, rng));
  // Plus that drops a position component.
  const PlusFn plus_no_z = [](const double* x, const double* d, double* out) {
    PoseManifold().Plus(x, d, out);
    out[6] = x[6];
  };
  EXPECT_FALSE(MinusUndoesPlus(xs, Deltas(rng), plus_no_z));
}

}  // namespace
}  // namespace ccma
