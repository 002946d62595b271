// The viewer's C++ side: frames read from trajectory and replay files, the
// scene (shapes, poses, paths), the page, and `ccma view` on bad input. The
// page itself is tested in a real browser by viewer/js/test/browser_test.mjs
// (CTest: viewer_browser_*).
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "formats/model_loader.h"
#include "ccma/state.h"
#include "tests/tool_run.h"
#include "viewer/html.h"
#include "viewer/scene.h"
#include "viewer/view_frames.h"

namespace ccma::viewer {
namespace viewer_test {

namespace fs = std::filesystem;
using ccma::testing::RunTool;
using ccma::testing::ModelPath;
using ccma::testing::ToolRun;

std::string Scratch(const std::string& name) { return ccma::testing::ScratchPath("viewer", name); }

// A trajectory CSV written by the tool itself.
std::string Trajectory(const std::string& model) {
  const std::string csv = Scratch(model + "_path.csv");
  const std::string waypoints = Scratch("lift.csv");
  std::ofstream(waypoints) << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n2,0,0.03,0.62,0,0,0\n";
  const ToolRun r = RunTool({"trajectory", "--model=" + ModelPath(model), "--waypoints=" + waypoints, "--out=" + csv});
  EXPECT_EQ(r.status, 0) << r.err;
  return csv;
}

TEST(ViewFrames, TrajectoryRowsBecomeFramesWithTheirControls) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  const std::vector<ViewFrame> frames = FramesFromTrajectory(model, Trajectory("4dof_reduced"));
  // 3 cm and 2 cm in steps of at most 1 cm: 4 steps, plus the row at t = 0.
  ASSERT_EQ(frames.size(), 5u);
  EXPECT_EQ(frames.front().time, 0);
  EXPECT_EQ(frames.back().time, 2);
  EXPECT_TRUE(frames.front().controls.isApprox(model.home_controls(), 1e-12));
  ASSERT_TRUE(frames.back().commanded.has_value());
  EXPECT_NEAR(frames.back().commanded->y(), 0.03, 1e-12);
  EXPECT_NEAR(frames.back().tracked->z(), 0.62, 1e-9);
  for (const ViewFrame& f : frames) EXPECT_FALSE(f.flagged);
}

TEST(ViewFrames, ThinKeepsFirstAndLastEvenly) {
  std::vector<ViewFrame> frames(101);
  for (int i = 0; i <= 100; ++i) frames[i].time = i;
  const std::vector<ViewFrame> kept = Thin(frames, 11);
  ASSERT_EQ(kept.size(), 11u);
  for (int i = 0; i <= 10; ++i) EXPECT_EQ(kept[i].time, 10 * i);
  EXPECT_EQ(Thin(frames, 200).size(), 101u);
}

TEST(ViewFrames, BadFilesNameFileLineAndColumn) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  const std::string good = Trajectory("4dof_reduced");
  std::ifstream in(good);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  const std::string bad = Scratch("bad.csv");
  std::ofstream(bad) << header << "\n" << row << "\n" << "zero" << row.substr(row.find(',')) << "\n";
  try {
    FramesFromTrajectory(model, bad);
    FAIL() << "accepted a cell that is not a number";
  } catch (const ViewInputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad + ":3: column 'time_s': not a number"), std::string::npos) << e.what();
  }
  std::ofstream(bad) << "time_s,x_m\n0,1\n";
  EXPECT_THROW(FramesFromTrajectory(model, bad), ViewInputError);  // no control columns
  std::ofstream(bad) << header << "\n" << row << ",1\n";
  EXPECT_THROW(FramesFromTrajectory(model, bad), ViewInputError);  // one cell too many
  EXPECT_THROW(FramesFromTrajectory(model, ccma::testing::TestDir()), ViewInputError);  // a directory
  EXPECT_THROW(FramesFromReplay(model, Scratch("no_such_dir")), ViewInputError);
}

