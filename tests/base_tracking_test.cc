// Driving the bases: omni-wheel kinematics, the PI tracker, the simulated
// set-up, and the closed-loop replay of the paper's 4-DOF experiments.
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "ccma/base_tracking.h"
#include "ccma/model_loader.h"
#include "ccma/omni_wheels.h"
#include "ccma/rotation.h"
#include "problems/replay.h"

namespace ccma {
namespace {

TEST(OmniWheels, InverseThenForwardIsTheIdentity) {
  std::vector<Wheel> mecanum(4);  // 4 wheels all driving along x, rollers at +-45 degrees
  for (int i = 0; i < 4; ++i) {
    mecanum[i].angle = M_PI / 4 + i * M_PI / 2;
    mecanum[i].mounting = -mecanum[i].angle - M_PI / 2;
    mecanum[i].roller = (i % 2 ? 1 : -1) * M_PI / 4;
    mecanum[i].distance = 0.2;
    mecanum[i].radius = 0.05;
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-2, 2);
  for (const auto& layout : {DefaultWheels(), mecanum}) {
    const OmniWheelKinematics k(layout);
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::Vector3d twist(d(rng), d(rng), d(rng));
      EXPECT_LT((k.Twist(k.WheelSpeeds(twist)) - twist).norm(), 1e-12);
    }
  }
}

TEST(OmniWheels, ThreeWheelBaseWorkedOutByHand) {
  // Wheels at 0, 120, 240 degrees, 0.1 m out, radius 0.03 m, driving
  // tangentially: wheel i turns at (e_i . v_i) / r with e_i the tangent.
  const OmniWheelKinematics k(DefaultWheels());
  const double s = std::sqrt(3.0) / 2 / 0.03, h = 0.5 / 0.03;
  EXPECT_LT((k.WheelSpeeds({1, 0, 0}) - Eigen::Vector3d(0, -s, s)).norm(), 1e-12);          // pure x
  EXPECT_LT((k.WheelSpeeds({0, 1, 0}) - Eigen::Vector3d(1 / 0.03, -h, -h)).norm(), 1e-12);  // pure y
  EXPECT_LT((k.WheelSpeeds({0, 0, 1}) - Eigen::Vector3d::Constant(0.1 / 0.03)).norm(), 1e-12);  // rotation
}

TEST(OmniWheels, RejectsLayoutsThatCannotDrive) {
  std::vector<Wheel> two = DefaultWheels();
  two.pop_back();
  EXPECT_THROW(OmniWheelKinematics{two}, std::invalid_argument);
  std::vector<Wheel> flat = DefaultWheels();
  flat[1].radius = 0;
  EXPECT_THROW(OmniWheelKinematics{flat}, std::invalid_argument);
  std::vector<Wheel> aligned = DefaultWheels();  // all driving along x: no y motion
  for (auto& w : aligned) w.mounting = -w.angle - M_PI / 2;
  EXPECT_THROW(OmniWheelKinematics{aligned}, std::invalid_argument);
}

TEST(ModelWheels, TheWheelsBlockIsReadAndValidated) {
  const std::string base = R"(name: w
bodies: [{name: ee, position: [0, 0, 0.3]}]
mobile_bases:
  - name: b
    actuation: complete
    pose: [0, 0, 0]
    wheels:
      - {angle: 0.7854, distance: 0.2, radius: 0.05, roller: -0.7854}
      - {angle: 2.3562, distance: 0.2, radius: 0.05, roller: 0.7854}
      - {angle: 3.9270, distance: 0.2, radius: 0.05, roller: -0.7854}
      - {angle: 5.4978, distance: 0.2, radius: RADIUS, roller: 0.7854}
joints: [{type: fixed, between: [b, ee], point: [0, 0, 0.3]}]
end_effector: {body: ee, point: [0, 0, 0.3], controlled: [x, y, yaw]}
)";
  auto with_radius = [&](const std::string& r) {
    std::string text = base;
    text.replace(text.find("RADIUS"), 6, r);
    return text;
  };
  const Model m = LoadModelFromString(with_radius("0.05"), "w.yaml");
  ASSERT_EQ(m.mobile_bases[0].wheels.size(), 4u);
  EXPECT_DOUBLE_EQ(m.mobile_bases[0].wheels[1].roller, 0.7854);
  try {
    LoadModelFromString(with_radius("-0.05"), "w.yaml");
    FAIL() << "accepted a negative radius";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("w.yaml:8: mobile_bases[0].wheels"), std::string::npos) << e.what();
  }
  // Without the block: three omni wheels at 120 degrees.
  const Model plain = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  EXPECT_EQ(plain.mobile_bases[0].wheels.size(), 3u);
}

