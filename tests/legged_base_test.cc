// Legged bases (docs/model_format.md, "Legged agents"): closed forms of a
// body pose driven by six controls, the loader's messages, body limits held
// by simulate and control, and the tool's columns.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "analyses/statics.h"
#include "ccma/rotation.h"
#include "cost_functions/legged_base_motor_cost.h"
#include "execution/gait.h"
#include "formats/model_loader.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "model_text.h"
#include "tool_run.h"

namespace ccma {
namespace legged_base_test {

// One quadruped at (0.2, -0.1) heading 0.3, body 0.45 m high, carrying a
// mast welded to its body; the end-effector at the mast's tip.
const char* kMastModel = R"(name: mast_on_a_dog
bodies:
  - {name: mast, position: [0.25, -0.05, 0.8]}
mobile_bases:
  - {name: dog, type: legged, pose: [0.2, -0.1, 0.3], body_height: 0.45}
joints:
  - {type: fixed, between: [dog, mast], point: [0.2, -0.1, 0.55]}
end_effector: {body: mast, point: [0.4, 0.05, 1.1], controlled: [x, y, z, roll, pitch, yaw]}
)";

Eigen::Matrix3d BodyRotation(const Eigen::VectorXd& u) {
  return RotationZ(u[2]) * Eigen::AngleAxisd(u[5], Eigen::Vector3d::UnitY()).toRotationMatrix() *
         Eigen::AngleAxisd(u[4], Eigen::Vector3d::UnitX()).toRotationMatrix();
}

TEST(LeggedBase, AMastTipIsWhereTheBodyPoseSays) {
  const Model model = LoadModelFromString(kMastModel, "mast.yaml");
  ASSERT_EQ(model.num_controls(), 6);
  EXPECT_EQ(model.effective_control_indices().size(), 6u);
  const Eigen::Vector3d p_home(0.2, -0.1, 0.45), tip_home(0.4, 0.05, 1.1);
  const Eigen::Matrix3d R_home = RotationZ(0.3);
  const Eigen::Vector3d tip_B = R_home.transpose() * (tip_home - p_home);
  ForwardProblem forward(model);
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd u(6);
    u << 0.2 + 0.3 * unit(rng), -0.1 + 0.3 * unit(rng), 0.3 + 2.0 * unit(rng), 0.45 + 0.1 * unit(rng),
        0.4 * unit(rng), 0.4 * unit(rng);
    ASSERT_TRUE(forward.Assemble(u).converged) << trial;
    const Eigen::Matrix3d R = BodyRotation(u);
    const Eigen::Vector3d expected = Eigen::Vector3d(u[0], u[1], u[3]) + R * tip_B;
    EXPECT_LT((forward.end_effector().position - expected).norm(), 1e-12) << trial;
    // R_EE = R_body(now) R_body(home)^T (the end-effector body is welded).
    EXPECT_LT((forward.end_effector().rotation - R * R_home.transpose()).norm(), 1e-12) << trial;
  }
}

TEST(LeggedBase, StaticsReportsTheWrenchTheBodyExertsOnTheChain) {
  // A 2 kg mast: the body holds its weight, force (0, 0, m g), with the
  // moment (c - p_body) x (0, 0, m g) about the body origin, tilted or not.
  std::string text = kMastModel;
  const std::string mast = "position: [0.25, -0.05, 0.8]}";
  text.replace(text.find(mast), mast.size(), "position: [0.25, -0.05, 0.8], mass: 2.0, com: [0.4, 0.05, 1.0]}");
  const Model model = LoadModelFromString(text, "mast.yaml");
  ForwardProblem forward(model);
  Eigen::VectorXd u(6);
  u << 0.3, 0.1, -0.7, 0.5, 0.2, -0.15;
  ASSERT_TRUE(forward.Assemble(u).converged);
  const StaticsReport report = ComputeStatics(model, forward.state(), u, ExternalWrench{});
  const Eigen::Vector3d p_home(0.2, -0.1, 0.45), c_home(0.4, 0.05, 1.0);
  const Eigen::Vector3d c_W = Eigen::Vector3d(u[0], u[1], u[3]) + BodyRotation(u) * RotationZ(0.3).transpose() * (c_home - p_home);
  const Eigen::Vector3d force(0, 0, 2.0 * 9.81);
  const Eigen::Vector3d moment = (c_W - Eigen::Vector3d(u[0], u[1], u[3])).cross(force);
  ASSERT_EQ(report.actuators.size(), 6u);
  const char* kinds[6] = {"base_force_x", "base_force_y", "base_force_z", "base_moment_x", "base_moment_y", "base_moment_z"};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(report.actuators[static_cast<size_t>(i)].kind, kinds[i]);
    const double expected = i < 3 ? force[i] : moment[i - 3];
    EXPECT_NEAR(report.actuators[static_cast<size_t>(i)].effort, expected, 1e-10) << kinds[i];
  }
}