// A cell is a plain decimal number: every one ccma writes, subnormals too
// (4.9e-324 used to be refused, strtod flagging its underflow), and nothing
// else strtod reads (a hexadecimal float used to pass as 8).
TEST(ViewFrames, CellsAreDecimalNumbersSubnormalsIncluded) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  std::ifstream in(Trajectory("4dof_reduced"));
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  const std::string rest = row.substr(row.find(','));
  const std::string csv = Scratch("decimal.csv");
  const std::string good[] = {"4.9e-324", "4.9406564584124654e-324", "-0.0", "+2", "2.", ".5", "1E+2", "7e-400"};
  const double value[] = {4.9e-324, 4.9406564584124654e-324, 0.0, 2.0, 2.0, 0.5, 100.0, 0.0};
  for (size_t i = 0; i < std::size(good); ++i) {
    std::ofstream(csv) << header << "\n" << row << "\n" << good[i] << rest << "\n";
    const std::vector<ViewFrame> frames = FramesFromTrajectory(model, csv);
    ASSERT_EQ(frames.size(), 2u) << good[i];
    EXPECT_EQ(frames[1].time, value[i]) << good[i];
  }
  EXPECT_GT(FramesFromTrajectory(model, csv).size(), 0u);
  const std::string bad[] = {"0x1p3", "0x10", "0X1P-2", "inf", "-Infinity", "nan", "NAN(1)", " 1", "1 ", "1e",
                             "1e+", ".", "-", "+.e1", "1.2.3", "1e5e1", "1,5", "1_000", "\xef\xbc\x91", "1e309"};
  for (const std::string& cell : bad) {
    std::ofstream(csv) << header << "\n" << row << "\n" << cell << rest << "\n";
    try {
      FramesFromTrajectory(model, csv);
      ADD_FAILURE() << "accepted the time " << cell;
    } catch (const ViewInputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(csv + ":3:"), std::string::npos) << cell << ": " << what;
      EXPECT_TRUE(what.find("not a number") != std::string::npos ||
                  what.find("not a finite number") != std::string::npos || what.find("cells") != std::string::npos)
          << cell << ": " << what;
    }
  }
}

// A control cell between 1e4 and 1e6 passes the CSV's bound (times may reach
// 1e6) but not the controls' [-1e4, 1e4]: refused when the frame is read,
// naming file, line and column, for a trajectory and for a replay's bases,
// and by `ccma view` with status 2 (it used to fail later without them).
TEST(ViewFrames, ControlsBeyondTheirBoundNameFileLineAndColumn) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  std::ifstream in(Trajectory("4dof_reduced"));
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  const std::string bad = Scratch("big_control.csv");
  // u0_x_m is column 14 (after time_s, 6 target and 6 reached components).
  std::string big = row;
  size_t at = 0;
  for (int c = 0; c < 13; ++c) at = big.find(',', at) + 1;
  big.replace(at, big.find(',', at) - at, "50000");
  std::ofstream(bad) << header << "\n" << row << "\n" << big << "\n";
  try {
    FramesFromTrajectory(model, bad);
    FAIL() << "accepted a control of 5e4";
  } catch (const ViewInputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad + ":3: column 'u0_x_m': a control of 50000 is outside [-1e4, 1e4]"),
              std::string::npos)
        << e.what();
  }
  const ToolRun r = RunTool({"view", "--model=" + ModelPath("4dof_reduced"), "--trajectory=" + bad,
                             "--out=" + Scratch("big_control.html")});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find(bad + ":3: column 'u0_x_m'"), std::string::npos) << r.err;

  const std::string dir = Scratch("big_replay");
  fs::create_directories(dir);
  std::ofstream(dir + "/end_effector.csv") << "time_s,cmd_x_m,cmd_y_m,cmd_z_m,x_m,y_m,z_m\n0,0,0,0.6,0,0,0.6\n";
  std::ofstream(dir + "/bases.csv") << "time_s,base0_x_m,base0_y_m,base0_theta_rad,base1_x_m,base1_y_m,"
                                       "base1_theta_rad,base2_x_m,base2_y_m,base2_theta_rad\n0,0,0,0,0,0,-1e4,0,0,-10001\n";
  try {
    FramesFromReplay(model, dir);
    FAIL() << "accepted a control of -10001";
  } catch (const ViewInputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/bases.csv:2: column 'base2_theta_rad': a control of -10001"),
              std::string::npos)
        << e.what();
  }
}

