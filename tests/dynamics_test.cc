// Inverse dynamics (analyses/dynamics.h) against closed forms written from
// the geometry, statics at rest, and the energy balance along a path.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analyses/dynamics.h"
#include "ccma/ccma.h"
#include "problems/forward_problem.h"
#include "problems/natural_spline.h"
#include "tests/bundled_models.h"
#include "tests/dynamics_fixtures.h"

namespace ccma {
namespace dynamics_test {

constexpr double kG = 9.81;

// (a) An arm on a motor: a hinge to the ground about -y at the origin, the
// arm's mass m at l along x, with a full inertia (off-diagonal terms too).
// Only I_yy (about the hinge axis) may enter: tau = (I_yy + m l^2) theta'' +
// m g l cos theta, whatever theta'.
TEST(InverseDynamics, ArmOnAMotorIsTheClosedForm) {
  const double m = 2.5, l = 0.4, Iyy = 0.03;
  const std::string text =
      "name: arm\nbodies:\n  - {name: arm, position: [0.2, 0, 0], mass: 2.5, com: [0.4, 0, 0],"
      " inertia: [0.02, 0.03, 0.025, 0.004, -0.003, 0.002]}\n"
      "joints:\n  - {name: hinge, type: revolute, actuated: true, between: [world, arm], point: [0, 0, 0], "
      "axis: [0, -1, 0]}\nend_effector: {body: arm, point: [0.5, 0, 0], controlled: [x, z]}\n";
  const Model model = LoadModelFromString(text, "arm.yaml");
  const InverseDynamics dynamics(model);
  ForwardProblem forward(model);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-2, 2);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, 0.7 * d(rng));
    const Eigen::VectorXd du = Eigen::VectorXd::Constant(1, d(rng));
    const Eigen::VectorXd ddu = Eigen::VectorXd::Constant(1, d(rng));
    ASSERT_TRUE(forward.Assemble(u).assembled);
    const DynamicsPoint p = dynamics.At(forward.state(), u, du, ddu);
    const double tau = (Iyy + m * l * l) * ddu[0] + m * kG * l * std::cos(u[0]);
    EXPECT_NEAR(p.efforts.control_efforts[0], tau, 1e-9 * (1 + std::abs(tau))) << trial;
    const double kinetic = 0.5 * (Iyy + m * l * l) * du[0] * du[0];
    EXPECT_NEAR(p.kinetic, kinetic, 1e-12 * (1 + kinetic));
    EXPECT_NEAR(p.potential, m * kG * l * std::sin(u[0]), 1e-12);
  }
}

// (b) A slider-crank, a closed loop: crank (pin mass m_c at r) on a motor
// about -y at the origin, a massless coupler of length L, a slider of mass M
// on a prismatic joint along x. With x(phi) = r cos phi + sqrt(L^2 -
// r^2 sin^2 phi) (phi from x, raising the crank):
//   tau = m_c r^2 phi'' + m_c g r cos phi + M x'' x_phi,
//   x'' = x_phi phi'' + x_phiphi phi'^2.
struct SliderCrank {
  double r = 0.1, L = 0.3, m_c = 1.5, M = 3.0, phi0 = 0.5;
  double D(double phi) const { return std::sqrt(L * L - r * r * std::sin(phi) * std::sin(phi)); }
  double x(double phi) const { return r * std::cos(phi) + D(phi); }
  double x_phi(double phi) const { return -r * std::sin(phi) - r * r * std::sin(phi) * std::cos(phi) / D(phi); }
  double x_phiphi(double phi) const {
    const double sc = std::sin(phi) * std::cos(phi), d = D(phi);
    return -r * std::cos(phi) - r * r * std::cos(2 * phi) / d - std::pow(r, 4) * sc * sc / (d * d * d);
  }
  double Torque(double phi, double dphi, double ddphi) const {
    const double xdd = x_phi(phi) * ddphi + x_phiphi(phi) * dphi * dphi;
    return m_c * r * r * ddphi + m_c * kG * r * std::cos(phi) + M * xdd * x_phi(phi);
  }
  std::string Yaml() const {
    const double bx = r * std::cos(phi0), bz = r * std::sin(phi0), cx = x(phi0);
    auto n = [](double v) { return std::to_string(v); };
    char buffer[2048];
    std::snprintf(buffer, sizeof(buffer),
                  "name: slider_crank\nbodies:\n"
                  "  - {name: crank, position: [0, 0, 0], mass: %.17g, com: [%.17g, 0, %.17g]}\n"
                  "  - {name: coupler, position: [%.17g, 0, %.17g]}\n"
                  "  - {name: slider, position: [%.17g, 0, 0], mass: %.17g}\n"
                  "joints:\n"
                  "  - {name: motor, type: revolute, actuated: true, q_home: %.17g, between: [world, crank], point: [0, 0, 0], axis: [0, -1, 0]}\n"
                  "  - {name: pin_b, type: revolute, between: [crank, coupler], point: [%.17g, 0, %.17g], axis: [0, 1, 0]}\n"
                  "  - {name: pin_c, type: revolute, between: [coupler, slider], point: [%.17g, 0, 0], axis: [0, 1, 0]}\n"
                  "  - {name: rail, type: prismatic, between: [world, slider], point: [%.17g, 0, 0], axis: [1, 0, 0]}\n"
                  "end_effector: {body: slider, point: [%.17g, 0, 0], controlled: [x]}\n",
                  m_c, bx, bz, bx, bz, cx, M, phi0, bx, bz, cx, cx, cx);
    (void)n;
    return buffer;
  }
};