// Controls of 6dof_three_legged with every body raised by dh.
Eigen::VectorXd Raised(const Model& model, double dh) {
  Eigen::VectorXd u = model.home_controls();
  for (int k = 0; k < model.num_bases(); ++k) u[model.base_control(k) + 3] += dh;
  return u;
}

TEST(LeggedBase, APlatformOnThreeRisesExactlyByTheirCommonHeightChange) {
  const Model model = LoadModel(testing::ModelPath("6dof_three_legged"));
  ASSERT_EQ(model.num_controls(), 18);
  ForwardProblem forward(model);
  const Eigen::Vector3d home = forward.end_effector().position;
  for (const double dh : {-0.12, -0.05, 0.03, 0.1}) {
    ASSERT_TRUE(forward.Assemble(Raised(model, dh)).converged) << dh;
    EXPECT_LT((forward.end_effector().position - home - Eigen::Vector3d(0, 0, dh)).norm(), 1e-12) << dh;
    EXPECT_LT((forward.end_effector().rotation - Eigen::Matrix3d::Identity()).norm(), 1e-12) << dh;
  }
}

// Three quadrupeds, each holding a ball on a post 0.1 m above its body; the
// balls sit in sleeves that slide along radial rails of a platform. Every
// ball lies on its rail, in the platform's plane: the platform tilts to the
// plane through the three balls, whatever the heights.
std::string RailsModel() {
  std::string bodies = "bodies:\n  - {name: plate, position: [0, 0, 0.55]}\n";
  std::string bases = "mobile_bases:\n", joints = "joints:\n";
  for (int i = 0; i < 3; ++i) {
    const double a = 2 * M_PI * i / 3 + M_PI / 2, c = 0.6 * std::cos(a), s = 0.6 * std::sin(a);
    const std::string n = std::to_string(i), p = "[" + std::to_string(c) + ", " + std::to_string(s) + ", 0.55]";
    bodies += "  - {name: sleeve" + n + ", position: " + p + "}\n";
    bases += "  - {name: dog" + n + ", type: legged, pose: [" + std::to_string(c) + ", " + std::to_string(s) +
             ", 0], body_height: 0.45}\n";
    joints += "  - {type: prismatic, between: [plate, sleeve" + n + "], point: " + p + ", axis: [" +
              std::to_string(c) + ", " + std::to_string(s) + ", 0]}\n";
    joints += "  - {type: spherical, between: [sleeve" + n + ", dog" + n + "], point: " + p + "}\n";
  }
  return "name: rails\n" + bodies + bases + joints +
         "end_effector: {body: plate, point: [0, 0, 0.55], controlled: [x, y, z, roll, pitch, yaw]}\n";
}

