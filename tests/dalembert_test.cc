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
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "analyses/dynamics.h"
#include "ccma/ccma.h"
#include "ccma/internal/masses.h"
#include "problems/forward_problem.h"
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

// Per mass [omega; alpha; a_c] at time t by central differences with step h.
std::vector<Eigen::Matrix<double, 9, 1>> Motion(const Model& model, const testing::SineControls& sine, double t,
                                                double h) {
  ForwardProblem forward(model);
  const std::vector<MassPose> before = Poses(model, forward, sine.U(t - h));
  const std::vector<MassPose> now = Poses(model, forward, sine.U(t));
  const std::vector<MassPose> after = Poses(model, forward, sine.U(t + h));
  std::vector<Eigen::Matrix<double, 9, 1>> out(now.size());
  for (size_t i = 0; i < now.size(); ++i) {
    const Eigen::Vector3d plus = RotationVector(after[i].R * now[i].R.transpose());
    const Eigen::Vector3d minus = RotationVector(before[i].R * now[i].R.transpose());
    out[i] << (plus - minus) / (2 * h), (plus + minus) / (h * h), (after[i].c - 2 * now[i].c + before[i].c) / (h * h);
  }
  return out;
}

// The efforts at time t by d'Alembert and virtual work (above).
Eigen::VectorXd DAlembertEfforts(const Model& model, const testing::SineControls& sine, double t) {
  const double h = 0.01;
  const std::vector<Eigen::Matrix<double, 9, 1>> coarse = Motion(model, sine, t, h), fine = Motion(model, sine, t, h / 2);
  ForwardProblem forward(model);
  const Eigen::VectorXd u = sine.U(t);
  const std::vector<MassPose> now = Poses(model, forward, u);
  std::vector<Eigen::Vector3d> F, M;  // per mass: force at c, moment about c
  size_t i = 0;
  internal::ForEachMass(model, [&](int, const MassProperties& m) {
    const Eigen::Matrix<double, 9, 1> x = (4 * fine[i] - coarse[i]) / 3;  // Richardson
    const Eigen::Vector3d omega = x.head<3>(), alpha = x.segment<3>(3), a_c = x.tail<3>();
    const Eigen::Matrix3d I_W = now[i].R * m.inertia_B * now[i].R.transpose();
    F.push_back(m.mass * model.gravity - m.mass * a_c);
    M.push_back(-(I_W * alpha + omega.cross(I_W * omega)));
    ++i;
  });
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

}  // namespace dalembert_test
}  // namespace ccma
