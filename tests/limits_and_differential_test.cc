// Control under inequalities and non-holonomic bases: joint limits are never
// left (every step, to 1e-9) and a target beyond them is never reported as
// reached; differential bases move along one circular arc per step (lateral
// displacement below 1e-9 m), which an omni model does not; check tells when
// differential bases leave the end-effector too few DOF.
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "ccma/joint_coordinates.h"
#include "analyses/mobility.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "ccma/rotation.h"
#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "problems/trajectory.h"
#include "tests/hinge_model.h"
#include "tests/tool_run.h"

namespace ccma {
namespace limits_and_differential_test {


std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The 4dof_reduced chain (posts on revolute joints) on differential bases.
Model DifferentialModel() {
  std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  size_t at = 0;
  int replaced = 0;
  while ((at = text.find("type: omni, actuation: reduced", at)) != std::string::npos) {
    text.replace(at, 30, "type: differential");
    ++replaced;
  }
  EXPECT_EQ(replaced, 3);
  return LoadModelFromString(text, "4dof_differential.yaml");
}

double Lateral(const Eigen::VectorXd& u0, const Eigen::VectorXd& u1, int base) {
  const int i = 3 * base;  // wheeled bases only: x, y, theta each
  const double mid = u0[i + 2] + 0.5 * WrapAngle(u1[i + 2] - u0[i + 2]);
  return -std::sin(mid) * (u1[i] - u0[i]) + std::cos(mid) * (u1[i + 1] - u0[i + 1]);
}

// Worst lateral displacement of any base over every step of a path.
double WorstLateral(const Model& model, const std::string& path, bool* converged) {
  ControlProblem control(model);
  Eigen::VectorXd previous = control.controls();
  double worst = 0;
  const TrajectoryResult result =
      FollowWaypoints(control, LoadWaypoints(std::string(CCMA_MODELS_DIR) + "/paths/" + path),
                      [&](const TrajectoryStep& step) {
                        for (int k = 0; k < model.num_bases(); ++k) {
                          worst = std::max(worst, std::abs(Lateral(previous, step.controls, k)));
                        }
                        previous = step.controls;
                      });
  *converged = result.converged;
  return worst;
}

TEST(JointLimits, ATargetBeyondALimitIsNeverReportedReached) {
  const Model model = LoadModelFromString(kHinge, "hinge.yaml");
  ControlProblem control(model);
  // z = 0.396 needs q = asin(0.48) = 0.50 > 0.3.
  const ControlResult result = control.MoveTo({Eigen::Vector3d(0, 0.2 * std::cos(0.5), 0.3 + 0.2 * std::sin(0.5)),
                                               Eigen::Vector3d::Zero()});
  EXPECT_FALSE(result.converged);
  EXPECT_NE(result.warning.find("joint 'hinge' at its upper limit 0.3 rad"), std::string::npos) << result.warning;
  const double q = JointCoordinate(model.joints[1], control.forward().state());
  EXPECT_LE(q, 0.3 + 1e-9);
  EXPECT_NEAR(q, 0.3, 1e-9);  // it went as far as the limit allows
  EXPECT_TRUE(LimitsViolated(model, control.forward().state()).empty());
  // Within the limits the same mechanism reaches a target exactly: q = asin(0.25 / 2) = 0.1253.
  ControlProblem again(model);
  const double q_target = std::asin(0.125);
  const ControlResult reached = again.MoveTo(
      {Eigen::Vector3d(0.01, 0.2 * std::cos(q_target), 0.3 + 0.2 * std::sin(q_target)), Eigen::Vector3d::Zero()});
  EXPECT_TRUE(reached.converged) << reached.warning;
  EXPECT_NEAR(JointCoordinate(model.joints[1], again.forward().state()), q_target, 1e-9);
  EXPECT_NEAR(again.controls()[3], q_target, 1e-9);  // the actuated joint's control is its q
}

// hybrid_ccma (reduced bases plus an actuated shoulder) with leg 0's passive
// base yaw limited to +-0.05 rad: a yaw target of 0.3 rad needs that joint
// beyond its limit. The stop must return an assembled configuration (the
// last reached path step's), not the failed step's torn LM iterate (which
// had E ~ 1e-3 m^2 and joints apart by millimetres).
TEST(JointLimits, AStopReturnsTheLastAssembledConfiguration) {
  std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/hybrid_ccma.yaml");
  const std::string joint = "  - {type: revolute, between: [base0, post0]";
  const size_t at = text.find(joint);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, joint.size(), "  - {name: yaw0, limits: [-0.05, 0.05], type: revolute, between: [base0, post0]");
  const Model model = LoadModelFromString(text, "hybrid_yaw_limited.yaml");
  ControlProblem control(model);
  ASSERT_TRUE(control.SetControls(model.home_controls()).assembled);
  PoseTarget target = control.CurrentPose();
  target.rpy.z() += 0.3;
  const ControlResult r = control.MoveTo(target);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.assembled);
  EXPECT_LT(r.residual_energy, 1e-20);
  EXPECT_LT(control.forward().Energy(), 1e-20);  // the poses returned close every joint
  EXPECT_NE(r.limited_by.find("yaw0"), std::string::npos) << r.limited_by;
  EXPECT_NE(r.warning.find("returned the last assembled configuration (path step "), std::string::npos) << r.warning;
  // The yaw stops at its limit: 0.25 rad of the 0.3 are missing, and the limit holds.
  EXPECT_NEAR(r.error, 0.25, 0.01);
  const Joint& yaw0 = model.joints[0];
  ASSERT_EQ(yaw0.name, "yaw0");
  EXPECT_LE(JointCoordinate(yaw0, control.forward().state()), 0.05 + 1e-9);
}

