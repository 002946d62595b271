// The viewer's collision shapes and clearance (viewer/scene_format.md,
// "collision"): the scene's "collision" object against the model file's
// numbers, no trace of it without collision geometry, each frame's clearance
// against MinimumClearance at the frame's drawn poses and against the closed
// form of a base's cylinder beside a pillar, frames below the margin flagged
// and counted, and `ccma view`'s JSON. The page drawing them is tested in
// Chromium (viewer/js/test/collision_checks.mjs, CTest viewer_browser_collision_*).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ccma/state.h"
#include "collision/clearance.h"
#include "collision/collision_model.h"
#include "formats/model_loader.h"
#include "tests/tool_run.h"
#include "viewer/scene.h"
#include "viewer/view_frames.h"

namespace ccma::viewer {
namespace viewer_collision_test {

using ccma::testing::ModelPath;
using ccma::testing::RunTool;
using ccma::testing::ToolRun;
using nlohmann::json;

std::string Scratch(const std::string& name) { return ccma::testing::ScratchPath("viewer_collision", name); }

std::string Text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// 4dof_reduced with capsules on link0 and post2 (world coordinates at home),
// a pillar at x = 1.2 (0.195 m from base2's cylinder at home) and a crate
// far on the other side.
const char kCollision[] = R"(
collision:
  margin: 0.05
  base_height: 0.25
  links:
    - {body: link0, from: [0, 0.583012702, 0.35], to: [0, 0.15, 0.6], radius: 0.03}
    - {body: post2, from: [0.504903811, -0.291506351, 0.1], to: [0.504903811, -0.291506351, 0.35], radius: 0.04}
obstacles:
  - {name: pillar, cylinder: {center: [1.2, -0.3], radius: 0.2, height: 1.0}}
  - {name: crate, box: {center: [-1.5, 1.0, 0.25], size: [0.5, 0.4, 0.3], yaw: 0.4}}
)";

Model CollisionModel4dof() {
  return LoadModelFromString(Text(ModelPath("4dof_reduced")) + kCollision, "4dof_collision.yaml");
}

// Frames of 4dof_reduced with every base shifted by shift_x[i] [m] from home
// (the chain translates rigidly with them).
std::vector<ViewFrame> ShiftedFrames(const Model& model, const std::vector<double>& shift_x) {
  std::vector<ViewFrame> frames(shift_x.size());
  for (size_t i = 0; i < shift_x.size(); ++i) {
    frames[i].time = static_cast<double>(i);
    frames[i].controls = model.home_controls();
    for (int k = 0; k < model.num_bases(); ++k) frames[i].controls[3 * k] += shift_x[i];
  }
  return frames;
}

std::vector<double> Numbers(const json& j) { return j.get<std::vector<double>>(); }

TEST(SceneCollision, CarriesTheShapesOfTheModelFile) {
  const Model model = CollisionModel4dof();
  const json scene = json::parse(BuildScene(model, {}, "model", nullptr));
  ASSERT_TRUE(scene.contains("collision"));
  const json& c = scene["collision"];
  EXPECT_EQ(c["margin"], 0.05);
  EXPECT_EQ(c["base_height"], 0.25);
  EXPECT_EQ(c["bases"], json({0.3, 0.3, 0.3}));  // the default base_radius
  EXPECT_EQ(c["base_bodies"], json({7, 8, 9}));  // base0..2 after the 7 bodies
  ASSERT_EQ(c["links"].size(), 2u);
  // link0's capsule in link0's frame (at home at [0, 0.366506351, 0.475], not turned).
  EXPECT_EQ(c["links"][0]["body"], 2);
  const std::vector<double> from = Numbers(c["links"][0]["from"]), to = Numbers(c["links"][0]["to"]);
  EXPECT_NEAR(from[0], 0, 1e-12);
  EXPECT_NEAR(from[1], 0.216506351, 1e-7);
  EXPECT_NEAR(from[2], -0.125, 1e-7);
  EXPECT_NEAR(to[1], 0.15 - 0.366506351, 1e-7);
  EXPECT_NEAR(to[2], 0.125, 1e-7);
  EXPECT_EQ(c["links"][0]["radius"], 0.03);
  EXPECT_EQ(c["links"][1]["body"], 5);  // post2
  EXPECT_NEAR(Numbers(c["links"][1]["to"])[2], 0.25, 1e-7);
  ASSERT_EQ(c["obstacles"].size(), 2u);
  const json& pillar = c["obstacles"][0];
  EXPECT_EQ(pillar["name"], "pillar");
  EXPECT_EQ(pillar["shape"], "cylinder");
  EXPECT_EQ(pillar["center"], json({1.2, -0.3, 0.5}));  // half-way up
  EXPECT_EQ(pillar["radius"], 0.2);
  EXPECT_EQ(pillar["z_min"], 0);
  EXPECT_EQ(pillar["z_max"], 1.0);
  EXPECT_FALSE(pillar.contains("size"));
  const json& crate = c["obstacles"][1];
  EXPECT_EQ(crate["shape"], "box");
  EXPECT_EQ(crate["center"], json({-1.5, 1.0, 0.25}));
  EXPECT_EQ(crate["size"], json({0.5, 0.4, 0.3}));
  EXPECT_EQ(crate["yaw"], 0.4);
  EXPECT_EQ(crate["z_min"], 0.1);
  EXPECT_EQ(crate["z_max"], 0.4);
  EXPECT_FALSE(crate.contains("radius"));
}

TEST(SceneCollision, NoTraceWithoutCollisionGeometry) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  ASSERT_FALSE(model.collision.enabled);
  SceneSummary summary;
  const std::string text = BuildScene(model, ShiftedFrames(model, {0, 0.3, 0.6}), "trajectory", &summary);
  EXPECT_EQ(text.find("collision"), std::string::npos);
  EXPECT_EQ(text.find("clearance"), std::string::npos);
  EXPECT_EQ(summary.clearance_below_margin, 0);
  EXPECT_EQ(json::parse(text)["frames"]["flags"], json({0, 0, 0}));
}