TEST(LeggedBase, APlatformTiltsToThePlaneThroughItsCarriersBalls) {
  const Model model = LoadModelFromString(RailsModel(), "rails.yaml");
  ForwardProblem forward(model);
  Eigen::VectorXd u = model.home_controls();
  const double heights[3] = {0.40, 0.47, 0.52};
  Eigen::Vector3d ball[3];
  for (int k = 0; k < 3; ++k) {
    const int i = model.base_control(k);
    u[i + 3] = heights[k];
    ball[k] = Eigen::Vector3d(u[i], u[i + 1], heights[k] + 0.1);
  }
  ASSERT_TRUE(forward.Assemble(u).converged);
  const Eigen::Vector3d normal = (ball[1] - ball[0]).cross(ball[2] - ball[0]).normalized();
  const Eigen::Vector3d z_plate = forward.end_effector().rotation.col(2);
  EXPECT_LT((z_plate - normal).norm(), 1e-12) << z_plate.transpose() << " vs " << normal.transpose();
  EXPECT_GT(std::acos(normal.z()), 0.05);  // a real tilt, not the home plane
}

TEST(LeggedBase, ControlHoldsTheBodyLimitsAndNamesThem) {
  const Model model = LoadModel(testing::ModelPath("6dof_three_legged"));
  ControlProblem control(model);
  PoseTarget target;
  target.position = Eigen::Vector3d(0, 0, 1.6);  // beyond every body's reach
  const ControlResult r = control.MoveTo(target);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.warning.find("base 'dog0' height at its upper limit 0.55 m"), std::string::npos) << r.warning;
  for (int k = 0; k < model.num_bases(); ++k) {
    EXPECT_LE(control.controls()[model.base_control(k) + 3], 0.55 + 1e-9);
  }
}

TEST(LeggedBase, ControlReachesTargetsOfAllSixComponents) {
  const Model model = LoadModel(testing::ModelPath("6dof_three_legged"));
  ControlProblem control(model);
  PoseTarget target;
  target.position = Eigen::Vector3d(0.05, 0.03, 1.0);
  target.rpy = Eigen::Vector3d(0.05, -0.04, 0.1);
  const ControlResult r = control.MoveTo(target);
  EXPECT_TRUE(r.converged) << r.warning;
  EXPECT_LT((control.forward().end_effector().position - target.position).norm(), 1e-9);
  EXPECT_LT((control.forward().end_effector().rpy - target.rpy).norm(), 1e-9);
}

TEST(LeggedBase, MalformedKeysAreRejectedWithTheirPath) {
  const std::string base = "{name: dog, type: legged, pose: [0.2, -0.1, 0.3], body_height: 0.45}";
  auto with = [&](const std::string& replacement) {
    std::string text = kMastModel;
    text.replace(text.find(base), base.size(), replacement);
    return testing::LoadErrorOf(text);
  };
  EXPECT_NE(with("{name: dog, type: legged, pose: [0.2, -0.1, 0.3]}").find("body_height"), std::string::npos);
  EXPECT_NE(with("{name: dog, type: legged, pose: [0.2, -0.1, 0.3], body_height: -0.1}").find("must be > 0"),
            std::string::npos);
  EXPECT_NE(with("{name: dog, type: legged, pose: [0.2, -0.1, 0.3], body_height: 0.45, body_limits: {height: "
                 "[0.5, 0.6]}}")
                .find("mobile_bases[0].body_limits.height: must contain the home value 0.45"),
            std::string::npos);
  EXPECT_NE(with("{name: dog, type: legged, pose: [0.2, -0.1, 0.3], body_height: 0.45, body_limits: {roll: [0.1, "
                 "0.2]}}")
                .find("body_limits.roll"),
            std::string::npos);
  EXPECT_NE(with("{name: dog, type: legged, pose: [0.2, -0.1, 0.3], body_height: 0.45, actuation: reduced}")
                .find("mobile_bases[0].actuation: is not a key of a legged base"),
            std::string::npos);
  EXPECT_NE(with("{name: dog, type: legged, pose: [0.2, -0.1, 0.3], body_height: 0.45, footprint: [0.7]}")
                .find("footprint"),
            std::string::npos);
  EXPECT_NE(with("{name: dog, type: omni, actuation: complete, pose: [0.2, -0.1, 0.3], body_height: 0.45}")
                .find("only legged bases have body_height"),
            std::string::npos);
  EXPECT_NE(with("{name: dog, type: walking, pose: [0.2, -0.1, 0.3]}").find("known: omni, differential, legged"),
            std::string::npos);
}

