// The rigid-motion predictor (problems/internal/planar_rigid_motion.h,
// ForwardOptions::rigid_motion_predictor): controls that move every base by
// one planar rigid motion are recognised (and nothing else is), and the
// forward solve then ends without an iteration at the moved state, which
// the geometry gives in closed form (end-effector R_z(psi) p + t, yaw +
// psi) and a solver without the predictor reaches too.
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ccma/internal/constraint_set.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "ccma/rotation.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "problems/internal/planar_rigid_motion.h"
#include "tests/bundled_models.h"
#include "tests/leg_closed_form.h"

namespace ccma {
namespace planar_rigid_motion_test {

using testing::BundledModels;

Model Load(const std::string& name) {
  if (name == "generated_12") {
    StewartOptions options;
    options.agents = 12;
    return LoadModelFromString(GenerateStewartModel(options), "generated_12.yaml");
  }
  return LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
}

// u with every base moved by rotation psi about world z, then translation t.
Eigen::VectorXd Moved(const Model& m, const Eigen::VectorXd& u, double psi, const Eigen::Vector2d& t) {
  Eigen::VectorXd v = u;
  const Eigen::Rotation2Dd R(psi);
  for (int k = 0; k < m.num_bases(); ++k) {
    const int i = m.base_control(k);
    v.segment<2>(i) = R * u.segment<2>(i) + t;
    v[i + 2] += psi;
  }
  return v;
}

// Controls away from home: a seeded 2 cm / 0.02 rad end-effector move.
Eigen::VectorXd OffHome(const Model& m, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1, 1);
  ControlProblem control(m);
  PoseTarget target = control.CurrentPose();
  target.position += 0.02 * Eigen::Vector3d{d(rng), d(rng), d(rng)};
  target.rpy += 0.02 * Eigen::Vector3d{d(rng), d(rng), d(rng)};
  control.MoveTo(target);
  return control.controls();
}

class RigidMotion : public ::testing::TestWithParam<std::string> {};

TEST_P(RigidMotion, IsRecognisedExactlyAndOnlyForOneRigidMotionOfAllBases) {
  const Model m = Load(GetParam());
  if (m.num_bases() == 0) GTEST_SKIP() << "no bases";
  const Eigen::VectorXd u = OffHome(m, 3);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> d(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const double psi = 1.5 * d(rng);
    const Eigen::Vector2d t{0.5 * d(rng), 0.5 * d(rng)};
    Eigen::VectorXd v = Moved(m, u, psi, t);
    PlanarRigidMotion motion;
    ASSERT_TRUE(PlanarRigidMotionBetween(m, u, v, &motion)) << "trial " << trial;
    EXPECT_NEAR(motion.dtheta, psi, 1e-14);
    EXPECT_LT((motion.t - t).norm(), 1e-14);
    // Headings are angles: a turn of 2 pi on one base changes nothing.
    v[m.base_control(m.num_bases() - 1) + 2] += 2 * M_PI;
    EXPECT_TRUE(PlanarRigidMotionBetween(m, u, v, &motion));
    // One base off the formation by 1e-9 m, or turned by 1e-9 rad (a legged
    // body raised or tilted by as much): a change of shape.
    for (int i = 0; i < m.num_base_controls(); ++i) {
      Eigen::VectorXd w = v;
      w[i] += 1e-9;
      EXPECT_FALSE(PlanarRigidMotionBetween(m, u, w, &motion)) << "control " << i;
    }
    // An actuated joint moved: not rigid.
    for (int i = m.num_base_controls(); i < m.num_controls(); ++i) {
      Eigen::VectorXd w = v;
      w[i] += 1e-9;
      EXPECT_FALSE(PlanarRigidMotionBetween(m, u, w, &motion)) << "control " << i;
    }
  }
  Eigen::VectorXd bad = u;
  bad[0] = std::numeric_limits<double>::quiet_NaN();
  PlanarRigidMotion motion;
  EXPECT_FALSE(PlanarRigidMotionBetween(m, u, u, &motion));  // nothing moved
  EXPECT_FALSE(PlanarRigidMotionBetween(m, u, bad, &motion));
  // A non-finite value anywhere, on either side (a position, a heading, the
  // last control), even where the rest is a rigid move.
  Eigen::VectorXd shifted = u;
  for (int k = 0; k < m.num_bases(); ++k) shifted[m.base_control(k)] += 0.01;
  ASSERT_TRUE(PlanarRigidMotionBetween(m, u, shifted, &motion));
  for (const int i : {0, 2, static_cast<int>(u.size()) - 1}) {
    for (const double x : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
      Eigen::VectorXd poisoned = shifted;
      poisoned[i] = x;
      EXPECT_FALSE(PlanarRigidMotionBetween(m, u, poisoned, &motion)) << "control " << i << " = " << x;
      EXPECT_FALSE(PlanarRigidMotionBetween(m, poisoned, u, &motion)) << "control " << i << " = " << x;
    }
  }
  EXPECT_FALSE(PlanarRigidMotionBetween(m, u, u.head(u.size() - 1), &motion));
  // A change at the scale of an outer solver's last steps that is not rigid
  // (one base moved 1e-13 m) is not one, however small.
  Eigen::VectorXd tiny = u;
  tiny[0] += 1e-13;
  EXPECT_FALSE(PlanarRigidMotionBetween(m, u, tiny, &motion));
  // A rigid one of that size is.
  EXPECT_TRUE(PlanarRigidMotionBetween(m, u, Moved(m, u, 0, Eigen::Vector2d(1e-13, 0)), &motion));
}

TEST_P(RigidMotion, FormationMovesEndWithoutAnIterationWhereTheGeometrySays) {
  const Model m = Load(GetParam());
  if (m.num_bases() == 0) GTEST_SKIP() << "no bases";
  ForwardOptions plain_options;
  plain_options.rigid_motion_predictor = false;
  ForwardProblem forward(m), plain(m, plain_options);
  Eigen::VectorXd u = OffHome(m, 5);
  ASSERT_TRUE(forward.Assemble(u).assembled);
  ASSERT_TRUE(plain.Assemble(u).assembled);
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> d(-1, 1);
  for (int step = 0; step < 12; ++step) {
    // Formation moves as a path would give them: 2 mm and 0.002 rad, or
    // (not for a mechanism anchored to the ground, which would be pulled
    // apart) a jump of up to 0.3 m and 0.5 rad.
    const bool jump = step % 2 == 1 && MovesRigidlyWithItsBases(m);
    const double scale = jump ? 0.3 : 0.002;
    const double psi = (jump ? 0.5 : 0.002) * d(rng);
    const Eigen::Vector2d t{scale * d(rng), scale * d(rng)};
    const EndEffectorPose before = forward.end_effector();
    u = Moved(m, u, psi, t);
    const ForwardResult r = forward.Solve(u);
    const ForwardResult p = plain.Assemble(u);
    ASSERT_TRUE(p.assembled) << "step " << step;
    if (!MovesRigidlyWithItsBases(m)) {
      // Anchored to the ground: the bases' motion changes its shape; the
      // predictor stays out and the solve iterates as without it.
      EXPECT_GT(r.iterations, 0) << "step " << step;
    } else {
      EXPECT_EQ(r.iterations, 0) << "step " << step;
      EXPECT_TRUE(r.gradient_norm_is_bound) << "step " << step;  // assembled: residuals only
      const Eigen::Matrix3d Rz = RotationZ(psi);
      const Eigen::Vector3d expected = Rz * before.position + Eigen::Vector3d(t.x(), t.y(), 0);
      EXPECT_LT((forward.end_effector().position - expected).norm(), 1e-12) << "step " << step;
      EXPECT_LT((forward.end_effector().rotation - Rz * before.rotation).norm(), 1e-12) << "step " << step;
    }
    EXPECT_TRUE(r.converged && r.assembled) << "step " << step;
    EXPECT_LE(r.residual_energy, kRigidImageEnergy) << "step " << step;
    EXPECT_LT(r.gradient_norm, 1e-12) << "step " << step;
    if (r.gradient_norm_is_bound) {
      // Checked on residuals only: the reported norm bounds the true one.
      EXPECT_EQ(r.iterations, 0) << "step " << step;
      EnergyDerivatives derivatives;
      forward.constraints().EvaluateDerivatives(forward.state(), forward.controls(), &derivatives);
      EXPECT_LE(derivatives.G.lpNorm<Eigen::Infinity>(), r.gradient_norm) << "step " << step;
      EXPECT_GT(r.gradient_norm, 0) << "step " << step;
    }
    EXPECT_LT((forward.end_effector().position - plain.end_effector().position).norm(), 1e-10) << "step " << step;
    EXPECT_LT(forward.state().Minus(plain.state()).lpNorm<Eigen::Infinity>(), 1e-9) << "step " << step;
  }
}

INSTANTIATE_TEST_SUITE_P(Bundled, RigidMotion,
                         ::testing::ValuesIn([] {
                           std::vector<std::string> names = BundledModels();
                           names.push_back("generated_12");
                           return names;
                         }()),
                         [](const auto& info) { return info.param; });

TEST(RigidMotionPredictor, AStationaryPointOutOfReachMovesAsItIs) {
  // Unreachable controls (one base pulled 1 m away): the solve ends at a
  // stationary point with E > 0. Moved rigidly, it stays one, with the same
  // E, and the predictor reports it without an iteration.
  const Model m = Load("4dof_reduced");
  ForwardProblem forward(m);
  Eigen::VectorXd u = m.home_controls();
  u[0] += 1.0;
  const ForwardResult far = forward.Assemble(u);
  ASSERT_TRUE(far.converged);
  ASSERT_FALSE(far.assembled);
  ASSERT_GT(far.residual_energy, 1e-3);
  const ForwardResult moved = forward.Solve(Moved(m, u, 0.3, Eigen::Vector2d(0.1, -0.2)));
  EXPECT_EQ(moved.iterations, 0);
  EXPECT_TRUE(moved.converged);
  EXPECT_FALSE(moved.assembled);
  EXPECT_NEAR(moved.residual_energy, far.residual_energy, 1e-12 * far.residual_energy);
  EXPECT_LT(moved.gradient_norm, 1e-12);
  EXPECT_FALSE(moved.gradient_norm_is_bound);  // E > 0: the gradient itself, not a bound
}

TEST(RigidMotionPredictor, AStateFromElsewhereIsNotTakenAsConverged) {
  // After SetState (a state nobody solved for these controls) the rigid
  // image is only a starting point: the solve iterates and assembles.
  const Model m = Load("6dof_symmetric");
  ForwardProblem forward(m);
  State s = forward.state();
  Eigen::VectorXd ds = Eigen::VectorXd::Zero(s.tangent_size());
  ds[6 * 1 + 3] = 0.01;  // body 1 moved 1 cm along x
  s.Plus(ds);
  forward.SetState(s);
  const ForwardResult r = forward.Solve(Moved(m, m.home_controls(), 0.1, Eigen::Vector2d(0.05, 0)));
  EXPECT_GT(r.iterations, 0);
  EXPECT_TRUE(r.assembled);
  EXPECT_LT(r.residual_energy, 1e-24);
}

TEST(RigidMotionPredictor, RepeatedLapsOfAHorizontalCircleStayExact) {
  // The benchmark's track (benchmarks/forward_benchmark.cc): the bases in
  // closed form for an end-effector on a horizontal 5 cm circle, 200 steps,
  // 50 laps from one ForwardProblem. Every step ends assembled at the
  // closed-form end-effector, and the rounding of 10,000 rigid moves does
  // not pile up past kRigidImageEnergy.
  for (const std::string name : {"4dof_reduced", "6dof_six_agents"}) {
    const Model m = Load(name);
    std::vector<Eigen::VectorXd> track;
    std::vector<Eigen::Vector3d> points;
    for (int k = 0; k <= 200; ++k) {
      const double angle = 2 * M_PI * k / 200;
      const Eigen::Vector3d p =
          m.end_effector.p_W_home + 0.05 * Eigen::Vector3d(std::cos(angle) - 1, std::sin(angle), 0);
      Eigen::VectorXd u = m.home_controls();
      for (const auto& leg : testing::FindLegs(m)) {
        u.segment<3>(3 * leg.base) = testing::BasePoseForLeg(m, leg, p, Eigen::Matrix3d::Identity(), 0.0);
      }
      track.push_back(u);
      points.push_back(p);
    }
    ForwardProblem forward(m);
    int without_iteration = 0;
    for (int lap = 0; lap < 50; ++lap) {
      for (int k = 1; k <= 200; ++k) {
        const ForwardResult r = forward.Solve(track[k]);
        ASSERT_TRUE(r.assembled) << name << " lap " << lap << " step " << k << ": E " << r.residual_energy;
        ASSERT_LE(r.residual_energy, kRigidImageEnergy) << name << " lap " << lap << " step " << k;
        ASSERT_LT((forward.end_effector().position - points[k]).norm(), 1e-12) << name << " step " << k;
        without_iteration += r.iterations == 0;
      }
    }
    // Most steps: the rounding reaches kRigidImageEnergy only every few
    // hundred moves (then one iteration cleans it).
    EXPECT_GE(without_iteration, 9500) << name;
  }
}

TEST(RigidMotionPredictor, OnlyMechanismsFreeOfTheGroundMoveWithTheirBases) {
  EXPECT_TRUE(MovesRigidlyWithItsBases(Load("4dof_reduced")));
  EXPECT_TRUE(MovesRigidlyWithItsBases(Load("generated_12")));
  // Anchored to `world` (and without bases): never moved rigidly.
  EXPECT_FALSE(MovesRigidlyWithItsBases(Load("planar_3rpr")));
  EXPECT_FALSE(MovesRigidlyWithItsBases(Load("stewart_gough_6ups")));
}

}  // namespace
}  // namespace ccma