// The bases move toward the pillar: base2's cylinder (radius 0.3) and the
// pillar (0.2) are hypot(0.695096189 - dx, 0.008493649) - 0.5 apart; the
// closest pair otherwise is link0's capsule (radius 0.03, its lower end at
// z = 0.35 straight over base0) and base0's cylinder (top at 0.25): 0.07 m.
TEST(SceneCollision, FramesBelowTheMarginAreFlaggedWithTheirClearance) {
  const Model model = CollisionModel4dof();
  const std::vector<double> dx = {0, 0.1, 0.16, 0.2, 0.3, 0.05};
  SceneSummary summary;
  const json scene = json::parse(BuildScene(model, ShiftedFrames(model, dx), "trajectory", &summary));
  const json& frames = scene["frames"];
  ASSERT_EQ(frames["clearance"].size(), dx.size());
  ASSERT_EQ(frames["clearance_pairs"].size(), dx.size());
  for (size_t i = 0; i < dx.size(); ++i) {
    const double pillar = std::hypot(0.695096189 - dx[i], 0.008493649) - 0.5;
    EXPECT_NEAR(frames["clearance"][i].get<double>(), std::min(pillar, 0.07), 2e-7) << "frame " << i;
    EXPECT_EQ(frames["clearance_pairs"][i], pillar < 0.07 ? json({"base2", "pillar"}) : json({"base0", "link0"}))
        << "frame " << i;
  }
  // Clearances 0.07, 0.07, 0.035, -0.005, -0.105, 0.07: the margin is 0.05.
  EXPECT_EQ(frames["flags"], json({0, 0, 1, 1, 1, 0}));
  EXPECT_EQ(summary.clearance_below_margin, 3);
  EXPECT_EQ(summary.flagged_frames, 3);
  EXPECT_EQ(summary.not_assembled, 0);
}

