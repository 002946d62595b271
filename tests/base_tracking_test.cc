// Driving the bases: omni-wheel kinematics, the PI tracker, the simulated
// set-up, and the closed-loop replay of the paper's 4-DOF experiments.
#include <cmath>
#include <chrono>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "execution/base_tracking.h"
#include "ccma/limits.h"
#include "formats/model_loader.h"
#include "ccma/omni_wheels.h"
#include "ccma/rotation.h"
#include "execution/replay.h"

namespace ccma {
namespace base_tracking_test {

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
      const Eigen::Vector3d twist{d(rng), d(rng), d(rng)};
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
  EXPECT_FALSE(r.torn) << r.max_residual_energy;
  EXPECT_TRUE(r.trustworthy());
  EXPECT_LT(r.max_residual_energy, 1e-9);  // noise-free bases lag a little: E ~ 1e-12
  for (const auto& s : r.samples) EXPECT_FALSE(s.torn) << s.time;
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

// ---- IsValid: every field in its documented range, messages name field and unit.

TEST(ReplayOptionsIsValid, TheDefaultsAndNoNoiseAreValid) {
  std::string why = "untouched";
  EXPECT_TRUE(TrackingGains().IsValid(&why));
  EXPECT_TRUE(SimulationNoise().IsValid(&why));
  EXPECT_TRUE(SimulationNoise::None().IsValid(&why));
  EXPECT_TRUE(ReplayOptions().IsValid(&why));
  EXPECT_EQ(why, "untouched");
  EXPECT_TRUE(ReplayOptions().IsValid(nullptr));
}

struct BadOption {
  std::string what;
  std::function<void(ReplayOptions*)> change;
  std::string field, unit;  // expected in the message
};
void PrintTo(const BadOption& b, std::ostream* os) { *os << b.what; }

class ReplayOptionsInvalid : public ::testing::TestWithParam<BadOption> {};

TEST_P(ReplayOptionsInvalid, IsRefusedNamingTheFieldAndUnit) {
  ReplayOptions options;
  GetParam().change(&options);
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_FALSE(options.IsValid(nullptr));
  EXPECT_NE(why.find(GetParam().field), std::string::npos) << why;
  EXPECT_NE(why.find(GetParam().unit), std::string::npos) << why;
  const auto waypoints = LoadWaypoints(std::string(CCMA_MODELS_DIR) + "/paths/4dof_combined.csv");
  const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  EXPECT_THROW(Replay(m, waypoints, options), std::invalid_argument);
}

const double kNaN = std::nan("");
const double kInf = HUGE_VAL;

INSTANTIATE_TEST_SUITE_P(
    Fields, ReplayOptionsInvalid,
    ::testing::Values(
        BadOption{"kp zero", [](ReplayOptions* o) { o->gains.kp_position = 0; }, "kp_position", "1/s"},
        BadOption{"kp nan", [](ReplayOptions* o) { o->gains.kp_heading = kNaN; }, "kp_heading", "1/s"},
        BadOption{"ki negative", [](ReplayOptions* o) { o->gains.ki_position = -1; }, "ki_position", "1/s^2"},
        BadOption{"ki infinite", [](ReplayOptions* o) { o->gains.ki_heading = kInf; }, "ki_heading", "1/s^2"},
        BadOption{"wheel speed zero", [](ReplayOptions* o) { o->gains.max_wheel_speed = 0; }, "max_wheel_speed",
                  "rad/s"},
        BadOption{"controller tiny", [](ReplayOptions* o) { o->gains.rate_hz = 1e-300; }, "rate_hz", "Hz"},
        BadOption{"controller fast", [](ReplayOptions* o) { o->gains.rate_hz = 2e4; }, "rate_hz", "Hz"},
        BadOption{"sigma negative", [](ReplayOptions* o) { o->noise.position_sigma = -1e-3; }, "position_sigma", "m"},
        BadOption{"sigma nan", [](ReplayOptions* o) { o->noise.heading_sigma = kNaN; }, "heading_sigma", "rad"},
        BadOption{"latency 20 s", [](ReplayOptions* o) { o->noise.mocap_latency = 20; }, "mocap_latency", " s"},
        BadOption{"radio latency negative", [](ReplayOptions* o) { o->noise.command_latency = -0.1; },
                  "command_latency", " s"},
        BadOption{"mocap zero", [](ReplayOptions* o) { o->noise.mocap_hz = 0; }, "mocap_hz", "Hz"},
        BadOption{"plant fast", [](ReplayOptions* o) { o->noise.plant_hz = 1e7; }, "plant_hz", "Hz"},
        BadOption{"slip one", [](ReplayOptions* o) { o->noise.slip = 1; }, "slip", "[0, 1)"},
        BadOption{"slip sigma negative", [](ReplayOptions* o) { o->noise.slip_sigma = -0.1; }, "slip_sigma",
                  "fraction"},
        BadOption{"output slow", [](ReplayOptions* o) { o->output_hz = 0.01; }, "output_hz", "Hz"},
        BadOption{"output infinite", [](ReplayOptions* o) { o->output_hz = kInf; }, "output_hz", "Hz"},
        BadOption{"settle negative", [](ReplayOptions* o) { o->settle_s = -1; }, "settle_s", " s"},
        BadOption{"torn threshold zero", [](ReplayOptions* o) { o->torn_residual_energy = 0; },
                  "torn_residual_energy", "m^2"}),
    [](const auto& info) {
      std::string n = info.param.what;
      for (char& c : n) if (!isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

std::vector<Waypoint> TwoWaypoints(double t0, double t1) {
  Waypoint a, b;
  a.position = b.position = Eigen::Vector3d(0, 0, 0.6);
  a.time = t0;
  b.time = t1;
  return {a, b};
}

TEST(Replay, RefusesRunsThatWouldNotEndQuickly) {
  const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  // 1e6 s at 100 Hz: 1e8 controller ticks.
  EXPECT_FALSE(IsValidReplay(TwoWaypoints(0, 1e6), ReplayOptions(), &why));
  EXPECT_NE(why.find("controller ticks"), std::string::npos) << why;
  EXPECT_THROW(Replay(m, TwoWaypoints(0, 1e6), ReplayOptions()), std::invalid_argument);
  // Times beyond kMaxTime, not finite, or decreasing; no waypoints.
  for (const auto& w : {TwoWaypoints(0, 1e308), TwoWaypoints(0, kInf), TwoWaypoints(0, kNaN), TwoWaypoints(5, 1),
                        std::vector<Waypoint>{}}) {
    EXPECT_FALSE(IsValidReplay(w, ReplayOptions(), &why));
    EXPECT_THROW(Replay(m, w, ReplayOptions()), std::invalid_argument) << why;
  }
  // Within the controller ticks but too many samples (2e4 s at 100 Hz = 2e6 samples).
  ReplayOptions fast_output;
  fast_output.output_hz = 100;
  fast_output.gains.rate_hz = 100;
  fast_output.noise.plant_hz = 100;
  EXPECT_FALSE(IsValidReplay(TwoWaypoints(0, 2e4), fast_output, &why));
  EXPECT_NE(why.find("samples"), std::string::npos) << why;
  // Plant steps: 2e4 s at 1 kHz.
  ReplayOptions slow_output;
  slow_output.output_hz = 1;
  EXPECT_FALSE(IsValidReplay(TwoWaypoints(0, 2e4), slow_output, &why));
  EXPECT_NE(why.find("plant steps"), std::string::npos) << why;
  // The limits themselves are accepted.
  ReplayOptions at_limit;  // kMaxTime s at 10 Hz: exactly kMaxReplayTicks
  at_limit.settle_s = 0;
  at_limit.output_hz = 0.1;
  at_limit.noise.plant_hz = 1;
  at_limit.gains.rate_hz = 10;
  EXPECT_TRUE(IsValidReplay(TwoWaypoints(0, kMaxTime), at_limit, &why)) << why;
  at_limit.settle_s = 0.1;
  EXPECT_FALSE(IsValidReplay(TwoWaypoints(0, kMaxTime), at_limit, &why));
  EXPECT_NE(why.find("controller ticks"), std::string::npos) << why;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(Replay, ATornChainIsReportedPerSampleAndOverall) {
  const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const auto waypoints = LoadWaypoints(std::string(CCMA_MODELS_DIR) + "/paths/4dof_sequential.csv");
  ReplayOptions options;
  options.noise.mocap_latency = options.noise.command_latency = 1.0;  // the PI loops oscillate
  const ReplayResult r = Replay(m, waypoints, options);
  EXPECT_TRUE(r.converged);  // the plan is fine; the bases are not
  EXPECT_TRUE(r.torn);
  EXPECT_FALSE(r.trustworthy());
  EXPECT_GT(r.max_residual_energy, 1e-2);
  int torn = 0;
  double first = kNaN;
  for (const auto& s : r.samples) {
    EXPECT_EQ(s.torn, s.residual_energy > options.torn_residual_energy) << s.time;
    if (s.torn && torn++ == 0) first = s.time;
  }
  EXPECT_EQ(r.torn_samples, torn);
  EXPECT_EQ(r.first_torn_time, first);
  EXPECT_EQ(r.torn_residual_energy, options.torn_residual_energy);
}

TEST(Replay, TheDefaultNoiseStrainsTheChainWithoutTearingIt) {
  const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_complete.yaml");
  const auto waypoints = LoadWaypoints(std::string(CCMA_MODELS_DIR) + "/paths/4dof_combined.csv");
  const ReplayResult r = Replay(m, waypoints, ReplayOptions());
  EXPECT_TRUE(r.trustworthy()) << r.max_residual_energy;
  EXPECT_GT(r.max_residual_energy, 1e-16);  // over-constrained: noisy bases never close it exactly
  EXPECT_LT(r.max_residual_energy, 0.1 * ReplayOptions().torn_residual_energy);
}

TEST(Replay, AnUnreachableWaypointGivesTheFailedStepsTime) {
  const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  auto waypoints = TwoWaypoints(0, 2);
  waypoints[1].position.z() = 1.5;  // far out of reach
  ReplayOptions options;
  options.noise = SimulationNoise::None();
  const ReplayResult r = Replay(m, waypoints, options);
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.trustworthy());
  EXPECT_FALSE(r.warning.empty());
  ASSERT_FALSE(std::isnan(r.failed_step_time));
  EXPECT_GT(r.failed_step_time, 0);
  EXPECT_LE(r.failed_step_time, 2);
  EXPECT_FALSE(r.samples.empty());
}

}  // namespace
}  // namespace ccma
