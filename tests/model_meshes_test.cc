// The `meshes:` key of bodies and mobile bases (docs/model_format.md,
// "Visual meshes"): what it loads into Body::meshes (the mesh frame relative
// to the body frame), its defaults, and every rejection with its message.
#include <string>

#include <gtest/gtest.h>

#include "ccma/limits.h"
#include "ccma/rotation.h"
#include "formats/model_loader.h"
#include "tests/model_text.h"

namespace ccma {
namespace model_meshes_test {

// A grounded arm (body at a general pose) and an omni base; MESHES_ARM and
// MESHES_BASE are replaced by each test.
const char kModel[] = R"(name: meshy
bodies:
  - name: post
    position: [0, 0, 0.5]
  - name: arm
    position: [0.3, -0.2, 0.8]
    rpy: [0.4, -0.3, 1.1]
    MESHES_ARM
mobile_bases:
  - name: base0
    actuation: complete
    pose: [1, 2, 0.7]
    MESHES_BASE
joints:
  - {type: revolute, between: [world, post], point: [0, 0, 0], axis: [0, 0, 1], actuated: true}
  - {type: revolute, between: [post, arm], point: [0.3, -0.2, 0.8], axis: [0, 1, 0]}
  - {type: spherical, between: [base0, arm], point: [1, 2, 0.8]}
end_effector: {body: arm, point: [0.3, -0.2, 0.8], controlled: [x, y]}
)";

std::string With(const std::string& arm, const std::string& base = "") {
  std::string text = kModel;
  text.replace(text.find("MESHES_ARM"), 10, arm);
  text.replace(text.find("MESHES_BASE"), 11, base);
  return text;
}

std::string ErrorOf(const std::string& text) { return testing::LoadErrorOf(text); }

const Body& Named(const Model& m, const std::string& name) { return m.bodies[m.FindBody(name)]; }

TEST(ModelMeshes, NoMeshesByDefault) {
  const Model m = LoadModelFromString(With(""), "m.yaml");
  for (const Body& b : m.bodies) EXPECT_TRUE(b.meshes.empty()) << b.name;
}

TEST(ModelMeshes, PoseGivenInWorldIsStoredInTheBodyFrame) {
  const Model m = LoadModelFromString(
      With("meshes: [{file: meshes/arm.stl, position: [0.5, 0.1, 0.9], rpy: [-0.2, 0.7, 2.5], scale: [0.001, 0.002, 0.003]},\n"
           "             {file: /abs/other.stl}]"),
      "m.yaml");
  const Body& arm = Named(m, "arm");
  ASSERT_EQ(arm.meshes.size(), 2u);
  const BodyMesh& mesh = arm.meshes[0];
  EXPECT_EQ(mesh.file, "meshes/arm.stl");
  EXPECT_EQ(mesh.line, 8);
  // Composed back with the body's home pose, the mesh frame is where the file says.
  const Eigen::Matrix3d R_WM = arm.R_WB_home * mesh.R_BM;
  const Eigen::Vector3d p_WM = arm.p_WB_home + arm.R_WB_home * mesh.p_BM;
  EXPECT_LT((R_WM - RotationFromRpy(Eigen::Vector3d(-0.2, 0.7, 2.5))).norm(), 1e-14);
  EXPECT_LT((p_WM - Eigen::Vector3d(0.5, 0.1, 0.9)).norm(), 1e-14);
  // An independent number: the offset (0.2, 0.3, 0.1) in the body frame is R_WB^T times it.
  EXPECT_LT((mesh.p_BM - RotationFromRpy(Eigen::Vector3d(0.4, -0.3, 1.1)).transpose() *
                             Eigen::Vector3d(0.2, 0.3, 0.1)).norm(), 1e-14);
  EXPECT_EQ(mesh.scale, Eigen::Vector3d(0.001, 0.002, 0.003));
  // Defaults: the body's own frame, unit scale.
  const BodyMesh& plain = arm.meshes[1];
  EXPECT_EQ(plain.file, "/abs/other.stl");
  EXPECT_LT((plain.R_BM - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_LT(plain.p_BM.norm(), 1e-15);
  EXPECT_EQ(plain.scale, Eigen::Vector3d::Ones());
}

TEST(ModelMeshes, OnlyPositionOrOnlyRpyKeepsTheOtherFromTheBody) {
  const Model m = LoadModelFromString(
      With("meshes: [{file: a.stl, position: [0.3, -0.2, 1.8]}, {file: b.stl, rpy: [0, 0, 0]}]"), "m.yaml");
  const Body& arm = Named(m, "arm");
  ASSERT_EQ(arm.meshes.size(), 2u);
  EXPECT_LT((arm.meshes[0].R_BM - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_LT((arm.R_WB_home * arm.meshes[0].p_BM - Eigen::Vector3d(0, 0, 1)).norm(), 1e-14);
  EXPECT_LT(arm.meshes[1].p_BM.norm(), 1e-15);
  EXPECT_LT((arm.meshes[1].R_BM - arm.R_WB_home.transpose()).norm(), 1e-14);  // world-aligned mesh
}

TEST(ModelMeshes, MobileBasesCarryMeshesInTheirFrame) {
  // The base's frame: (1, 2, 0), turned 0.7 rad about z.
  const Model m = LoadModelFromString(
      With("", "meshes: [{file: base.stl}, {file: base.stl, position: [1, 3, 0.2], rpy: [0, 0, 0]}]"), "m.yaml");
  const Body& base = Named(m, "base0");
  ASSERT_TRUE(base.is_mobile_base());
  ASSERT_EQ(base.meshes.size(), 2u);
  EXPECT_LT(base.meshes[0].p_BM.norm(), 1e-15);
  EXPECT_LT((base.meshes[0].R_BM - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  // (0, 1, 0.2) from the base's origin in the world is (sin 0.7, cos 0.7, 0.2) in its frame.
  EXPECT_LT((base.meshes[1].p_BM - Eigen::Vector3d(std::sin(0.7), std::cos(0.7), 0.2)).norm(), 1e-14);
  EXPECT_LT((base.meshes[1].R_BM - RotationZ(-0.7)).norm(), 1e-14);
  EXPECT_TRUE(Named(m, "arm").meshes.empty());
}

TEST(ModelMeshes, BadEntriesNameFileLineAndKey) {
  const std::string long_name(kMaxMeshPathLength + 1, 'a');
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"meshes: a.stl", "bad.yaml:8: bodies[1].meshes: must be a list"},
      {"meshes: [a.stl]", "bad.yaml:8: bodies[1].meshes[0]: must be a mapping"},
      {"meshes: [{position: [0, 0, 0]}]", "bad.yaml:8: bodies[1].meshes[0].file: missing required key"},
      {"meshes: [{file: ''}]", "bad.yaml:8: bodies[1].meshes[0].file: must be a non-empty string"},
      {"meshes: [{file: [a.stl]}]", "bad.yaml:8: bodies[1].meshes[0].file: must be a non-empty string"},
      {"meshes: [{file: " + long_name + "}]", "bad.yaml:8: bodies[1].meshes[0].file: longer than 4096 bytes"},
      {"meshes: [{file: \"a\\0b.stl\"}]", "bad.yaml:8: bodies[1].meshes[0].file: contains a NUL character"},
      {"meshes: [{file: a.stl, position: [0, 0]}]", "bad.yaml:8: bodies[1].meshes[0].position: must be a list of 3 numbers"},
      {"meshes: [{file: a.stl, rpy: [0, x, 0]}]", "bad.yaml:8: bodies[1].meshes[0].rpy[1]: must be a number, got 'x'"},
      {"meshes: [{file: a.stl, position: [0, 0, 2e4]}]", "bad.yaml:8: bodies[1].meshes[0].position[2]: '2e4' must lie in"},
      {"meshes: [{file: a.stl, scale: [1, 0, 1]}]", "bad.yaml:8: bodies[1].meshes[0].scale[1]: must be positive"},
      {"meshes: [{file: a.stl, scale: [1, 1, -2]}]", "bad.yaml:8: bodies[1].meshes[0].scale[2]: must be positive"},
      {"meshes: [{file: a.stl, scale: [1, .nan, 1]}]", "bad.yaml:8: bodies[1].meshes[0].scale[1]: must be a finite number"},
      {"meshes: [{file: a.stl, scale: [1, 1]}]", "bad.yaml:8: bodies[1].meshes[0].scale: must be a list of 3 numbers"},
      {"meshes: [{file: a.stl, scael: [1, 1, 1]}]", "bad.yaml:8: bodies[1].meshes[0]: unknown key 'scael' (did you mean 'scale'?)"},
      {"meshs: [{file: a.stl}]", "bad.yaml:8: bodies[1]: unknown key 'meshs' (did you mean 'meshes'?)"},
  };
  for (const auto& [line, expected] : cases) {
    const std::string error = ErrorOf(With(line));
    EXPECT_EQ(error.rfind(expected, 0), 0u) << line << "\n  gave: " << error << "\n  want: " << expected;
  }
  const std::string base_error = ErrorOf(With("", "meshes: [{file: a.stl, scale: [0, 1, 1]}]"));
  EXPECT_EQ(base_error.rfind("bad.yaml:13: mobile_bases[0].meshes[0].scale[0]: must be positive", 0), 0u) << base_error;
}

TEST(ModelMeshes, UnknownKeyFarFromAnyIsAWarning) {
  std::vector<std::string> warnings;
  const Model m = LoadModelFromString(With("meshes: [{file: a.stl, colour: red}]"), "m.yaml", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "m.yaml:8: bodies[1].meshes[0].colour: unknown key, ignored");
  EXPECT_EQ(Named(m, "arm").meshes.size(), 1u);
}

std::string ManyMeshes(int n) {
  std::string list = "meshes: [";
  for (int i = 0; i < n; ++i) list += std::string(i ? ", " : "") + "{file: m" + std::to_string(i) + ".stl}";
  return list + "]";
}

TEST(ModelMeshes, CountsAreBoundedPerBodyAndPerModel) {
  EXPECT_EQ(Named(LoadModelFromString(With(ManyMeshes(kMaxMeshesPerBody)), "m.yaml"), "arm").meshes.size(),
            static_cast<size_t>(kMaxMeshesPerBody));
  const std::string per_body = ErrorOf(With(ManyMeshes(kMaxMeshesPerBody + 1)));
  EXPECT_EQ(per_body.rfind("bad.yaml:8: bodies[1].meshes: 65 meshes; at most 64", 0), 0u) << per_body;
  // kMaxMeshes / 64 + 1 bodies of 64 meshes each: the body past the total names itself.
  const int bodies = kMaxMeshes / kMaxMeshesPerBody + 1;
  std::string text = "name: many\nbodies:\n";
  for (int b = 0; b < bodies; ++b) {
    text += "  - {name: b" + std::to_string(b) + ", position: [0, 0, 0], " + ManyMeshes(kMaxMeshesPerBody) + "}\n";
  }
  const std::string total = ErrorOf(text);
  EXPECT_EQ(total.rfind("bad.yaml:" + std::to_string(2 + bodies) + ": bodies[" + std::to_string(bodies - 1) +
                            "].meshes: more than 10000 meshes in the model", 0),
            0u)
      << total.substr(0, 200);
}

}  // namespace
}  // namespace ccma