TEST(InverseDynamics, SliderCrankIsTheClosedForm) {
  const SliderCrank sc;
  const Model model = LoadModelFromString(sc.Yaml(), "slider_crank.yaml");
  const InverseDynamics dynamics(model);
  ForwardProblem forward(model);
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> d(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const double phi = sc.phi0 + 0.8 * d(rng);
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, phi);
    const Eigen::VectorXd du = Eigen::VectorXd::Constant(1, 3 * d(rng));
    const Eigen::VectorXd ddu = Eigen::VectorXd::Constant(1, 5 * d(rng));
    ASSERT_TRUE(forward.Assemble(u).assembled);
    const DynamicsPoint p = dynamics.At(forward.state(), u, du, ddu);
    const double tau = sc.Torque(phi, du[0], ddu[0]);
    EXPECT_NEAR(p.efforts.control_efforts[0], tau, 1e-9 * (1 + std::abs(tau))) << "phi " << phi;
  }
}

// At rest the efforts are statics', bit for bit: the same loads and the
// same operations (EffortEvaluator::At is AtLoads(GeneralizedLoads)).
TEST(InverseDynamics, AtRestIsStaticsExactly) {
  const SliderCrank sc;
  const Model model = LoadModelFromString(sc.Yaml(), "slider_crank.yaml");
  const InverseDynamics dynamics(model);
  const EffortEvaluator statics(model);
  ForwardProblem forward(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(1);
  for (double phi : {0.1, 0.5, 1.1}) {
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, phi);
    ASSERT_TRUE(forward.Assemble(u).assembled);
    const DynamicsPoint p = dynamics.At(forward.state(), u, zero, zero);
    EXPECT_EQ(p.efforts.control_efforts[0], statics.At(forward.state(), u).control_efforts[0]);
    EXPECT_EQ(p.kinetic, 0.0);
  }
}

using testing::SinePath;
using testing::WithMasses;