TEST(LeggedBase, SimulateRefusesControlsOutsideTheBodyLimits) {
  const std::string model = testing::ModelPath("6dof_three_legged");
  const testing::ToolRun run = testing::RunTool(
      {"simulate", "--model=" + model,
       "--controls=0,0.9,-1.5707963,0.6,0,0,-0.779422863,-0.45,0.523598776,0.45,0,0,0.779422863,-0.45,2.617993878,0.45,0,0"});
  EXPECT_EQ(run.status, 2);
  EXPECT_TRUE(run.out.empty());
  EXPECT_NE(run.err.find("base 'dog0' height outside its limits [0.3, 0.55]"), std::string::npos) << run.err;
}

TEST(LeggedBase, AFootprintIsABoxAlongTheHeading) {
  // dog0 stands at (0, 0.9) facing -y: its 0.7 x 0.3 m box spans x in
  // [-0.15, 0.15]; a pillar of radius 0.1 at (0.5, 0.9) is 0.25 m away.
  const std::string obstacles = testing::ScratchPath("legged", "pillar.yaml");
  std::ofstream(obstacles) << "obstacles:\n  - {name: pillar, cylinder: {center: [0.5, 0.9], radius: 0.1, height: 2.0}}\n";
  const testing::ToolRun run =
      testing::RunTool({"simulate", "--model=" + testing::ModelPath("6dof_three_legged"), "--obstacles=" + obstacles});
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json out = nlohmann::json::parse(run.out);
  EXPECT_NEAR(double(out["clearance"]["min"]), 0.25, 1e-12);
  EXPECT_EQ(out["clearance"]["pair"], nlohmann::json({"dog0", "pillar"}));
}

TEST(LeggedBase, TrajectoryColumnsCarrySixControlsPerLeggedBase) {
  const std::string path = testing::ScratchPath("legged", "up.csv");
  std::ofstream(path) << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.95,0,0,0\n1,0,0,0.98,0,0,0.05\n";
  const std::string out = testing::ScratchPath("legged", "out.csv");
  const testing::ToolRun run =
      testing::RunTool({"trajectory", "--model=" + testing::ModelPath("6dof_three_legged"), "--waypoints=" + path, "--out=" + out});
  ASSERT_EQ(run.status, 0) << run.err;
  const std::string csv = testing::Slurp(out);
  EXPECT_NE(csv.find("u0_x_m,u0_y_m,u0_theta_rad,u0_height_m,u0_roll_rad,u0_pitch_rad,u1_x_m"), std::string::npos)
      << csv.substr(0, 400);
}

// Replay of a short walk: the gait's share of the error is reported, and it
// vanishes with the gait's amplitudes.
nlohmann::json ReplayWalk(const std::vector<std::string>& extra) {
  const std::string path = testing::ScratchPath("legged", "walk.csv");
  std::ofstream(path) << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.95,0,0,0\n2,0.1,0,0.95,0,0,0\n";
  std::vector<std::string> args = {"replay", "--model=" + testing::ModelPath("6dof_three_legged"),
                                   "--waypoints=" + path, "--out=" + testing::ScratchPath("legged", "replay"),
                                   "--noise=none"};
  args.insert(args.end(), extra.begin(), extra.end());
  const testing::ToolRun run = testing::RunTool(args, 300);
  EXPECT_EQ(run.status, 0) << run.err;
  return nlohmann::json::parse(run.out);
}

