// Retiming (analyses/retime.h): the output, run through the same inverse
// dynamics as `ccma dynamics`, stays within every limit; a limit sets the
// speed on every segment; it is never slower than the best uniform scaling
// of the path; bang-bang bounds on a motor arm; a path beyond its limits at
// rest is reported, not retimed.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analyses/internal/motion_limits.h"
#include "analyses/retime.h"
#include "ccma/ccma.h"

namespace ccma {
namespace retime_test {

// The motor arm of dynamics_test: tau = (I + m l^2) theta'' + m g l cos theta,
// I + m l^2 = 0.43 kg m^2, m g l = 9.81 N m.
Model Arm(const std::string& limits) {
  const std::string text =
      "name: arm\nbodies:\n  - {name: arm, position: [0.2, 0, 0], mass: 2.5, com: [0.4, 0, 0],"
      " inertia: [0.02, 0.03, 0.025, 0.004, -0.003, 0.002]}\n"
      "joints:\n  - {name: hinge, type: revolute, actuated: true, between: [world, arm], point: [0, 0, 0], "
      "axis: [0, -1, 0]" + limits + "}\nend_effector: {body: arm, point: [0.5, 0, 0], controlled: [x, z]}\n";
  return LoadModelFromString(text, "arm.yaml");
}

// theta from -0.5 to 1.0 rad in `rows` rows one second apart: in equal
// steps, or (smooth) along 3 tau^2 - 2 tau^3, at rest at both ends.
ControlPath Sweep(int rows, double from = -0.5, double to = 1.0, bool smooth = false) {
  ControlPath path;
  path.source = "sweep.csv";
  for (int i = 0; i < rows; ++i) {
    path.times.push_back(i);
    const double tau = static_cast<double>(i) / (rows - 1);
    path.controls.push_back(Eigen::VectorXd::Constant(1, from + (to - from) * (smooth ? tau * tau * (3 - 2 * tau) : tau)));
    path.lines.push_back(i + 2);
    path.reached.push_back(std::nullopt);
  }
  return path;
}

ControlPath Timed(ControlPath path, const std::vector<double>& times) {
  path.times = times;
  return path;
}

// Every row of `report`'s timing within every limit of `model`, as
// ccma dynamics judges it (efforts, and rates against velocity_limit).
void ExpectWithinLimits(const Model& model, const ControlPath& path, const RetimeReport& report) {
  const DynamicsReport check = ComputeDynamics(model, Timed(path, report.times));
  EXPECT_TRUE(check.within_limits);
  for (const internal::MotionLimit& limit : internal::MotionLimits(model)) {
    for (const DynamicsRow& row : check.rows) {
      ASSERT_TRUE(row.assembled);
      EXPECT_LE(internal::Utilisation(limit, row.efforts, row.rates), 1 + 1e-9) << limit.name << " at " << row.time;
    }
  }
}

// A closed loop: the slider-crank of dynamics_test with the motor limited.
Model SliderCrank() {
  const std::string text =
      "name: slider_crank\nbodies:\n"
      "  - {name: crank, position: [0, 0, 0], mass: 1.5, com: [0.087758256189037279, 0, 0.047942553860420303]}\n"
      "  - {name: coupler, position: [0.087758256189037279, 0, 0.047942553860420303]}\n"
      "  - {name: slider, position: [0.38390266611321716, 0, 0], mass: 3.0}\n"
      "joints:\n"
      "  - {name: motor, type: revolute, actuated: true, q_home: 0.5, between: [world, crank], point: [0, 0, 0],"
      " axis: [0, -1, 0], effort_limits: [-4, 4]}\n"
      "  - {type: revolute, between: [crank, coupler], point: [0.087758256189037279, 0, 0.047942553860420303], axis: [0, 1, 0]}\n"
      "  - {type: revolute, between: [coupler, slider], point: [0.38390266611321716, 0, 0], axis: [0, 1, 0]}\n"
      "  - {type: prismatic, between: [world, slider], point: [0.38390266611321716, 0, 0], axis: [1, 0, 0]}\n"
      "end_effector: {body: slider, point: [0.38390266611321716, 0, 0], controlled: [x]}\n";
  return LoadModelFromString(text, "slider_crank.yaml");
}

TEST(Retime, MotorArmWithinItsEffortLimitsNearTheBangBangTime) {
  const Model model = Arm(", effort_limits: [-30, 30]");
  const ControlPath path = Sweep(61, -0.5, 1.0, true);
  const RetimeReport report = Retime(model, path);
  ASSERT_TRUE(report.feasible);
  EXPECT_EQ(report.method, "topp-ra");
  ExpectWithinLimits(model, path, report);
  EXPECT_LT(report.duration, report.uniform_duration);
  // Bang-bang over 1.5 rad: |theta''| <= (30 + 9.81) / 0.43 at best and
  // (30 - 9.81) / 0.43 at worst, so 2 sqrt(L / A) brackets the optimum.
  const double fastest = 2 * std::sqrt(1.5 / (39.81 / 0.43)), slowest = 2 * std::sqrt(1.5 / (20.19 / 0.43));
  EXPECT_GT(report.duration, fastest);
  EXPECT_LT(report.duration, 1.25 * slowest);
  // The motor's limit sets the speed on every segment.
  ASSERT_EQ(report.segment_limits.size(), 60u);
  for (size_t i = 0; i < report.segment_limits.size(); ++i) EXPECT_EQ(report.segment_limits[i], 0) << i;
  ASSERT_EQ(report.limiting.size(), 1u);
  EXPECT_EQ(report.limiting[0].name, "hinge");
  EXPECT_EQ(report.limiting[0].kind, "effort");
  EXPECT_NEAR(report.limiting[0].share, 1.0, 1e-12);
}

TEST(Retime, AVelocityLimitCapsTheRateAndSetsTheCruise) {
  const Model model = Arm(", effort_limits: [-30, 30], velocity_limit: 2");
  const ControlPath path = Sweep(61, -0.5, 1.0, true);
  const RetimeReport report = Retime(model, path);
  ASSERT_TRUE(report.feasible);
  ExpectWithinLimits(model, path, report);
  EXPECT_GT(report.duration, 1.5 / 2);  // never faster than cruising at V all the way
  EXPECT_LE(report.duration, report.uniform_duration);
  bool cruising = false;
  for (const RetimeLimitShare& l : report.limiting) cruising |= l.kind == "velocity" && l.share > 0.5;
  EXPECT_TRUE(cruising);
}

// The crank from 0.3 to 1.4 rad.
TEST(Retime, SliderCrankClosedLoopWithinLimitsAndFasterThanUniform) {
  const Model model = SliderCrank();
  const ControlPath path = Sweep(41, 0.3, 1.4, true);
  const RetimeReport report = Retime(model, path);
  ASSERT_TRUE(report.feasible);
  ExpectWithinLimits(model, path, report);
  EXPECT_LE(report.duration, report.uniform_duration);
  EXPECT_EQ(report.method, "topp-ra");
  for (size_t i = 0; i < report.segment_limits.size(); ++i) EXPECT_GE(report.segment_limits[i], 0) << i;
}

TEST(Retime, APathBeyondALimitAtRestIsReportedNotRetimed) {
  const Model model = Arm(", effort_limits: [-5, 5]");  // gravity alone needs 9.81 cos(theta)
  const RetimeReport report = Retime(model, Sweep(31));
  EXPECT_FALSE(report.feasible);
  ASSERT_TRUE(report.infeasible.has_value());
  EXPECT_EQ(report.infeasible->row, 0);
  EXPECT_EQ(report.infeasible->line, 2);
  EXPECT_EQ(report.infeasible->control, "hinge");
  EXPECT_EQ(report.infeasible->kind, "effort");
  EXPECT_NEAR(report.infeasible->effort, 2.5 * 9.81 * 0.4 * std::cos(0.5), 1e-9);
  EXPECT_TRUE(report.times.empty());
}

TEST(Retime, AModelWithoutLimitsOrAPathNoLimitBoundsIsBadInput) {
  EXPECT_THROW(Retime(Arm(""), Sweep(11)), std::invalid_argument);
  // Limits on a motor that does not move or feel the motion: none binds.
  EXPECT_THROW(Retime(Arm(", velocity_limit: 3"), Sweep(11, 0.2, 0.2 + 1e-300)), std::invalid_argument);
}

// At a constant rate no row feels a uniform speed-up (no acceleration at
// the rows): only the rest-to-rest timing is bounded, and it is TOPP-RA's.
TEST(Retime, APathAtAConstantRateHasNoUniformBound) {
  const Model model = Arm(", effort_limits: [-30, 30]");
  const ControlPath path = Sweep(61);
  const RetimeReport report = Retime(model, path);
  ASSERT_TRUE(report.feasible);
  EXPECT_EQ(report.method, "topp-ra");
  EXPECT_EQ(report.uniform_duration, 0.0);
  ExpectWithinLimits(model, path, report);
  EXPECT_GT(report.duration, 2 * std::sqrt(1.5 / (39.81 / 0.43)));
}

TEST(Retime, TwoRowsTakeTheUniformScalingWhereItIsBounded) {
  // Two rows of the arm: the spline is a line, no row feels a speed-up and
  // TOPP-RA needs three rows: nothing bounds the timing.
  EXPECT_THROW(Retime(Arm(", effort_limits: [-30, 30]"), Sweep(2)), std::invalid_argument);
  // The slider-crank's slider feels the crank's rate squared at every row.
  const Model model = SliderCrank();
  const ControlPath path = Sweep(2, 0.3, 1.4);
  const RetimeReport report = Retime(model, path);
  ASSERT_TRUE(report.feasible);
  EXPECT_EQ(report.method, "uniform");
  ExpectWithinLimits(model, path, report);
  EXPECT_DOUBLE_EQ(report.duration, report.uniform_duration);
}

}  // namespace retime_test
}  // namespace ccma