TEST(Scene, HomeFrameShapesAndEscaping) {
  Model model = LoadModel(ModelPath("4dof_reduced"));
  model.description = "</script><script>alert(1)</script> & more";
  SceneSummary summary;
  const std::string text = BuildScene(model, {}, "model", &summary);
  EXPECT_EQ(text.find('<'), std::string::npos);
  EXPECT_EQ(text.find('&'), std::string::npos);
  const nlohmann::json scene = nlohmann::json::parse(text);
  EXPECT_EQ(scene["description"], model.description);  // the escapes read back
  EXPECT_EQ(summary.frames, 1);
  ASSERT_EQ(scene["bodies"].size(), 10u);
  ASSERT_EQ(scene["joints"].size(), 9u);
  // The end-effector platform: three joint points and the end-effector point in a ring.
  EXPECT_EQ(scene["bodies"][0]["points"].size(), 4u);
  EXPECT_EQ(scene["bodies"][0]["links"].size(), 4u);
  // A link body: its two joint points, one capsule.
  EXPECT_EQ(scene["bodies"][2]["links"].size(), 1u);
  // Bases: discs, a capsule from the centre to the post's joint.
  EXPECT_EQ(scene["bodies"][7]["kind"], "omni");
  EXPECT_GT(scene["bodies"][7]["radius"].get<double>(), 0.05);
  // Home poses: p_WB and the quaternion (x, y, z, w) of every body.
  const State home = State::Home(model);
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto& pose = scene["frames"]["poses"][0][b];
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(pose[i].get<double>(), home.p_WB(b)[i], 1e-7);
    EXPECT_NEAR(std::abs(pose[6].get<double>()), std::abs(home.q_WB(b).w()), 1e-7);
  }
  EXPECT_FALSE(scene.contains("paths"));
}

TEST(Scene, TrajectoryFramesAreReassembledAlongThePath) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  const std::vector<ViewFrame> frames = FramesFromTrajectory(model, Trajectory("4dof_reduced"));
  SceneSummary summary;
  const nlohmann::json scene = nlohmann::json::parse(BuildScene(model, frames, "trajectory", &summary));
  EXPECT_EQ(summary.frames, 5);
  EXPECT_EQ(summary.flagged_frames, 0);
  EXPECT_EQ(summary.not_assembled, 0);
  const auto& poses = scene["frames"]["poses"];
  ASSERT_EQ(poses.size(), 5u);
  // The end-effector body (ee, index 0) reaches the target: y 0.03, z 0.62.
  EXPECT_NEAR(poses[4][0][1].get<double>(), 0.03, 1e-6);
  EXPECT_NEAR(poses[4][0][2].get<double>(), 0.62, 1e-6);
  EXPECT_EQ(scene["paths"]["bases"].size(), 3u);
  EXPECT_EQ(scene["paths"]["commanded"].size(), 5u);
}

TEST(Scene, UnreachableFramesAreFlagged) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  ViewFrame far;
  far.time = 1;
  far.controls = model.home_controls();
  far.controls[1] = 1.5;  // base0 pulled 0.9 m outwards: the leg cannot reach
  SceneSummary summary;
  BuildScene(model, {far}, "trajectory", &summary);
  EXPECT_EQ(summary.not_assembled, 1);
  EXPECT_EQ(summary.flagged_frames, 1);
}

// A trajectory CSV of 4dof_reduced whose bases all sit at home shifted by
// shift_x[i] [m] in frame i (the chain translates rigidly with them).
std::string JumpingTrajectory(const Model& model, const std::vector<double>& shift_x) {
  const std::string csv = Scratch("jumping.csv");
  std::ofstream out(csv);
  out.precision(17);
  out << "time_s";
  for (int k = 0; k < model.num_bases(); ++k) out << ",u" << k << "_x_m,u" << k << "_y_m,u" << k << "_theta_rad";
  out << ",target_x_m,target_y_m,target_z_m,x_m,y_m,z_m,reached\n";
  const Eigen::VectorXd home = model.home_controls();
  for (size_t i = 0; i < shift_x.size(); ++i) {
    out << i;
    for (int k = 0; k < model.num_bases(); ++k) {
      out << "," << home[3 * k] + shift_x[i] << "," << home[3 * k + 1] << "," << home[3 * k + 2];
    }
    out << "," << shift_x[i] << ",0,0.6," << shift_x[i] << ",0,0.6,1\n";
  }
  return csv;
}

// Bases jumping 2 km (100,000 sub-steps of 0.02) between frames: those frames
// are not attempted (the work bound, scene.h) and the mechanism stays at the
// last frame assembled; before the bound each took 100,000 forward solves.
// CTest runs viewer_test with a 60 s TIMEOUT (tests/CMakeLists.txt).
TEST(Scene, FramesBeyondTheWorkBoundAreNotAttempted) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  const std::vector<ViewFrame> frames = FramesFromTrajectory(model, JumpingTrajectory(model, {0, 2000, 0, 2000, 1}));
  ASSERT_EQ(frames.size(), 5u);
  SceneSummary summary;
  const nlohmann::json scene = nlohmann::json::parse(BuildScene(model, frames, "trajectory", &summary));
  EXPECT_EQ(summary.frames, 5);
  EXPECT_EQ(summary.beyond_work_bound, 2);
  EXPECT_EQ(summary.not_assembled, 2);
  EXPECT_EQ(summary.flagged_frames, 2);
  EXPECT_EQ(scene["frames"]["flags"], nlohmann::json({0, 1, 0, 1, 0}));
  const auto& poses = scene["frames"]["poses"];
  ASSERT_EQ(poses.size(), 5u);
  EXPECT_EQ(poses[1], poses[0]);  // stayed at the last frame assembled
  EXPECT_EQ(poses[3], poses[2]);
  // The last frame, 1 m (50 sub-steps) from frame 2, is assembled: moved 1 m in x.
  EXPECT_NEAR(poses[4][0][0].get<double>() - poses[2][0][0].get<double>(), 1.0, 1e-6);
}