// Runs one base in closed loop without noise towards `set` for `seconds`.
struct LoopResult {
  Eigen::Vector3d error;
  double peak_wheel_speed;
  double overshoot;  // largest excursion past the set point along x [m]
};
LoopResult RunStep(const Eigen::Vector3d& set, double seconds, const TrackingGains& gains) {
  const OmniWheelKinematics k(DefaultWheels());
  BaseTracker tracker(k, gains);
  SimulatedBases bases({k}, {Eigen::Vector3d::Zero()}, SimulationNoise::None());
  LoopResult out{Eigen::Vector3d::Zero(), 0, 0};
  for (int tick = 0; tick < seconds * gains.rate_hz; ++tick) {
    const Eigen::VectorXd wheels = tracker.Update(set, Eigen::Vector3d::Zero(), bases.MeasuredPose(0));
    out.peak_wheel_speed = std::max(out.peak_wheel_speed, wheels.cwiseAbs().maxCoeff());
    bases.CommandWheels(0, wheels);
    bases.Advance(1.0 / gains.rate_hz);
    out.overshoot = std::max(out.overshoot, bases.TruePose(0).x() - set.x());
  }
  out.error = bases.TruePose(0) - set;
  return out;
}

TEST(BaseTracker, SettlesAStepWithoutNoise) {
  const LoopResult r = RunStep({0.05, -0.03, 0.1}, 5.0, TrackingGains());
  EXPECT_LT(r.error.head<2>().norm(), 1e-4);  // 0.1 mm
  EXPECT_LT(std::abs(r.error.z()), 1e-4);
}

TEST(BaseTracker, SaturationHoldsAndTheIntegratorDoesNotWindUp) {
  TrackingGains gains;
  gains.max_wheel_speed = 10.0;  // 0.3 m/s at the rim
  const LoopResult r = RunStep({2.0, 0.0, 0.0}, 20.0, gains);
  EXPECT_LE(r.peak_wheel_speed, gains.max_wheel_speed + 1e-12);
  EXPECT_LT(r.error.head<2>().norm(), 1e-4);
  // The saturated approach takes ~6.7 s; integrating the error through it
  // would store ~7 m s, i.e. ki * 7 = 28 m/s of demand, and overshoot by
  // metres. With anti-windup the overshoot stays below 1 % of the step.
  EXPECT_LT(r.overshoot, 0.02);
}

class ZeroNoiseReplay : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(ZeroNoiseReplay, TracksTheEndEffectorWithinAMillimetre) {
  const auto& [model_name, path] = GetParam();
  const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + model_name + ".yaml");
  const auto waypoints = LoadWaypoints(std::string(CCMA_MODELS_DIR) + "/paths/" + path + ".csv");
  ReplayOptions options;
  options.noise = SimulationNoise::None();
  const ReplayResult r = Replay(m, waypoints, options);
  EXPECT_TRUE(r.converged) << r.warning;
  EXPECT_GT(r.samples.size(), 1000u);
  for (int c = 0; c < 3; ++c) EXPECT_LT(r.rmse[c], 1e-3) << "component " << c;
  for (int c = 3; c < 6; ++c) EXPECT_LT(r.rmse[c], 1e-3) << "component " << c;
  // The commanded path really moves (the RMSE is not trivially small).
  double travel = 0;
  for (const auto& s : r.samples) travel = std::max(travel, std::abs(s.commanded[0]));
  EXPECT_GT(travel, 0.05);
}

INSTANTIATE_TEST_SUITE_P(PaperExperiments, ZeroNoiseReplay,
                         ::testing::Combine(::testing::Values("4dof_reduced", "4dof_complete"),
                                            ::testing::Values("4dof_sequential", "4dof_combined")));

TEST(Replay, TheSameSeedReproducesTheSameNumbers) {
  const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const auto waypoints = LoadWaypoints(std::string(CCMA_MODELS_DIR) + "/paths/4dof_combined.csv");
  ReplayOptions options;  // the default, documented noise
  const ReplayResult a = Replay(m, waypoints, options);
  const ReplayResult b = Replay(m, waypoints, options);
  options.noise.seed = 2;
  const ReplayResult c = Replay(m, waypoints, options);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(a.rmse[i], b.rmse[i]);
  EXPECT_NE(a.rmse[0], c.rmse[0]);
  EXPECT_GT(a.rmse[0], 1e-5);  // the noise does act
}

}  // namespace
}  // namespace ccma