TEST(LeggedBase, ReplaySeparatesTheGaitsErrorFromTracking) {
  const nlohmann::json walk = ReplayWalk({"--gait_bob_m=0.02"});
  ASSERT_TRUE(walk.contains("gait")) << walk.dump();
  EXPECT_EQ(walk["gait"]["bob_m"], 0.02);
  // Bobbing 20 mm moves the platform up and down by about as much (RMS of a
  // sine: 0.02 / sqrt 2 = 14 mm, while walking).
  const double z_gait = walk["gait"]["rmse_from_gait"]["z_mm"];
  EXPECT_GT(z_gait, 3.0);
  EXPECT_LT(z_gait, 20.0);
  // bases.csv carries every control of a legged base, and ccma view animates it.
  const std::string dir = testing::ScratchPath("legged", "replay");
  EXPECT_NE(testing::Slurp(dir + "/bases.csv").find("set0_height_m,set0_roll_rad,set0_pitch_rad,base0_x_m"),
            std::string::npos);
  const testing::ToolRun view = testing::RunTool({"view", "--model=" + testing::ModelPath("6dof_three_legged"),
                                                  "--replay=" + dir, "--out=" + testing::ScratchPath("legged", "r.html")});
  EXPECT_EQ(view.status, 0) << view.err;
  const nlohmann::json still = ReplayWalk({"--gait_bob_m=0", "--gait_sway_rad=0"});
  EXPECT_LT(double(still["gait"]["rmse_from_gait"]["z_mm"]), 1e-9);
  EXPECT_NEAR(double(still["rmse"]["z_mm"]), double(still["gait"]["rmse_from_tracking"]["z_mm"]), 1e-9);
}

// The gait is evaluated at every controller tick (issue 49 item 4): sampled
// only at the 20 Hz output, a 10 Hz gait was seen at the same phase every
// time (sin = 0: no bob, 0.28 mm against 5.3 mm at 9.7 Hz), and 100 Hz
// equalled 1e-300 Hz. The three bodies bob in phase, lifting the platform by
// 10 mm sin(2 pi f t) while they walk (200 of the 301 ticks of the 2 s walk
// and 1 s of settling): rmse_from_gait.z = 10 / sqrt(2) * sqrt(200 / 301) =
// 5.76 mm at any frequency the controller rate shows (4 ticks a period).
TEST(LeggedBase, TheGaitIsEvaluatedAtTheControllerRate) {
  const auto z_mm = [](const std::vector<std::string>& flags) {
    const nlohmann::json walk = ReplayWalk(flags);
    return walk.contains("gait") ? double(walk["gait"]["rmse_from_gait"]["z_mm"]) : -1.0;
  };
  const double expected = 10 / std::sqrt(2.0) * std::sqrt(200.0 / 301.0);
  for (const std::string hz : {"2", "9.7", "10", "20", "25"}) {
    EXPECT_NEAR(z_mm({"--gait_hz=" + hz}), expected, 0.03 * expected) << hz << " Hz";
  }
  EXPECT_NEAR(z_mm({"--gait_hz=100", "--controller_hz=400"}), expected, 0.03 * expected);
  // A gait of 1e-300 Hz does not bob (sin 0 = 0): only its sway's 0.02 rad
  // of roll moves the platform's centre, by a fraction of a millimetre.
  EXPECT_LT(z_mm({"--gait_hz=1e-300"}), 0.1 * expected);
  // A gait faster than a quarter of the controller rate is refused, naming both.
  const std::string path = testing::ScratchPath("legged", "walk.csv");
  const testing::ToolRun fast = testing::RunTool({"replay", "--model=" + testing::ModelPath("6dof_three_legged"),
                                                  "--waypoints=" + path, "--out=" + testing::ScratchPath("legged", "fast"),
                                                  "--noise=none", "--gait_hz=26"});
  EXPECT_EQ(fast.status, 2) << fast.err;
  EXPECT_TRUE(fast.out.empty());
  EXPECT_NE(fast.err.find("a gait of 26 Hz (gait_hz) needs a controller rate (controller_hz) of at least 104 Hz"),
            std::string::npos)
      << fast.err;
}

