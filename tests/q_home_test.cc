// `q_home` (model_format.md, "Home value of a joint coordinate"): every
// reported q is q_home plus the motion since home, limits and controls are in
// that coordinate, a revolute value is wrapped into (-pi, pi].
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "ccma/joint_coordinates.h"
#include "formats/model_loader.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"

namespace ccma {
namespace q_home_test {

// A door on an actuated hinge about z at the origin; the end-effector 1 m
// out along x. Its encoder reads Q0 at home.
std::string Door(double q_home, const std::string& limits) {
  return "name: door\nbodies:\n  - {name: leaf, position: [0.5, 0, 1]}\njoints:\n"
         "  - {name: hinge, type: revolute, actuated: true, q_home: " +
         std::to_string(q_home) + limits +
         ", between: [world, leaf], point: [0, 0, 1], axis: [0, 0, 1]}\n"
         "end_effector: {body: leaf, point: [1, 0, 1], controlled: [x, y]}\n";
}

TEST(QHome, ReportedCoordinateAndControlIncludeIt) {
  const Model model = LoadModelFromString(Door(0.3, ", limits: [0, 1.5]"), "door.yaml");
  EXPECT_DOUBLE_EQ(model.home_controls()[0], 0.3);
  ForwardProblem problem(model);
  ASSERT_TRUE(problem.Solve(model.home_controls()).assembled);
  EXPECT_NEAR(JointCoordinates(model, problem.state())[0].q, 0.3, 1e-12);
  EXPECT_NEAR(problem.end_effector().position.x(), 1.0, 1e-9);  // home: u = q_home
  Eigen::VectorXd u(1);
  u << 0.8;  // 0.5 rad from home
  ASSERT_TRUE(problem.Assemble(u).assembled);
  EXPECT_NEAR(problem.end_effector().position.x(), std::cos(0.5), 1e-9);
  EXPECT_NEAR(problem.end_effector().position.y(), std::sin(0.5), 1e-9);
  EXPECT_NEAR(JointCoordinates(model, problem.state())[0].q, 0.8, 1e-9);
  EXPECT_TRUE(JointCoordinates(model, problem.state())[0].within_limits);
}

TEST(QHome, RevoluteValueWrapsButLimitsStayOneInterval) {
  // Limits [2.5, 3.5] straddle pi: q = 3.3 is reported as 3.3 - 2 pi, inside.
  const Model model = LoadModelFromString(Door(3.0, ", limits: [2.5, 3.5]"), "door.yaml");
  ForwardProblem problem(model);
  Eigen::VectorXd u(1);
  u << 3.3;
  ASSERT_TRUE(problem.Assemble(u).assembled);
  const JointCoordinateReport r = JointCoordinates(model, problem.state())[0];
  EXPECT_NEAR(r.q, 3.3 - 2 * M_PI, 1e-9);
  EXPECT_TRUE(r.within_limits);
  EXPECT_TRUE(LimitsViolated(model, problem.state()).empty());
  u << 3.7;  // beyond the upper limit
  ASSERT_TRUE(problem.Assemble(u).assembled);
  EXPECT_FALSE(JointCoordinates(model, problem.state())[0].within_limits);
}

TEST(QHome, ControlKeepsTheLimitInItsCoordinate) {
  const Model model = LoadModelFromString(Door(0.3, ", limits: [0, 0.6]"), "door.yaml");
  ControlProblem control(model);
  PoseTarget target;  // 0.5 rad from home needs q = 0.8 > 0.6
  target.position << std::cos(0.5), std::sin(0.5), 1;
  const ControlResult result = control.MoveTo(target);
  EXPECT_FALSE(result.converged);
  EXPECT_NE(result.limited_by.find("hinge"), std::string::npos);
  EXPECT_NEAR(control.forward().controls()[0], 0.6, 1e-6);
}

TEST(QHome, PrismaticDisplacementStartsAtIt) {
  const Model model = LoadModelFromString(
      "name: slider\nbodies:\n  - {name: cart, position: [0, 0, 0]}\njoints:\n"
      "  - {name: rail, type: prismatic, actuated: true, q_home: 0.1, between: [world, cart], point: [0, 0, 0], "
      "axis: [1, 0, 0]}\nend_effector: {body: cart, point: [0, 0, 0], controlled: [x]}\n",
      "slider.yaml");
  ForwardProblem problem(model);
  Eigen::VectorXd u(1);
  u << 0.15;
  ASSERT_TRUE(problem.Assemble(u).assembled);
  EXPECT_NEAR(problem.end_effector().position.x(), 0.05, 1e-9);
  EXPECT_NEAR(JointCoordinates(model, problem.state())[0].q, 0.15, 1e-9);
}

TEST(QHome, BadValuesAreRejectedWithFileLineAndKey) {
  try {
    LoadModelFromString(Door(0.3, ", limits: [0.5, 1.5]"), "door.yaml");
    FAIL() << "home outside its limits was accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("door.yaml:5: joints[0].limits: must satisfy lo <= q_home <= hi"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(LoadModelFromString(Door(2e4, ""), "door.yaml"), ModelError);
  const std::string spherical =
      "name: ball\nbodies:\n  - {name: b, position: [0, 0, 0]}\nmobile_bases:\n  - {name: m, pose: [0, 0, 0]}\n"
      "joints:\n  - {type: spherical, q_home: 0.1, between: [m, b], point: [0, 0, 0]}\n"
      "end_effector: {body: b, point: [0, 0, 0], controlled: [x]}\n";
  EXPECT_THROW(LoadModelFromString(spherical, "ball.yaml"), ModelError);
}

}  // namespace
}  // namespace ccma