TEST(JointLimits, EveryTrajectoryRowKeepsTheLimits) {
  const Model model = LoadModelFromString(kHinge, "hinge.yaml");
  const std::string waypoints = ccma::testing::TestDir() + "/hinge_path_" + std::to_string(::getpid()) + ".csv";
  // Up past the upper limit, then down past the lower one.
  std::ofstream(waypoints) << "time,x,y,z,roll,pitch,yaw\n0,0,0.2,0.3,0,0,0\n1,0,0.17,0.4,0,0,0\n2,0,0.19,0.22,0,0,0\n";
  ControlProblem control(model);
  int rows = 0;
  double worst = 0;
  FollowWaypoints(control, LoadWaypoints(waypoints), [&](const TrajectoryStep& step) {
    const double q = JointCoordinate(model.joints[1], step.state);
    worst = std::max({worst, q - 0.3, -0.2 - q});
    ++rows;
  });
  EXPECT_GT(rows, 5);
  EXPECT_LE(worst, 1e-9);
}

TEST(DifferentialBases, BothPathsAreFollowedAlongArcs) {
  const Model model = DifferentialModel();
  for (const char* path : {"4dof_sequential.csv", "4dof_combined.csv"}) {
    bool converged = false;
    const double worst = WorstLateral(model, path, &converged);
    EXPECT_TRUE(converged) << path;
    EXPECT_LT(worst, 1e-9) << path;
  }
}

TEST(DifferentialBases, TheSameCheckFailsOnTheOmniModel) {
  const Model omni = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  bool converged = false;
  EXPECT_GT(WorstLateral(omni, "4dof_sequential.csv", &converged), 1e-4);
  EXPECT_TRUE(converged);
}

TEST(DifferentialBases, CheckSaysWhenWeldedPostsLeaveTooFewDof) {
  const Model free_headings = DifferentialModel();
  const MobilityReport r = AnalyzeMobility(free_headings, State::Home(free_headings), free_headings.home_controls());
  EXPECT_EQ(r.end_effector_dof, 4);
  EXPECT_EQ(r.end_effector_dof_nonholonomic, 4);  // the bases turn under their posts first
  std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/4dof_complete.yaml");
  size_t at = 0;
  while ((at = text.find("type: omni, actuation: complete", at)) != std::string::npos) {
    text.replace(at, 31, "type: differential");
  }
  const Model welded = LoadModelFromString(text, "4dof_complete_differential.yaml");
  const MobilityReport w = AnalyzeMobility(welded, State::Home(welded), welded.home_controls());
  EXPECT_EQ(w.end_effector_dof, 4);
  // Each base can only push its leg radially: the end-effector moves in z only.
  EXPECT_EQ(w.end_effector_dof_nonholonomic, 1);
}

}  // namespace
}  // namespace ccma

namespace ccma {
namespace limits_and_differential_test {

// Generated Stewart-Gough platforms: rigid with their legs fixed, 6-DOF
// platform, and every leg's coordinate equal to its control after a solve.
TEST(GeneratedStewartGough, RigidAndLegCoordinatesFollowTheirControls) {
  for (int legs : {6, 8, 12}) {
    StewartOptions options;
    options.agents = legs;
    const Model model = LoadModelFromString(GenerateStewartGoughModel(options), "generated.yaml");
    EXPECT_EQ(model.num_bases(), 0);
    EXPECT_EQ(model.num_controls(), legs);
    const MobilityReport r = AnalyzeMobility(model, State::Home(model), model.home_controls());
    EXPECT_TRUE(r.rigid_with_controls_fixed) << legs;
    EXPECT_EQ(r.end_effector_dof, 6) << legs;
    if (legs != 6) continue;  // more legs than DOF: a generic leg vector does not assemble
    ForwardProblem forward(model);
    Eigen::VectorXd u(6);
    u << 0.01, -0.02, 0.015, 0.0, -0.01, 0.02;
    const ForwardResult result = forward.Assemble(u);
    EXPECT_TRUE(result.assembled);
    for (const JointCoordinateReport& q : JointCoordinates(model, forward.state())) {
      const Joint& joint = model.joints[q.joint];
      if (joint.actuated) EXPECT_NEAR(q.q, u[joint.control], 1e-9) << joint.name;
    }
  }
}

}  // namespace
}  // namespace ccma
