// `ccma view --trajectory=T.csv --dynamics=D.csv` (viewer/frame_efforts.h):
// each frame's effort share of every limited actuator, against the closed
// form of an arm on a motor turning at a constant rate (torque m g l cos q),
// frames beyond the limit counted, a row that did not assemble, and the
// flag's misuse and hostile CSVs on the command line (exit 2, file, line and
// column named, nothing on stdout).
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "formats/model_loader.h"
#include "tests/tool_run.h"
#include "viewer/frame_efforts.h"
#include "viewer/scene.h"
#include "viewer/view_frames.h"

namespace ccma::viewer {
namespace viewer_efforts_test {

using nlohmann::json;
using ccma::testing::RunTool;
using ccma::testing::ToolRun;

// The arm of tests/dynamics_cli_test.cc (2.5 kg at l = 0.4 m from a hinge
// about -y), its motor limited to [-20, 9] N m: gravity's torque m g l cos q
// (9.81 N m at q = 0) is beyond 9 N m where |q| < 0.41 rad.
constexpr char kArm[] =
    "name: arm\nbodies:\n  - {name: arm, position: [0.2, 0, 0], mass: 2.5, com: [0.4, 0, 0],"
    " inertia: [0.02, 0.03, 0.025, 0.004, -0.003, 0.002]}\n"
    "joints:\n  - {name: hinge, type: revolute, actuated: true, between: [world, arm], point: [0, 0, 0], "
    "axis: [0, -1, 0], effort_limits: [-20, 9]}\nend_effector: {body: arm, point: [0.5, 0, 0], controlled: [x, z]}\n";

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = ccma::testing::ScratchPath("viewer_efforts", name);
  std::ofstream(path) << text;
  return path;
}

// A trajectory CSV (the columns ccma view and ccma dynamics read): q(t) =
// -0.4 + 1.3 t, rows every 0.1 s, times shifted by `shift` s.
std::string ArmTrajectory(int rows, double shift = 0) {
  std::ostringstream csv;
  csv.precision(17);
  csv << "time_s,target_x_m,target_y_m,target_z_m,x_m,y_m,z_m,u_hinge_rad\n";
  for (int r = 0; r < rows; ++r) {
    const double t = 0.1 * r, q = -0.4 + 1.3 * t, x = 0.5 * std::cos(q), z = 0.5 * std::sin(q);
    csv << t + shift << "," << x << ",0," << z << "," << x << ",0," << z << "," << q << "\n";
  }
  return csv.str();
}

// The dynamics CSV of the arm's trajectory, written by `ccma dynamics`.
std::string ArmEfforts(const std::string& model, const std::string& trajectory, const std::string& name) {
  const std::string out = ccma::testing::ScratchPath("viewer_efforts", name);
  const ToolRun r = RunTool({"dynamics", "--model=" + model, "--trajectory=" + trajectory, "--out=" + out});
  EXPECT_EQ(r.status, 0) << r.err;
  return out;
}

TEST(FrameEfforts, ShareOfTheLimitIsTheClosedFormTorqueOverTheLimitsEnd) {
  const std::string model_path = Write("arm.yaml", kArm);
  const std::string trajectory = Write("arm_path.csv", ArmTrajectory(11));
  const std::string efforts_csv = ArmEfforts(model_path, trajectory, "arm_efforts.csv");
  const Model model = LoadModel(model_path);
  const std::vector<ViewFrame> frames = FramesFromTrajectory(model, trajectory);
  const FrameEfforts efforts = ReadFrameEfforts(model, efforts_csv, frames);
  ASSERT_EQ(efforts.actuators.size(), 1u);
  EXPECT_EQ(efforts.actuators[0].name, "hinge");
  EXPECT_EQ(efforts.actuators[0].kind, "effort");
  EXPECT_EQ(efforts.actuators[0].body, 0);  // the arm the motor drives
  ASSERT_EQ(efforts.shares.size(), 11u);
  int beyond = 0;
  double max = 0;
  for (int f = 0; f < 11; ++f) {
    const double q = -0.4 + 1.3 * 0.1 * f, torque = 2.5 * 9.81 * 0.4 * std::cos(q);
    EXPECT_NEAR(efforts.shares[f][0], torque / 9.0, 1e-9) << f;
    beyond += torque > 9.0 ? 1 : 0;
    max = std::max(max, torque / 9.0);
  }
  EXPECT_GT(beyond, 0);
  EXPECT_LT(beyond, 11);  // both kinds of frame
  EXPECT_NEAR(efforts.max, max, 1e-9);

  SceneSummary summary;
  const json scene = json::parse(BuildScene(model, frames, "trajectory", &summary, nullptr, nullptr, ColorBy::kBody,
                                            nullptr, &efforts));
  ASSERT_TRUE(scene.contains("efforts"));
  EXPECT_EQ(scene["efforts"]["actuators"][0]["body"], 0);
  EXPECT_EQ(scene["efforts"]["shares"].size(), scene["frames"]["time"].size());
  EXPECT_NEAR(scene["efforts"]["shares"][3][0].get<double>(), efforts.shares[3][0], 1e-7);
  EXPECT_EQ(summary.effort_frames_beyond_limit, beyond);
  ASSERT_TRUE(summary.max_effort_share.has_value());
  EXPECT_NEAR(*summary.max_effort_share, max, 1e-9);
  // Without efforts, no key.
  EXPECT_FALSE(json::parse(BuildScene(model, frames, "trajectory", nullptr)).contains("efforts"));
}

TEST(FrameEfforts, ARowThatDidNotAssembleIsMinusOne) {
  const Model model = LoadModel(Write("arm.yaml", kArm));
  const std::string trajectory = Write("arm_path3.csv", ArmTrajectory(3));
  const std::string efforts = Write("gap.csv", "time_s,u_hinge_Nm,kinetic_J,potential_J,power_W\n"
                                              "0,8,0,0,0\n0.1,,,,\n0.2,-10,0,0,0\n");
  const FrameEfforts e = ReadFrameEfforts(model, efforts, FramesFromTrajectory(model, trajectory));
  ASSERT_EQ(e.shares.size(), 3u);
  EXPECT_NEAR(e.shares[0][0], 8.0 / 9.0, 1e-12);
  EXPECT_EQ(e.shares[1][0], -1.0);
  EXPECT_NEAR(e.shares[2][0], 10.0 / 20.0, 1e-12);  // the lower end
}

void ExpectViewRefused(const std::vector<std::string>& args, const std::string& message) {
  const ToolRun r = RunTool(args);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
}

TEST(ViewDynamicsCli, ColoursAndRefusesWhatItCannotColour) {
  const std::string model = Write("arm.yaml", kArm);
  const std::string trajectory = Write("arm_path.csv", ArmTrajectory(11));
  const std::string efforts = ArmEfforts(model, trajectory, "cli_efforts.csv");
  const std::string page = ccma::testing::ScratchPath("viewer_efforts", "arm.html");
  const ToolRun r = RunTool({"view", "--model=" + model, "--trajectory=" + trajectory, "--dynamics=" + efforts,
                             "--out=" + page});
  ASSERT_EQ(r.status, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_GT(j["max_effort_share"].get<double>(), 1.0);
  EXPECT_GT(j["effort_frames_beyond_limit"].get<int>(), 0);
  EXPECT_NE(r.err.find("beyond its effort or push limit"), std::string::npos) << r.err;

  const std::vector<std::string> base = {"view", "--model=" + model, "--out=" + page};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = base;
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  ExpectViewRefused(with({"--dynamics=" + efforts}), "--dynamics goes with --trajectory");
  ExpectViewRefused(with({"--trajectory=" + trajectory, "--dynamics=" + efforts, "--color_by=load"}),
                    "not with --color_by=load");
  // The dynamics of another trajectory (its times 5 s later): the first frame's time is missing.
  const std::string later = ArmEfforts(model, Write("later.csv", ArmTrajectory(11, 5.0)), "later_efforts.csv");
  ExpectViewRefused(with({"--trajectory=" + trajectory, "--dynamics=" + later}), "no row at time_s 0");
  const std::string bad = Write("bad.csv", "time_s,u_hinge_Nm\n0,1\n0.1,nan\n");
  ExpectViewRefused(with({"--trajectory=" + trajectory, "--dynamics=" + bad}), "bad.csv:3");
  ExpectViewRefused(with({"--trajectory=" + trajectory, "--dynamics=" + Write("nocol.csv", "time_s,x\n0,1\n")}),
                    "u_hinge_Nm");
  std::string free_arm = kArm;
  free_arm.replace(free_arm.find(", effort_limits: [-20, 9]"), 25, "");
  ExpectViewRefused({"view", "--model=" + Write("free.yaml", free_arm), "--trajectory=" + trajectory,
                     "--dynamics=" + efforts, "--out=" + page},
                    "no effort_limits or push_limit");
}

}  // namespace viewer_efforts_test
}  // namespace ccma::viewer