// The page's total: frames 19.97 m apart (999 sub-steps each) use up the
// 200,000 sub-steps after 200 moves; the 201st is not attempted, and the next,
// back at the last frame assembled (1 sub-step), still fits.
TEST(Scene, FramesPastTheTotalWorkBoundAreNotAttempted) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  std::vector<ViewFrame> frames(203);
  for (size_t i = 0; i < frames.size(); ++i) {
    frames[i].time = static_cast<double>(i);
    frames[i].controls = model.home_controls();
    for (int k = 0; k < model.num_bases(); ++k) frames[i].controls[3 * k] += i % 2 == 1 ? 19.97 : 0.0;
  }
  SceneSummary summary;
  const nlohmann::json scene = nlohmann::json::parse(BuildScene(model, frames, "trajectory", &summary));
  EXPECT_EQ(summary.beyond_work_bound, 1);
  EXPECT_EQ(summary.not_assembled, 1);
  const auto& flags = scene["frames"]["flags"];
  ASSERT_EQ(flags.size(), 203u);
  EXPECT_EQ(flags[201], 1);
  EXPECT_EQ(flags[200], 0);
  EXPECT_EQ(flags[202], 0);
}

TEST(Html, PageIsSelfContained) {
  ASSERT_TRUE(HasBundle()) << "built without the viewer's JavaScript (see the CMake configure output)";
  const std::string html = ViewerHtml("{\"format\":\"ccma-scene-1\"}", "m<x>");
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("default-src 'none'"), std::string::npos);
  EXPECT_NE(html.find("<title>ccma view: m&lt;x&gt;</title>"), std::string::npos);
  // Exactly the two script elements of the shell close.
  size_t closes = 0;
  for (size_t p = html.find("</script"); p != std::string::npos; p = html.find("</script", p + 1)) ++closes;
  EXPECT_EQ(closes, 2u);
  // three.js is inside, with its licence comment.
  EXPECT_NE(html.find("three"), std::string::npos);
}

TEST(ViewCli, WritesThePageAndSummarises) {
  const std::string out = Scratch("page.html");
  const ToolRun r = RunTool({"view", "--model=" + ModelPath("6dof_six_agents"), "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], 1);
  EXPECT_EQ(j["out"], out);
  EXPECT_EQ(j["bytes"].get<size_t>(), fs::file_size(out));
  EXPECT_EQ(j["source"], "model");
}

TEST(ViewCli, FramesBeyondTheWorkBoundAreCounted) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  const std::string out = Scratch("jumping.html");
  const ToolRun r = RunTool({"view", "--model=" + ModelPath("4dof_reduced"),
                             "--trajectory=" + JumpingTrajectory(model, {0, 2000, 4000, 2000, 0}), "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], 5);
  EXPECT_EQ(j["beyond_work_bound_frames"], 3);
  EXPECT_EQ(j["not_assembled_frames"], 3);
  EXPECT_EQ(j["flagged_frames"], 3);
  EXPECT_NE(r.err.find("3 of them not attempted"), std::string::npos) << r.err;
}

TEST(ViewCli, BadInputExitsTwoWithNothingOnStdout) {
  const std::string out = Scratch("bad.html");
  const std::string bad = Scratch("garbage.csv");
  std::ofstream(bad) << "time_s,u0_x_m\n1,2,3\n";
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"view", "--model=" + ModelPath("4dof_reduced"), "--trajectory=" + bad, "--out=" + out},
           {"view", "--model=" + ModelPath("4dof_reduced"), "--trajectory=" + bad, "--replay=/tmp", "--out=" + out},
           {"view", "--model=" + ModelPath("4dof_reduced"), "--replay=/nonexistent", "--out=" + out},
           {"view", "--model=" + ModelPath("4dof_reduced"), "--trajectory=/dev/zero", "--out=" + out},
           {"view", "--model=" + ModelPath("4dof_reduced")},
       }) {
    const ToolRun r = RunTool(args);
    EXPECT_EQ(r.status, 2) << args[2] << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(r.err.empty());
  }
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace ccma::viewer
