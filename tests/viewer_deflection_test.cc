// `ccma view --deflection=SCALE` (viewer/deflection_shape.h): the loaded
// shape in the scene against `ccma simulate --loaded` (the same loaded
// equilibrium, number for number) and the scale applied exactly; a motorised
// arm against its closed form; without the flag, no trace of it; the flag's
// values and the static-view flags refused with exit 2.
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ccma/rotation.h"
#include "formats/model_loader.h"
#include "tests/tool_run.h"
#include "viewer/scene.h"

namespace ccma::viewer {
namespace viewer_deflection_test {

using nlohmann::json;
using ccma::testing::ModelPath;
using ccma::testing::RunTool;
using ccma::testing::ToolRun;

std::string StewartPath() {
  return std::string(CCMA_MODELS_DIR) + "/../examples/statics/stewart_gough_compliant.yaml";
}

// A 2 kg arm, its centre 0.5 m out along x, on a motor about y of stiffness
// k = 500 N*m/rad at the height 1 m: gravity turns it down by theta with
// k theta = m g 0.5 cos(theta) (the exact equilibrium).
const char kArm[] =
    "name: arm\nbodies:\n  - {name: arm, position: [0.5, 0, 1], mass: 2}\njoints:\n"
    "  - {name: shoulder, type: revolute, actuated: true, stiffness: 500, between: [world, arm], point: [0, 0, 1],"
    " axis: [0, 1, 0]}\nend_effector: {body: arm, point: [1, 0, 1], controlled: [z]}\n";

// The scene of a page: the text of <script id="ccma-scene">.
json DeflectionSceneOf(const std::string& html_path) {
  const std::string html = ccma::testing::Slurp(html_path);
  const std::string open = "<script type=\"application/json\" id=\"ccma-scene\">";
  const size_t from = html.find(open) + open.size();
  return json::parse(html.substr(from, html.find("</script>", from) - from));
}

Eigen::Vector3d Vec3(const json& v) { return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()}; }

// A simulate body's quaternion [w, x, y, z]; a scene pose's [.., qx, qy, qz, qw].
Eigen::Quaterniond SimulateQuaternion(const json& body) {
  const json& q = body["quaternion"];
  return Eigen::Quaterniond(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>());
}
Eigen::Quaterniond SceneQuaternion(const json& pose) {
  return Eigen::Quaterniond(pose[6].get<double>(), pose[3].get<double>(), pose[4].get<double>(), pose[5].get<double>());
}
double QuaternionGap(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
}

TEST(ViewDeflection, LoadedPosesAreSimulateLoadedAndTheScaleIsAppliedExactly) {
  const std::string dir = ccma::testing::ScratchPath("viewer_deflection", "");
  const std::string controls = "--controls=0.01,-0.02,0.03,0.015,-0.01,0.005";
  const std::string wrench = "--wrench=40,-25,-300,5,-8,3";
  const double scale = 250;
  ToolRun r = RunTool({"view", "--model=" + StewartPath(), controls, wrench, "--deflection=250",
                       "--out=" + dir + "stewart.html"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json out = json::parse(r.out);
  const json scene = DeflectionSceneOf(dir + "stewart.html");
  r = RunTool({"simulate", "--model=" + StewartPath(), controls, wrench, "--loaded"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json loaded = json::parse(r.out);
  r = RunTool({"simulate", "--model=" + StewartPath(), controls});
  ASSERT_EQ(r.status, 0) << r.err;
  const json rigid = json::parse(r.out);
  EXPECT_EQ(scene["source"], "controls");
  const json& d = scene["deflection"];
  EXPECT_EQ(d["scale"].get<double>(), scale);
  EXPECT_EQ(d["converged"], true);
  ASSERT_EQ(d["poses"].size(), loaded["bodies"].size());
  double largest = 0;
  for (std::size_t b = 0; b < loaded["bodies"].size(); ++b) {
    const Eigen::Vector3d p0 = Vec3(rigid["bodies"][b]["position"]), p1 = Vec3(loaded["bodies"][b]["position"]);
    const Eigen::Quaterniond q0 = SimulateQuaternion(rigid["bodies"][b]), q1 = SimulateQuaternion(loaded["bodies"][b]);
    // The rigid frame and the loaded equilibrium, as simulate prints them.
    EXPECT_LT((Vec3(scene["frames"]["poses"][0][b]) - p0).norm(), 1e-7) << b;
    EXPECT_LT((Vec3(d["loaded_poses"][b]) - p1).norm(), 1e-11) << b;
    EXPECT_LT(QuaternionGap(SceneQuaternion(d["loaded_poses"][b]), q1), 1e-11) << b;
    // Drawn: the displacement and the rotation from the rigid pose, times the scale.
    EXPECT_LT((Vec3(d["poses"][b]) - (p0 + scale * (p1 - p0))).norm(), 2e-7) << b;
    const Eigen::Quaterniond drawn = QuaternionExp(scale * QuaternionLog(q1 * q0.conjugate())) * q0;
    EXPECT_LT(QuaternionGap(SceneQuaternion(d["poses"][b]), drawn), 1e-6) << b;
    largest = std::max(largest, (p1 - p0).norm());
    EXPECT_GE(d["body_deflection"][b].get<double>(), (p1 - p0).norm() - 1e-11) << b;  // its origin among its points
  }
  EXPECT_GT(largest * scale, 0.05);  // visibly exaggerated: centimetres from under a millimetre
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(d["end_effector"][i].get<double>(), loaded["deflection"]["end_effector"][i].get<double>(), 1e-11);
  }
  EXPECT_NEAR(out["max_deflection_m"].get<double>(), d["max"].get<double>(), 1e-11);
  EXPECT_EQ(out["deflection_scale"].get<double>(), scale);
  EXPECT_EQ(out["source"], "controls");
}

TEST(ViewDeflection, ArmOnAMotorSpringAgainstItsClosedForm) {
  const Model model = LoadModelFromString(kArm, "arm.yaml");
  double theta = 0;  // k theta = m g L cos(theta), by fixed point
  for (int i = 0; i < 100; ++i) theta = 2 * model.gravity.norm() * 0.5 * std::cos(theta) / 500;
  SceneSummary summary;
  DeflectionRequest request;
  request.scale = 7;
  const json scene = json::parse(BuildScene(model, {}, "model", &summary, nullptr, nullptr, ColorBy::kBody, &request));
  const json& d = scene["deflection"];
  // The tip (1 m from the pivot) moves most: a chord 2 sin(theta / 2).
  EXPECT_NEAR(d["body_deflection"][0].get<double>(), 2 * std::sin(theta / 2), 1e-10);
  EXPECT_NEAR(summary.deflected->max_deflection_m, 2 * std::sin(theta / 2), 1e-10);
  // Drawn: the centre's displacement round the pivot, (0.5 cos - 0.5, 0, -0.5 sin), times 7.
  const Eigen::Vector3d rigid(0.5, 0, 1), loaded(0.5 * std::cos(theta), 0, 1 - 0.5 * std::sin(theta));
  EXPECT_LT((Vec3(d["poses"][0]) - (rigid + 7 * (loaded - rigid))).norm(), 2e-7);
  EXPECT_LT((Vec3(d["loaded_poses"][0]) - loaded).norm(), 1e-10);
  // and turned 7 theta about y.
  const Eigen::Quaterniond q = SceneQuaternion(d["poses"][0]);
  EXPECT_NEAR(2 * std::atan2(q.y(), q.w()), 7 * theta, 1e-6);
  EXPECT_NEAR(d["end_effector"][4].get<double>(), theta, 1e-10);
}

TEST(ViewDeflection, NoTraceWithoutTheFlag) {
  const std::string dir = ccma::testing::ScratchPath("viewer_deflection", "");
  ToolRun r = RunTool({"view", "--model=" + StewartPath(), "--out=" + dir + "plain.html"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(json::parse(r.out).contains("deflection_scale"));
  EXPECT_FALSE(DeflectionSceneOf(dir + "plain.html").contains("deflection"));
  // --controls alone: the rigid model assembled there, as simulate puts it.
  const std::string controls = "--controls=0,0.02,-0.01,0.03,0,0.01";
  r = RunTool({"view", "--model=" + StewartPath(), controls, "--out=" + dir + "controls.html"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["source"], "controls");
  const json scene = DeflectionSceneOf(dir + "controls.html");
  EXPECT_FALSE(scene.contains("deflection"));
  r = RunTool({"simulate", "--model=" + StewartPath(), controls});
  ASSERT_EQ(r.status, 0) << r.err;
  const json rigid = json::parse(r.out);
  for (std::size_t b = 0; b < rigid["bodies"].size(); ++b) {
    EXPECT_LT((Vec3(scene["frames"]["poses"][0][b]) - Vec3(rigid["bodies"][b]["position"])).norm(), 1e-7) << b;
  }
}

TEST(ViewDeflection, BadValuesAndFlagsExitTwo) {
  const std::string dir = ccma::testing::ScratchPath("viewer_deflection", "");
  const std::string page = "--out=" + dir + "bad.html";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--model=" + StewartPath(), "--deflection=0"}, "SCALE must be one number in (0, 1e6]"},
      {{"--model=" + StewartPath(), "--deflection=-3"}, "SCALE must be one number in (0, 1e6]"},
      {{"--model=" + StewartPath(), "--deflection=2e6"}, "SCALE must be one number in (0, 1e6]"},
      {{"--model=" + StewartPath(), "--deflection=1,2"}, "SCALE must be one number in (0, 1e6]"},
      {{"--model=" + StewartPath(), "--deflection=nan"}, "is not a finite number"},
      {{"--model=" + StewartPath(), "--deflection=inf"}, "is not a finite number"},
      {{"--model=" + ModelPath("4dof_reduced"), "--deflection=10"}, "has no stiffness keys"},
      {{"--model=" + StewartPath(), "--wrench=0,0,-10,0,0,0"}, "--wrench goes with --deflection"},
      {{"--model=" + StewartPath(), "--deflection=10", "--wrench=0,0,-10"}, "--wrench: 6 numbers"},
      {{"--model=" + StewartPath(), "--deflection=10", "--color_by=load"}, "not with --color_by=load"},
      {{"--model=" + StewartPath(), "--deflection=10", "--controls=1,2"}, "--controls:"},
      {{"--model=" + StewartPath(), "--deflection=10", "--workspace=" + dir + "map.csv"}, "for a static view"},
      {{"--model=" + StewartPath(), "--controls=0,0,0,0,0,0", "--trajectory=" + dir + "t.csv"}, "for a static view"},
  };
  for (const auto& [args, message] : cases) {
    std::vector<std::string> all = {"view"};
    all.insert(all.end(), args.begin(), args.end());
    all.push_back(page);
    const ToolRun r = RunTool(all);
    EXPECT_EQ(r.status, 2) << args.back() << "\n" << r.err;
    EXPECT_EQ(r.out, "") << args.back();
    EXPECT_NE(r.err.find(message), std::string::npos) << args.back() << ": " << r.err;
  }
}

}  // namespace
}  // namespace ccma::viewer
