// `ccma view --color_by=load` (viewer/frame_loads.h): each frame's statics,
// each body's load (the largest reaction force of the joints touching it),
// against closed forms: the tripod's legs, a hanging chain; a frame not
// balanced, frames not determinate, a model without masses; the bounds and
// the flag on the command line.
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "formats/model_loader.h"
#include "tests/tool_run.h"
#include "viewer/frame_loads.h"
#include "viewer/scene.h"

namespace ccma::viewer {
namespace viewer_loads_test {

using nlohmann::json;
using ccma::testing::ModelPath;
using ccma::testing::RunTool;
using ccma::testing::ToolRun;

const double kG = 9.81;  // the default gravity [m/s^2]

std::string TripodPath() { return std::string(CCMA_MODELS_DIR) + "/../examples/statics/tripod.yaml"; }

// The body index of `name` in the scene.
int BodyIndex(const json& scene, const std::string& name) {
  for (std::size_t b = 0; b < scene["bodies"].size(); ++b) {
    if (scene["bodies"][b]["name"] == name) return static_cast<int>(b);
  }
  ADD_FAILURE() << "no body " << name;
  return 0;
}

// Two bodies hanging from the world: A (1 kg) at [0, 0, -0.5] on a motorised
// revolute about x at the origin, B (2 kg) at [bx, 0, bz] on a spherical
// joint at [0, 0, -1]. Straight down (bx = 0) it hangs balanced, the motor
// idle.
std::string Chain(double bx, double bz) {
  return "name: chain\nbodies:\n"
         "  - {name: A, position: [0, 0, -0.5], mass: 1}\n"
         "  - {name: B, position: [" + std::to_string(bx) + ", 0, " + std::to_string(bz) + "], mass: 2}\n"
         "joints:\n"
         "  - {name: top, type: revolute, actuated: true, between: [world, A], point: [0, 0, 0], axis: [1, 0, 0]}\n"
         "  - {name: middle, type: spherical, between: [A, B], point: [0, 0, -1]}\n"
         "end_effector: {body: B, point: [0, 0, -2], controlled: [x]}\n";
}

TEST(FrameLoads, TripodLegsCarryAThirdOfTheWeightAlongThem) {
  const Model model = LoadModel(TripodPath());
  SceneSummary summary;
  const json scene = json::parse(BuildScene(model, {}, "model", &summary, nullptr, nullptr, ColorBy::kLoad));
  const json& loads = scene["loads"];
  // 3 kg on three legs from the unit circle to an apex 1 m up: each leg is a
  // two-force member at 45 degrees, W/3 vertically, W sqrt(2)/3 along it.
  const double leg = 3 * kG * std::sqrt(2.0) / 3;  // 13.873 N
  ASSERT_EQ(loads["body_loads"].size(), 1u);
  EXPECT_NEAR(loads["body_loads"][0][BodyIndex(scene, "top")].get<double>(), leg, 1e-6);
  for (const char* name : {"low0", "up0", "low1", "up1", "low2", "up2"}) {
    EXPECT_NEAR(loads["body_loads"][0][BodyIndex(scene, name)].get<double>(), leg, 1e-6) << name;
  }
  EXPECT_NEAR(loads["max"].get<double>(), leg, 1e-6);
  EXPECT_NEAR(summary.max_load, leg, 1e-6);
  EXPECT_EQ(loads["masses"], true);
  EXPECT_EQ(loads["balanced"], json::array({1}));
  EXPECT_EQ(loads["determinate"], json::array({1}));
  EXPECT_EQ(loads["unit"], "N");
  EXPECT_EQ(summary.unbalanced_frames, 0);
  EXPECT_EQ(summary.indeterminate_frames, 0);
}

TEST(FrameLoads, EveryFrameAtItsOwnStateAsTheLegsExtend) {
  const Model model = LoadModel(TripodPath());
  std::vector<ViewFrame> frames;
  for (const double q : {0.0, 0.1, 0.2}) {
    ViewFrame f;
    f.time = 10 * q;
    f.controls = Eigen::VectorXd::Constant(3, q);
    frames.push_back(f);
  }
  SceneSummary summary;
  const json scene = json::parse(BuildScene(model, frames, "trajectory", &summary, nullptr, nullptr, ColorBy::kLoad));
  ASSERT_EQ(summary.not_assembled, 0);
  const json& loads = scene["loads"];
  ASSERT_EQ(loads["body_loads"].size(), 3u);
  // Legs of length l = sqrt(2) + q from the unit circle: the apex at
  // h = sqrt(l^2 - 1), each leg W l / (3 h) along itself.
  double largest = 0;
  for (int f = 0; f < 3; ++f) {
    const double l = std::sqrt(2.0) + 0.1 * f, h = std::sqrt(l * l - 1);
    const double leg = 3 * kG * l / (3 * h);
    EXPECT_NEAR(loads["body_loads"][f][BodyIndex(scene, "top")].get<double>(), leg, 1e-6) << "frame " << f;
    largest = std::max(largest, leg);
  }
  EXPECT_LT(loads["body_loads"][2][0].get<double>(), loads["body_loads"][0][0].get<double>());  // steeper legs
  EXPECT_NEAR(loads["max"].get<double>(), largest, 1e-6);
}

TEST(FrameLoads, ABodyTakesTheLargestReactionOfItsJoints) {
  const Model model = LoadModelFromString(Chain(0, -1.5), "chain.yaml");
  SceneSummary summary;
  const json scene = json::parse(BuildScene(model, {}, "model", &summary, nullptr, nullptr, ColorBy::kLoad));
  // The top joint holds both bodies (3 kg), the middle one B alone (2 kg):
  // A touches both, B the middle one.
  EXPECT_NEAR(scene["loads"]["body_loads"][0][0].get<double>(), 3 * kG, 1e-6);
  EXPECT_NEAR(scene["loads"]["body_loads"][0][1].get<double>(), 2 * kG, 1e-6);
  EXPECT_NEAR(scene["loads"]["max"].get<double>(), 3 * kG, 1e-6);
  EXPECT_EQ(scene["loads"]["balanced"], json::array({1}));
  EXPECT_EQ(scene["loads"]["determinate"], json::array({1}));
}

TEST(FrameLoads, AnUnbalancedFrameIsMarked) {
  // B's centre 0.5 m to the side of the middle joint: a spherical joint
  // cannot hold its weight's moment.
  const Model model = LoadModelFromString(Chain(0.5, -1), "chain.yaml");
  SceneSummary summary;
  const json scene = json::parse(BuildScene(model, {}, "model", &summary, nullptr, nullptr, ColorBy::kLoad));
  EXPECT_EQ(scene["loads"]["balanced"], json::array({0}));
  EXPECT_EQ(summary.unbalanced_frames, 1);
}

TEST(FrameLoads, ClosedLoopsGiveMinimumNormLoadsMarkedIndeterminate) {
  std::string text = ccma::testing::Slurp(ModelPath("4dof_reduced"));
  text.replace(text.find("end_effector:\n"), 14, "end_effector:\n  payload: {mass: 5}\n");
  const Model model = LoadModelFromString(text, "4dof_payload.yaml");
  SceneSummary summary;
  const json scene = json::parse(BuildScene(model, {}, "model", &summary, nullptr, nullptr, ColorBy::kLoad));
  EXPECT_EQ(scene["loads"]["determinate"], json::array({0}));
  EXPECT_EQ(summary.indeterminate_frames, 1);
  EXPECT_EQ(scene["loads"]["balanced"], json::array({1}));
  // The platform's three joints share its 5 kg: together at least its weight.
  EXPECT_GE(scene["loads"]["body_loads"][0][0].get<double>(), 5 * kG / 3 - 1e-9);
}

TEST(FrameLoads, NoMassesNoLoadsAndNoKeyUnlessAsked) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  SceneSummary summary;
  const json scene = json::parse(BuildScene(model, {}, "model", &summary, nullptr, nullptr, ColorBy::kLoad));
  EXPECT_EQ(scene["loads"]["masses"], false);
  EXPECT_EQ(scene["loads"]["max"], 0.0);
  ASSERT_EQ(scene["loads"]["body_loads"][0].size(), model.bodies.size());
  for (const json& load : scene["loads"]["body_loads"][0]) EXPECT_EQ(load.get<double>(), 0.0);
  EXPECT_FALSE(json::parse(BuildScene(model, {}, "model", nullptr)).contains("loads"));
}

TEST(FrameLoads, StaticsBeyondTheWorkBoundIsRefusedBeforeAnySolve) {
  const Model model = LoadModel(TripodPath());
  EXPECT_NO_THROW(FrameLoads(model, 2000));
  try {
    FrameLoads(model, 100000000);
    ADD_FAILURE() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("work bound of 2e+10"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(FrameLoads(LoadModel(ModelPath("4dof_reduced")), 100000000));  // no masses: nothing to solve
}

TEST(ViewLoadsCli, FlagValuesAndBounds) {
  const std::string dir = ccma::testing::ScratchPath("viewer_loads", "");
  ToolRun r = RunTool({"view", "--model=" + TripodPath(), "--color_by=load", "--out=" + dir + "tripod.html"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json out = json::parse(r.out);
  EXPECT_NEAR(out["max_load"].get<double>(), 3 * kG * std::sqrt(2.0) / 3, 1e-6);
  EXPECT_EQ(out["unbalanced_frames"], 0);
  EXPECT_EQ(out["indeterminate_frames"], 0);
  r = RunTool({"view", "--model=" + TripodPath(), "--out=" + dir + "plain.html"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(json::parse(r.out).contains("max_load"));
  r = RunTool({"view", "--model=" + TripodPath(), "--color_by=weight", "--out=" + dir + "bad.html"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("--color_by must be body or load"), std::string::npos) << r.err;
  // 300 legs and a mass: 5100 rows x 3606 coordinates, beyond one statics' bound.
  r = RunTool({"generate", "--agents=300", "--kind=stewart_gough", "--out=" + dir + "big.yaml"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::string big = ccma::testing::Slurp(dir + "big.yaml");
  big.replace(big.find("position: [0, 0, 0.6]}"), 22, "position: [0, 0, 0.6], mass: 1}");
  std::ofstream(dir + "big_mass.yaml") << big;
  r = RunTool({"view", "--model=" + dir + "big_mass.yaml", "--color_by=load", "--out=" + dir + "big.html"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("--color_by=load: statics: 5100 constraint rows x 3606 state coordinates exceed 8000000"),
            std::string::npos) << r.err;
}

}  // namespace
}  // namespace ccma::viewer
