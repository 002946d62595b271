// The forward problem: exact assembly where the geometry gives the answer,
// honest reports where it cannot assemble, warm starts, bad input, and the
// same result whatever orientation the bodies' home frames have.
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <regex>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "formats/model_loader.h"
#include "ccma/rotation.h"
#include "problems/forward_problem.h"
#include "tests/leg_closed_form.h"
#include "tests/model_text.h"

namespace ccma {
namespace forward_problem_test {

const std::vector<std::string> kReferenceModels = {"4dof_reduced", "4dof_complete", "6dof_symmetric",
                                                   "6dof_asymmetric", "6dof_six_agents"};

std::string ReadReference(const std::string& name) {
  std::ifstream in(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
Model LoadReference(const std::string& name) {
  return LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
}

// Controls that move every base by the same planar rigid motion (rotation by
// psi about the world z axis, then translation t): the whole mechanism moves
// rigidly, so these are reachable for any model and the end-effector's pose
// follows in closed form. The tests below that use them test the solver
// itself, so they switch off the predictor that moves the state rigidly
// (planar_rigid_motion_test.cc covers it).
ForwardOptions WithoutRigidPredictor() {
  ForwardOptions options;
  options.rigid_motion_predictor = false;
  return options;
}

Eigen::VectorXd RigidlyMovedControls(const Model& m, double psi, const Eigen::Vector2d& t) {
  Eigen::VectorXd u = m.home_controls();
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(psi).toRotationMatrix();
  for (int k = 0; k < m.num_bases(); ++k) {
    u.segment<2>(3 * k) = R * u.segment<2>(3 * k) + t;
    u[3 * k + 2] += psi;
  }
  return u;
}

class EveryReferenceModel : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryReferenceModel, HomeIsAssembled) {
  const Model m = LoadReference(GetParam());
  ForwardProblem forward(m);
  EXPECT_LT(forward.Energy(), 1e-30);
  const ForwardResult r = forward.Solve(m.home_controls());
  EXPECT_TRUE(r.converged);
  EXPECT_TRUE(r.assembled);
  EXPECT_LT((forward.end_effector().position - m.end_effector.p_W_home).norm(), 1e-14);
}

TEST_P(EveryReferenceModel, RigidPlanarMotionOfAllBasesMovesTheEndEffectorRigidly) {
  const Model m = LoadReference(GetParam());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    const double psi = 0.6 * d(rng);
    const Eigen::Vector2d t{0.2 * d(rng), 0.2 * d(rng)};
    ForwardProblem forward(m, WithoutRigidPredictor());
    const ForwardResult r = forward.Assemble(RigidlyMovedControls(m, psi, t));
    ASSERT_TRUE(r.assembled) << r.residual_energy;
    const Eigen::Matrix3d Rz = RotationZ(psi);
    const Eigen::Vector3d expected = Rz * m.end_effector.p_W_home + Eigen::Vector3d(t.x(), t.y(), 0);
    EXPECT_LT((forward.end_effector().position - expected).norm(), 1e-10);
    EXPECT_LT((forward.end_effector().rotation - Rz).norm(), 1e-10);
    EXPECT_LT(r.residual_energy, 1e-24);
  }
}

TEST_P(EveryReferenceModel, WarmStartedPaperSizeStepsConvergeQuadratically) {
  // 1 cm steps of all bases: redundant rows (revolute 6 for 5, fixed 9 for
  // 6, planar 4 for 3) must neither stall nor slow the solve.
  const Model m = LoadReference(GetParam());
  ForwardProblem forward(m, WithoutRigidPredictor());
  for (int step = 1; step <= 10; ++step) {
    const ForwardResult r =
        forward.Solve(RigidlyMovedControls(m, 0.005 * step, Eigen::Vector2d(0.01 * step, 0)));
    EXPECT_TRUE(r.assembled);
    EXPECT_LT(r.residual_energy, 1e-24);
    EXPECT_LE(r.iterations, 6) << "step " << step;
  }
}

TEST_P(EveryReferenceModel, SameAssemblyWhateverTheBodiesHomeOrientation) {
  // The same mechanism with every chain body's home frame pitched by 90
  // degrees (gimbal lock for Euler angles), or turned at random: the bodies'
  // origins and the end-effector must assemble identically.
  const Model plain = LoadReference(GetParam());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-M_PI, M_PI);
  for (const std::string& kind : {"pitched", "random"}) {
    const std::string rotated = testing::WithBodyRpy(ReadReference(GetParam()), [&](const std::string&) {
      return kind == "pitched" ? Eigen::Vector3d(0.3, M_PI / 2, -0.7)
                               : Eigen::Vector3d{d(rng), d(rng) / 2, d(rng)};
    });
    ASSERT_NE(rotated.find("rpy"), std::string::npos);
    const Model turned = LoadModelFromString(rotated, GetParam() + "_" + kind + ".yaml");

    const Eigen::VectorXd u = RigidlyMovedControls(plain, 0.2, Eigen::Vector2d(0.03, -0.02));
    Eigen::VectorXd u_perturbed = u;
    if (!plain.end_effector.controlled[kRoll]) {
      // Over-actuated: only reachable controls; use the rigid motion.
    } else {
      for (int i = 0; i < u.size(); ++i) u_perturbed[i] += 0.004 * std::sin(3.0 * i);
    }
    ForwardProblem a(plain, WithoutRigidPredictor()), b(turned, WithoutRigidPredictor());
    const ForwardResult ra = a.Assemble(u_perturbed);
    const ForwardResult rb = b.Assemble(u_perturbed);
    ASSERT_TRUE(ra.assembled);
    ASSERT_TRUE(rb.assembled) << kind << ": " << rb.residual_energy;
    EXPECT_LT((a.end_effector().position - b.end_effector().position).norm(), 1e-10) << kind;
    EXPECT_LT((a.end_effector().rotation - b.end_effector().rotation).norm(), 1e-10) << kind;
    for (int i = 0; i < plain.num_bodies(); ++i) {
      EXPECT_LT((a.state().p_WB(i) - b.state().p_WB(i)).norm(), 1e-10) << kind << " body " << i;
      // Each body's motion from home is the same rotation.
      const Eigen::Matrix3d motion_a = a.state().R_WB(i) * plain.bodies[i].R_WB_home.transpose();
      const Eigen::Matrix3d motion_b = b.state().R_WB(i) * turned.bodies[i].R_WB_home.transpose();
      EXPECT_LT((motion_a - motion_b).norm(), 1e-10) << kind << " body " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(FiveReferenceModels, EveryReferenceModel, ::testing::ValuesIn(kReferenceModels));

TEST(ForwardProblem, OverActuatedModelReportsUnreachableControls) {
  // Moving one base of a rigid, over-actuated system by 1 cm cannot be
  // assembled: the solve converges to dE/ds = 0 with E > 0 and says so.
  for (const std::string name : {"4dof_reduced", "4dof_complete"}) {
    const Model m = LoadReference(name);
    ForwardProblem forward(m);
    Eigen::VectorXd u = m.home_controls();
    u[0] += 0.01;
    const ForwardResult r = forward.Assemble(u);
    EXPECT_TRUE(r.converged) << r.message;
    EXPECT_FALSE(r.assembled);
    EXPECT_GT(r.residual_energy, 1e-8);
    EXPECT_NEAR(r.residual_energy, forward.Energy(), 1e-20);
  }
}

TEST(ForwardProblem, ControlsOutOfReachAreNotForced) {
  // Bases pulled 30 cm apart: the legs cannot reach the end-effector.
  const Model m = LoadReference("6dof_symmetric");
  Eigen::VectorXd u = m.home_controls();
  for (int k = 0; k < m.num_bases(); ++k) u.segment<2>(3 * k) *= 1.5;
  ForwardProblem forward(m);
  const ForwardResult r = forward.Assemble(u);
  EXPECT_FALSE(r.assembled);
  EXPECT_GT(r.residual_energy, 1e-4);
}

TEST(ForwardProblem, HeadingsAreWalkedTheShortWay) {
  const Model m = LoadReference("6dof_symmetric");
  Eigen::VectorXd u = RigidlyMovedControls(m, 0.01, Eigen::Vector2d::Zero());
  u[2] += 2 * M_PI;  // the same heading, written differently
  ForwardProblem forward(m);
  const ForwardResult r = forward.Assemble(u);
  EXPECT_TRUE(r.assembled);
  EXPECT_EQ(r.substeps, 1);
}

TEST(ForwardProblem, RejectsBadControlsBeforeCeresSeesThem) {
  const Model m = LoadReference("4dof_reduced");
  ForwardProblem forward(m);
  EXPECT_THROW(forward.Solve(Eigen::VectorXd::Zero(4)), std::invalid_argument);
  Eigen::VectorXd u = m.home_controls();
  u[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(forward.Solve(u), std::invalid_argument);
  u[4] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(forward.Assemble(u), std::invalid_argument);
  // The problem is still usable afterwards.
  EXPECT_TRUE(forward.Solve(m.home_controls()).assembled);
}

TEST(ForwardProblem, EveryLinearSolverGivesTheSameAssembly) {
  const Model m = LoadReference("6dof_asymmetric");
  const Eigen::VectorXd u = RigidlyMovedControls(m, -0.1, Eigen::Vector2d(0.02, 0.05));
  Eigen::Vector3d reference;
  bool first = true;
  for (LinearSolverChoice choice : {LinearSolverChoice::kDenseQr, LinearSolverChoice::kDenseNormalCholesky,
                                    LinearSolverChoice::kSparseNormalCholesky}) {
    ForwardOptions options;
    options.linear_solver = choice;
    ForwardProblem forward(m, options);
    ASSERT_TRUE(forward.Assemble(u).assembled);
    if (first) reference = forward.end_effector().position;
    EXPECT_LT((forward.end_effector().position - reference).norm(), 1e-12);
    first = false;
  }
}

}  // namespace
}  // namespace ccma