// Each frame's clearance is MinimumClearance at the poses the scene draws
// (rounded to 1e-7 m there, so they agree to a few 1e-7 m).
TEST(SceneCollision, ClearanceIsMinimumClearanceAtTheDrawnPoses) {
  const Model model = CollisionModel4dof();
  const json scene = json::parse(BuildScene(model, ShiftedFrames(model, {0, 0.25, 0.5, -0.4}), "trajectory", nullptr));
  const CollisionModel collision(model);
  const json& frames = scene["frames"];
  ASSERT_EQ(frames["poses"].size(), 4u);
  for (size_t f = 0; f < 4; ++f) {
    State s(model.num_bodies());
    for (int b = 0; b < model.num_bodies(); ++b) {
      const std::vector<double> p = Numbers(frames["poses"][f][b]);  // px py pz qx qy qz qw
      s.SetPose(b, Eigen::Quaterniond(p[6], p[3], p[4], p[5]).normalized(), Eigen::Vector3d(p[0], p[1], p[2]));
    }
    const ClearanceSummary c = MinimumClearance(collision, s);
    ASSERT_TRUE(c.any);
    EXPECT_NEAR(frames["clearance"][f].get<double>(), c.min, 1e-6) << "frame " << f;
    EXPECT_EQ(frames["clearance_pairs"][f], json({c.a, c.b})) << "frame " << f;
  }
  // The mechanism moved 0.9 m between frames 2 and 3: the pillar is no longer the closest.
  EXPECT_NE(frames["clearance_pairs"][2], frames["clearance_pairs"][3]);
}

TEST(SceneCollision, HomeFrameBelowTheMarginIsFlagged) {
  // The pillar of docs/viewer.md's picture: base2's cylinder overlaps it by 4.8 mm.
  const Model model = LoadModelFromString(
      Text(ModelPath("4dof_reduced")) + "obstacles:\n  - {name: pillar, cylinder: {center: [1.0, -0.3], radius: 0.2, height: 1.0}}\n",
      "pillar.yaml");
  SceneSummary summary;
  const json scene = json::parse(BuildScene(model, {}, "model", &summary));
  EXPECT_NEAR(scene["frames"]["clearance"][0].get<double>(), std::hypot(0.495096189, 0.008493649) - 0.5, 2e-7);
  EXPECT_EQ(scene["frames"]["flags"], json({1}));
  EXPECT_EQ(scene["collision"]["margin"], 0.02);  // the default
  EXPECT_EQ(scene["collision"]["links"], json::array());
  EXPECT_EQ(summary.clearance_below_margin, 1);
  EXPECT_EQ(summary.flagged_frames, 1);
}

TEST(ViewCollisionCli, CountsFramesBelowTheMarginOnlyWithCollisionGeometry) {
  const std::string obstacles = Scratch("room.yaml");
  std::ofstream(obstacles) << "obstacles:\n  - {name: pillar, cylinder: {center: [1.0, -0.3], radius: 0.2, height: 1.0}}\n";
  const std::string out = Scratch("room.html");
  const ToolRun r = RunTool({"view", "--model=" + ModelPath("4dof_reduced"), "--obstacles=" + obstacles, "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["clearance_below_margin_frames"], 1);
  EXPECT_EQ(j["flagged_frames"], 1);
  EXPECT_NE(r.err.find("1 frame(s) with a clearance below the margin of 0.02 m"), std::string::npos) << r.err;
  const std::string html = Text(out);
  EXPECT_NE(html.find("\"clearance_pairs\":[[\"base2\",\"pillar\"]]"), std::string::npos);

  const ToolRun plain = RunTool({"view", "--model=" + ModelPath("4dof_reduced"), "--out=" + out});
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_FALSE(json::parse(plain.out).contains("clearance_below_margin_frames"));
  EXPECT_EQ(Text(out).find("\"collision\""), std::string::npos);
}

}  // namespace
}  // namespace ccma::viewer