// The gait in closed form: nothing while a base stands still; walking, the
// height and roll move by bob sin(2 pi f t) and sway sin(2 pi f t), zero at
// the start and as far below the set-point as above it over a period.
TEST(LeggedBase, TheGaitIsZeroAtRestAndSymmetricWhileWalking) {
  const Model model = LoadModel(testing::ModelPath("6dof_three_legged"));
  Gait gait;
  gait.hz = 2;
  const Eigen::VectorXd home = model.home_controls();
  Eigen::VectorXd standing = Eigen::VectorXd::Zero(home.size()), walking = standing;
  walking[model.base_control(0)] = 0.05;  // base 0 walks along x
  Eigen::VectorXd u = home;
  ApplyGait(model, gait, 0.1, standing, &u);
  EXPECT_EQ(u, home);
  double low = 0, high = 0, left = 0, right = 0;
  for (int k = 0; k < 40; ++k) {
    const double t = k / 80.0;  // one period in 40 steps
    u = home;
    ApplyGait(model, gait, t, walking, &u);
    const int i = model.base_control(0);
    EXPECT_NEAR(u[i + 3] - home[i + 3], gait.bob_m * std::sin(2 * M_PI * 2 * t), 1e-15);
    EXPECT_NEAR(u[i + 4] - home[i + 4], gait.sway_rad * std::sin(2 * M_PI * 2 * t), 1e-15);
    EXPECT_EQ(u.segment(model.base_control(1), 6), home.segment(model.base_control(1), 6));  // base 1 stands
    low = std::min(low, u[i + 3] - home[i + 3]);
    high = std::max(high, u[i + 3] - home[i + 3]);
    left = std::min(left, u[i + 4] - home[i + 4]);
    right = std::max(right, u[i + 4] - home[i + 4]);
  }
  EXPECT_NEAR(high, gait.bob_m, 1e-15);
  EXPECT_NEAR(low, -gait.bob_m, 1e-15);
  EXPECT_NEAR(right, gait.sway_rad, 1e-15);
  EXPECT_NEAR(left, -gait.sway_rad, 1e-15);
  u = home;
  ApplyGait(model, gait, 0.0, walking, &u);
  EXPECT_EQ(u, home);  // the walk starts without a jump
}

TEST(LeggedBase, WorkspaceMapsAndPlansHoldTheBodyLimits) {
  // Heights from 0.85 to 1.75 m: the lower ones within reach, the top one
  // beyond what the bodies (at most 0.55 m) and arms can lift.
  const std::string map = testing::ScratchPath("legged", "map.csv");
  testing::ToolRun run = testing::RunTool({"workspace", "--model=" + testing::ModelPath("6dof_three_legged"),
                                           "--z=0.85:1.75", "--resolution=4", "--out=" + map});
  ASSERT_EQ(run.status, 0) << run.err;
  const std::string csv = testing::Slurp(map);
  EXPECT_NE(csv.find(",u17\n"), std::string::npos);  // 18 controls
  const nlohmann::json out = nlohmann::json::parse(run.out);
  EXPECT_EQ(out["samples"], 4);
  EXPECT_GE(int(out["reachable"]), 2);
  EXPECT_LT(int(out["reachable"]), 4);
  const std::string path = testing::ScratchPath("legged", "plan.csv");
  std::ofstream(path) << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.95,0,0,0\n4,0.2,0,0.95,0,0,0\n8,0.2,0.2,1.0,0,0,0.1\n";
  run = testing::RunTool({"plan", "--model=" + testing::ModelPath("6dof_three_legged"), "--waypoints=" + path,
                          "--out=" + testing::ScratchPath("legged", "planned.csv")});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(nlohmann::json::parse(run.out)["converged"].get<bool>());
}

TEST(LeggedBase, TheGeneratorMakesRigidPlatformsOnAnyNumberOfQuadrupeds) {
  for (const int agents : {3, 5}) {
    const std::string out = testing::ScratchPath("legged", "gen" + std::to_string(agents) + ".yaml");
    testing::ToolRun run =
        testing::RunTool({"generate", "--kind=legged", "--agents=" + std::to_string(agents), "--out=" + out});
    ASSERT_EQ(run.status, 0) << run.err;
    run = testing::RunTool({"check", "--model=" + out});
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json check = nlohmann::json::parse(run.out);
    EXPECT_EQ(check["controls"], 6 * agents);
    EXPECT_EQ(check["dof_with_controls_fixed"], 0);
    EXPECT_EQ(check["end_effector_dof"], 6);
  }
}

}  // namespace
}  // namespace ccma
