// Regression against reference configurations: for seeded end-effector poses
// near home, every base pose follows in closed form from the leg geometry
// (tests/leg_closed_form.h); the forward problem at those controls must put
// the end-effector exactly there (1e-9 m, 1e-9 rad) and assemble.
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "formats/model_loader.h"
#include "ccma/rotation.h"
#include "problems/forward_problem.h"
#include "tests/leg_closed_form.h"

namespace ccma {
namespace reference_configurations_test {

using testing::BasePoseForLeg;
using testing::FindLegs;
using testing::Leg;

constexpr int kPosesPerModel = 20;

Model LoadReference(const std::string& name) {
  return LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
}

struct Target {
  Eigen::Vector3d p_EE;
  Eigen::Matrix3d R_EE;
  Eigen::VectorXd u;
};

// A seeded pose within 3 cm and 0.05 rad of home (no tilt for 4-DOF models),
// and the closed-form controls that reach it.
Target MakeTarget(const Model& m, std::mt19937& rng) {
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  const bool tilts = m.end_effector.controlled[kRoll];
  Target t;
  t.p_EE = m.end_effector.p_W_home + 0.03 * Eigen::Vector3d{d(rng), d(rng), d(rng)};
  const Eigen::Vector3d rpy{tilts ? 0.05 * d(rng) : 0.0, tilts ? 0.05 * d(rng) : 0.0, 0.05 * d(rng)};
  t.R_EE = RotationFromRpy(rpy);
  t.u = m.home_controls();
  for (const Leg& leg : FindLegs(m)) {
    t.u.segment<3>(3 * leg.base) = BasePoseForLeg(m, leg, t.p_EE, t.R_EE, 0.05 * d(rng));
  }
  return t;
}

class ReferenceConfigurations : public ::testing::TestWithParam<std::string> {};

TEST_P(ReferenceConfigurations, ClosedFormControlsPutTheEndEffectorOnTarget) {
  const Model m = LoadReference(GetParam());
  const std::vector<Leg> legs = FindLegs(m);
  ASSERT_EQ(static_cast<int>(legs.size()), m.num_bases());
  for (int seed = 0; seed < kPosesPerModel; ++seed) {
    std::mt19937 rng(seed);
    const Target t = MakeTarget(m, rng);
    ForwardProblem forward(m);
    const ForwardResult r = forward.Assemble(t.u);
    ASSERT_TRUE(r.assembled) << GetParam() << " seed " << seed << ": E = " << r.residual_energy;
    EXPECT_TRUE(r.converged) << r.message;
    EXPECT_LT(r.residual_energy, 1e-22);
    const EndEffectorPose ee = forward.end_effector();
    EXPECT_LT((ee.position - t.p_EE).norm(), 1e-9) << GetParam() << " seed " << seed;
    const double angle = QuaternionLog(Eigen::Quaterniond(ee.rotation * t.R_EE.transpose())).norm();
    EXPECT_LT(angle, 1e-9) << GetParam() << " seed " << seed;
    // Every base sits exactly at its control (motor rows satisfied).
    for (int k = 0; k < m.num_bases(); ++k) {
      const int body = m.mobile_bases[k].body;
      EXPECT_NEAR(forward.state().p_WB(body).x(), t.u[3 * k], 1e-10);
      EXPECT_NEAR(forward.state().p_WB(body).y(), t.u[3 * k + 1], 1e-10);
      EXPECT_NEAR(forward.state().p_WB(body).z(), 0.0, 1e-10);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(FiveReferenceModels, ReferenceConfigurations,
                         ::testing::Values("4dof_reduced", "4dof_complete", "6dof_symmetric",
                                           "6dof_asymmetric", "6dof_six_agents"));

TEST(ReferenceConfigurations, LegShapesAreTheOnesOfThePaper) {
  auto shapes = [](const std::string& name) {
    std::string s;
    for (const Leg& leg : FindLegs(LoadReference(name))) s += leg.shape + " ";
    return s;
  };
  EXPECT_EQ(shapes("4dof_reduced"), "RRR RRR RRR ");
  EXPECT_EQ(shapes("4dof_complete"), "FRR FRR FRR ");
  EXPECT_EQ(shapes("6dof_symmetric"), "FRS FRS FRS ");
  EXPECT_EQ(shapes("6dof_asymmetric"), "FRS FRS FRRU ");
  EXPECT_EQ(shapes("6dof_six_agents"), "RRS RRS RRS RRS RRS RRS ");
}

// The oracle itself must not be vacuous: perturbing one closed-form control
// by 1 mm moves the end-effector off target (4-DOF: not assembled at all).
TEST(ReferenceConfigurations, PerturbedControlsMissTheTarget) {
  for (const std::string name : {"4dof_reduced", "6dof_symmetric"}) {
    const Model m = LoadReference(name);
    std::mt19937 rng(3);
    Target t = MakeTarget(m, rng);
    t.u[0] += 1e-3;
    ForwardProblem forward(m);
    const ForwardResult r = forward.Assemble(t.u);
    const double miss = (forward.end_effector().position - t.p_EE).norm();
    EXPECT_TRUE(!r.assembled || miss > 1e-5) << name << ": miss " << miss;
  }
}

}  // namespace
}  // namespace ccma
