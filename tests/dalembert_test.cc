// Inverse dynamics against an independent d'Alembert computation built only
// from assembled poses (issue 52): no Jacobian, multiplier or sensitivity
// of ccma's is used on the reference side.
//   1. Every body's centre-of-mass acceleration a_c, angular velocity omega
//      and angular acceleration alpha from central differences in time of
//      the poses assembled along an analytic control path (Richardson
//      extrapolation of steps h and h/2: error O(h^4)).
//   2. Its d'Alembert forces: F = m g - m a_c at the centre of mass and
//      M = -(I_W alpha + omega x I_W omega) about it (I_W = R I_B R^T).
//   3. A control's effort by virtual work: e_k = -sum_b (F . dc/du_k +
//      M . dphi/du_k), the virtual displacements dc/du_k, dphi/du_k from
//      central differences in u_k of assembled poses.
// On every bundled model whose controls move freely, with seeded masses,
// inertias and a payload, at interior instants of a sine path.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "analyses/dynamics.h"
#include "ccma/ccma.h"
#include "ccma/internal/masses.h"
#include "problems/forward_problem.h"
#include "problems/natural_spline.h"
#include "tests/bundled_models.h"
#include "tests/dynamics_fixtures.h"

namespace ccma {
namespace dalembert_test {

// The rotation vector of R (Eigen's angle-axis, not ccma's Log).
Eigen::Vector3d RotationVector(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

// A mass's world centre and its body's rotation at an assembled state.
struct MassPose {
  Eigen::Vector3d c;
  Eigen::Matrix3d R;
};

// Every mass of the model (bodies, then the payload: ccma/internal/masses.h)
// at controls u, assembled from `forward`'s current state (close to u).
std::vector<MassPose> Poses(const Model& model, ForwardProblem& forward, const Eigen::VectorXd& u) {
  EXPECT_TRUE(forward.Assemble(u).assembled);
  std::vector<MassPose> out;
  internal::ForEachMass(model, [&](int b, const MassProperties& m) {
    const State& s = forward.state();
    out.push_back({s.p_WB(b) + s.R_WB(b) * m.com_B, s.R_WB(b)});
  });
  return out;
}

// Controls as a function of time [s].
using ControlCurve = std::function<Eigen::VectorXd(double)>;

// Per mass [omega; alpha; a_c; v_c] at time t by central differences with step h.
std::vector<Eigen::Matrix<double, 12, 1>> Motion(const Model& model, const ControlCurve& U, double t, double h) {
  ForwardProblem forward(model);
  const std::vector<MassPose> before = Poses(model, forward, U(t - h));
  const std::vector<MassPose> now = Poses(model, forward, U(t));
  const std::vector<MassPose> after = Poses(model, forward, U(t + h));
  std::vector<Eigen::Matrix<double, 12, 1>> out(now.size());
  for (size_t i = 0; i < now.size(); ++i) {
    const Eigen::Vector3d plus = RotationVector(after[i].R * now[i].R.transpose());
    const Eigen::Vector3d minus = RotationVector(before[i].R * now[i].R.transpose());
    out[i] << (plus - minus) / (2 * h), (plus + minus) / (h * h), (after[i].c - 2 * now[i].c + before[i].c) / (h * h),
        (after[i].c - before[i].c) / (2 * h);
  }
  return out;
}

// Per mass at time t: its d'Alembert force at the centre of mass (gravity
// included) and moment about it, and its omega and v_c (Richardson of the
// steps h and h/2), with the poses at t.
struct DAlembertLoads {
  std::vector<Eigen::Vector3d> F, M, omega, v_c;
  std::vector<MassPose> poses;
};

DAlembertLoads LoadsAt(const Model& model, const ControlCurve& U, double t, double h) {
  const std::vector<Eigen::Matrix<double, 12, 1>> coarse = Motion(model, U, t, h), fine = Motion(model, U, t, h / 2);
  ForwardProblem forward(model);
  DAlembertLoads out;
  out.poses = Poses(model, forward, U(t));
  size_t i = 0;
  internal::ForEachMass(model, [&](int, const MassProperties& m) {
    const Eigen::Matrix<double, 12, 1> x = (4 * fine[i] - coarse[i]) / 3;  // Richardson
    const Eigen::Vector3d omega = x.head<3>(), alpha = x.segment<3>(3), a_c = x.segment<3>(6);
    const Eigen::Matrix3d I_W = out.poses[i].R * m.inertia_B * out.poses[i].R.transpose();
    out.F.push_back(m.mass * model.gravity - m.mass * a_c);
    out.M.push_back(-(I_W * alpha + omega.cross(I_W * omega)));
    out.omega.push_back(omega);
    out.v_c.push_back(x.tail<3>());
    ++i;
  });
  return out;
}

// The efforts at time t by d'Alembert and virtual work (above).
Eigen::VectorXd DAlembertEfforts(const Model& model, const testing::SineControls& sine, double t) {
  const ControlCurve U = [&sine](double time) { return sine.U(time); };
  const DAlembertLoads loads = LoadsAt(model, U, t, 0.01);
  const std::vector<Eigen::Vector3d>& F = loads.F;
  const std::vector<Eigen::Vector3d>& M = loads.M;
  const std::vector<MassPose>& now = loads.poses;
  ForwardProblem forward(model);
  const Eigen::VectorXd u = sine.U(t);
  const double eps = 1e-5;
  Eigen::VectorXd e = Eigen::VectorXd::Zero(u.size());
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    Eigen::VectorXd up = u, down = u;
    up[k] += eps;
    down[k] -= eps;
    const std::vector<MassPose> p = Poses(model, forward, up), q = Poses(model, forward, down);
    for (size_t j = 0; j < now.size(); ++j) {
      const Eigen::Vector3d dc = (p[j].c - q[j].c) / (2 * eps);
      const Eigen::Vector3d dphi = RotationVector(p[j].R * q[j].R.transpose()) / (2 * eps);
      e[k] -= F[j].dot(dc) + M[j].dot(dphi);
    }
  }
  return e;
}

TEST(DAlembert, EffortsEqualFiniteDifferencesOfAssembledPosesOnBundledModels) {
  int checked = 0;
  for (const std::string& name : testing::BundledModels()) {
    const Model model = testing::WithMasses(LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"), 51);
    if (testing::SinePath(model, 41, 21, 1.5).times.empty()) continue;  // controls tied: no free sine path
    const testing::SineControls sine(model, 41, 1.5);
    const InverseDynamics dynamics(model);
    ForwardProblem forward(model);
    for (const double t : {0.3, 0.8, 1.2}) {
      ASSERT_TRUE(forward.Assemble(sine.U(t)).assembled) << name;
      const Eigen::VectorXd e =
          dynamics.At(forward.state(), forward.controls(), sine.Rate(t), sine.Acceleration(t)).efforts.control_efforts;
      const Eigen::VectorXd reference = DAlembertEfforts(model, sine, t);
      const Eigen::VectorXd inertial_only = reference - EffortEvaluator(model).At(forward.state(), forward.controls())
                                                            .control_efforts;
      const double scale = 1 + reference.cwiseAbs().maxCoeff();
      EXPECT_LT((e - reference).cwiseAbs().maxCoeff(), 1e-6 * scale) << name << " t=" << t;
      // The motion matters: the inertial part is far above the tolerance.
      EXPECT_GT(inertial_only.cwiseAbs().maxCoeff(), 1e-3 * scale) << name << " t=" << t;
    }
    ++checked;
  }
  EXPECT_GE(checked, 4);  // 4dof_two_legged, 6dof_symmetric, planar_3rpr, stewart_gough_6ups at least
}

// The over-actuated models tie their controls, so an effort of one control
// alone is not defined (the multipliers share the loads at minimum norm) and
// a control cannot be moved alone for its virtual displacement. Their
// d'Alembert check is the power: along the dense rows of a followed path
// (tests/dynamics_fixtures.h; consistent between the rows), at the middle of
// three spline segments (a cubic there: h at most 0.4 of the segment and 2 ms, and h/2),
// e . u' = -sum (F . v_c + M . omega) with F, M, v_c, omega from the poses.
// (Power cannot see the gyroscopic moment: omega . (omega x I omega) = 0;
// the efforts of the free models above do.)
TEST(DAlembert, PowerEqualsFiniteDifferencesOfAssembledPosesOnTiedModels) {
  int checked = 0;
  for (const std::string& name : testing::BundledModels()) {
    const Model model = testing::WithMasses(LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"), 52);
    if (!testing::SinePath(model, 41, 21, 1.5).times.empty()) continue;  // free: checked above
    const bool differential = std::any_of(model.mobile_bases.begin(), model.mobile_bases.end(),
                                          [](const MobileBase& b) { return b.type == BaseType::kDifferential; });
    const ControlPath path = testing::FollowedPath(model, 0.03, 1.2, 0.0005, differential);
    ASSERT_GT(path.times.size(), 20u) << name;
    const NaturalCubicSpline spline(path.times, UnwrappedControls(model, path.controls));
    const ControlCurve U = [&spline](double t) { return spline.Value(t); };
    const InverseDynamics dynamics(model);
    ForwardProblem forward(model);
    for (const double where : {0.25, 0.5, 0.75}) {
      const size_t k = static_cast<size_t>(where * static_cast<double>(path.times.size() - 2));
      const double t = 0.5 * (path.times[k] + path.times[k + 1]);
      const double h = std::min(0.4 * (path.times[k + 1] - path.times[k]), 0.002);
      ASSERT_TRUE(forward.Assemble(U(t)).assembled) << name;
      const double power = dynamics.At(forward.state(), forward.controls(), spline.Rate(t), spline.Acceleration(t)).power;
      const DAlembertLoads loads = LoadsAt(model, U, t, h);
      double reference = 0, scale = 0;
      for (size_t j = 0; j < loads.F.size(); ++j) {
        reference -= loads.F[j].dot(loads.v_c[j]) + loads.M[j].dot(loads.omega[j]);
        scale += std::abs(loads.F[j].dot(loads.v_c[j])) + std::abs(loads.M[j].dot(loads.omega[j]));
      }
      EXPECT_GT(scale, 1e-3) << name;  // the mechanism moves
      EXPECT_NEAR(power, reference, 1e-6 * scale) << name << " t=" << t;
    }
    ++checked;
  }
  EXPECT_GE(checked, 7);  // every over-actuated bundled model
}

}  // namespace dalembert_test
}  // namespace ccma