// The work of the controls equals the change of kinetic plus potential
// energy along the spline's motion: power_W integrated by 3-point
// Gauss-Legendre on every segment (within a segment the motion is smooth;
// at the knots the third derivative of u jumps, which rules out Simpson
// across them) against the energies at the ends.
// `scale`: the integral of |power| [J].
double WorkAlong(const Model& model, const ControlPath& path, double* energy_change, double* scale) {
  const NaturalCubicSpline spline(path.times, UnwrappedControls(model, path.controls));  // as ComputeDynamics
  const InverseDynamics dynamics(model);
  ForwardProblem forward(model);
  const auto at = [&](double t) {
    const Eigen::VectorXd u = spline.Value(t);
    EXPECT_TRUE(forward.Assemble(u).assembled) << t;
    return dynamics.At(forward.state(), u, spline.Rate(t), spline.Acceleration(t));
  };
  const double node = std::sqrt(0.6), weights[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double work = 0;
  *scale = 0;
  for (size_t i = 0; i + 1 < path.times.size(); ++i) {
    const double mid = 0.5 * (path.times[i] + path.times[i + 1]), half = 0.5 * (path.times[i + 1] - path.times[i]);
    for (int k = 0; k < 3; ++k) {
      const double power = at(mid + (k - 1) * node * half).power;
      work += weights[k] * half * power;
      *scale += weights[k] * half * std::abs(power);
    }
  }
  const DynamicsPoint first = at(path.times.front()), last = at(path.times.back());
  *energy_change = (last.kinetic + last.potential) - (first.kinetic + first.potential);
  return work;
}

TEST(InverseDynamics, ControlsWorkIsTheChangeOfEnergyOnBundledModels) {
  int checked = 0;
  for (const std::string& name : testing::BundledModels()) {
    const Model model = WithMasses(LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"), 31);
    const ControlPath path = SinePath(model, 41, 101, 1.5);  // less than a period: the energy changes
    if (path.times.empty()) continue;  // controls tied (over-actuated): no free sine path
    double change = 0, scale = 0;
    const double work = WorkAlong(model, path, &change, &scale);
    EXPECT_GT(std::abs(change), 1e-5) << name;  // not a trivial 0 = 0 [J]
    EXPECT_NEAR(work, change, 1e-6 * std::abs(change)) << name;
    EXPECT_GT(scale, 10 * std::abs(change)) << name;  // the power changes sign: a real balance
    ++checked;
  }
  // The models whose every control moves freely (4dof_two_legged,
  // 6dof_symmetric, planar_3rpr, stewart_gough_6ups); the rest tie their controls.
  EXPECT_GE(checked, 4);
}

// The same balance on the models whose controls a sine cannot move (the
// over-actuated CCMAs: their bases' x and y are tied by the chain), along the
// dense rows ControlProblem::FollowWaypoints makes (0.5 mm steps): between
// consistent rows the spline's controls stay consistent to 1e-6 or better
// (their max_rate_inconsistency), and the balance holds to 1e-6 (measured:
// 1e-11 to 4e-8). A model with differential-drive bases follows a vertical
// loop: its radial bases then drive along their headings; on a horizontal
// loop they turn in place towards their travel within one row (100 rad/s and
// more), a kink no spline of the rows follows.
TEST(InverseDynamics, ControlsWorkIsTheChangeOfEnergyOnTiedModels) {
  int checked = 0;
  for (const std::string& name : testing::BundledModels()) {
    const Model model = WithMasses(LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"), 31);
    if (!SinePath(model, 41, 101, 1.5).times.empty()) continue;  // checked above
    const bool differential = std::any_of(model.mobile_bases.begin(), model.mobile_bases.end(),
                                          [](const MobileBase& b) { return b.type == BaseType::kDifferential; });
    const ControlPath path = testing::FollowedPath(model, 0.03, 1.2, 0.0005, differential);
    ASSERT_FALSE(path.times.empty()) << name;
    double change = 0, scale = 0;
    const double work = WorkAlong(model, path, &change, &scale);
    EXPECT_GT(std::abs(change), 1e-4) << name;
    EXPECT_NEAR(work, change, 1e-6 * std::abs(change)) << name;
    ++checked;
  }
  // 4dof_complete, 4dof_differential, 4dof_reduced, 6dof_asymmetric, 6dof_six_agents,
  // 6dof_three_legged, hybrid_ccma.
  EXPECT_GE(checked, 7);
}

// The slow limit: the same path 1000 times slower gives statics' efforts.
TEST(InverseDynamics, AThousandTimesSlowerIsStatics) {
  const Model model = WithMasses(LoadModel(std::string(CCMA_MODELS_DIR) + "/stewart_gough_6ups.yaml"), 32);
  ControlPath path = SinePath(model, 42, 60, 2.0);
  ASSERT_FALSE(path.times.empty());
  for (double& t : path.times) t *= 1000;
  const DynamicsReport report = ComputeDynamics(model, path);
  const EffortEvaluator statics(model);
  ForwardProblem forward(model);
  for (size_t r = 0; r < path.times.size(); ++r) {
    ASSERT_TRUE(forward.Assemble(path.controls[r]).assembled);
    const Eigen::VectorXd e = statics.At(forward.state(), forward.controls()).control_efforts;
    EXPECT_LT((report.rows[r].efforts - e).cwiseAbs().maxCoeff(), 1e-6 * (1 + e.cwiseAbs().maxCoeff())) << r;
  }
}

}  // namespace dynamics_test
}  // namespace ccma
