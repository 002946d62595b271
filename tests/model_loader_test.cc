// The model-file contract (shared/model_format.md): what loads, what each
// body's local geometry becomes, and every rejection with its message.
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "ccma/constraint_set.h"
#include "ccma/model_loader.h"
#include "ccma/rotation.h"

namespace ccma {
namespace {

// A small valid model; tests replace one line to break it.
const char kValid[] = R"(name: tiny
description: one base, a post and an arm
bodies:
  - name: post
    position: [1, 2, 0.1]
  - name: arm
    position: [1, 2, 0.5]
    rpy: [0.1, 0.2, 0.3]
mobile_bases:
  - name: base0
    type: omni
    actuation: complete
    pose: [1, 2, 0.5]
joints:
  - type: revolute
    between: [base0, post]
    point: [1, 2, 0.1]
    axis: [0, 0, 2]
  - type: universal
    between: [post, arm]
    point: [1, 2, 0.5]
    axes: [[1, 0, 0], [0, 1, 0]]
end_effector:
  body: arm
  point: [1, 2, 0.6]
  controlled: [x, y, z, yaw]
)";

std::string Replace(const std::string& text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the model";
  std::string out = text;
  out.replace(at, from.size(), to);
  return out;
}

// The error message for `text`, or "" when it loads.
std::string ErrorOf(const std::string& text) {
  try {
    LoadModelFromString(text, "bad.yaml");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

TEST(ModelLoader, LoadsTheValidModel) {
  std::vector<std::string> warnings;
  const Model m = LoadModelFromString(kValid, "tiny.yaml", &warnings);
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(m.name, "tiny");
  ASSERT_EQ(m.num_bodies(), 3);  // post, arm, base0
  EXPECT_EQ(m.bodies[2].name, "base0");
  EXPECT_TRUE(m.bodies[2].is_mobile_base());
  EXPECT_EQ(m.state_size(), 18);
  EXPECT_EQ(m.num_controls(), 3);
  EXPECT_EQ(m.effective_control_indices().size(), 3u);
  EXPECT_EQ(m.num_constraints(), 6 + 4 + 9);
  // Axes are normalised; points become body-local.
  const Joint& rev = m.joints[0];
  EXPECT_NEAR(rev.a_A.norm(), 1.0, 1e-15);
  // base0 sits at (1, 2, 0) with heading 0.5: the point (1, 2, 0.1) is at
  // (0, 0, 0.1) in its frame whatever the heading.
  EXPECT_NEAR((rev.p_A - Eigen::Vector3d(0, 0, 0.1)).norm(), 0.0, 1e-15);
  // The arm is rotated by rpy: its local point maps back to the world point.
  const Joint& uni = m.joints[1];
  const Eigen::Matrix3d R_arm = RotationFromRpy({0.1, 0.2, 0.3});
  EXPECT_NEAR((R_arm * uni.b_B - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((R_arm * m.end_effector.p_B + m.bodies[1].p_WB_home -
               Eigen::Vector3d(1, 2, 0.6)).norm(), 0.0, 1e-15);
  EXPECT_TRUE(m.end_effector.controlled[kYaw]);
  EXPECT_FALSE(m.end_effector.controlled[kRoll]);
  // Assembled at home by construction.
  const ConstraintSet constraints(m);
  EXPECT_LT(constraints.Energy(State::Home(m), m.home_controls()), 1e-30);
}

TEST(ModelLoader, AcceptsJson) {
  const char json[] = R"({"name": "j", "bodies": [{"name": "ee", "position": [0, 0, 0.2]}],
    "mobile_bases": [{"name": "b", "actuation": "reduced", "pose": [0, 0, 0]}],
    "joints": [{"type": "spherical", "between": ["b", "ee"], "point": [0, 0, 0.2]}],
    "end_effector": {"body": "ee", "point": [0, 0, 0.2], "controlled": ["x"]}})";
  const Model m = LoadModelFromString(json, "j.json");
  EXPECT_EQ(m.mobile_bases[0].actuation, Actuation::kReduced);
  EXPECT_EQ(m.effective_control_indices().size(), 2u);
}

TEST(ModelLoader, WarnsAboutUnknownKeysWithoutRejecting) {
  std::vector<std::string> warnings;
  LoadModelFromString(Replace(kValid, "name: tiny\n", "name: tiny\ncolour: red\n"), "w.yaml",
                      &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("colour"), std::string::npos);
  EXPECT_NE(warnings[0].find("w.yaml:2"), std::string::npos);
}

struct Rejection {
  std::string what;
  std::string from, to;      // the edit applied to kValid
  std::string must_contain;  // key or name the message must name
  int line;                  // line the message must name (0: none)
};

void PrintTo(const Rejection& r, std::ostream* os) { *os << r.what; }

class ModelRejection : public ::testing::TestWithParam<Rejection> {};

TEST_P(ModelRejection, NamesFileLineAndKey) {
  const Rejection& r = GetParam();
  const std::string message = ErrorOf(Replace(kValid, r.from, r.to));
  ASSERT_FALSE(message.empty()) << r.what << ": was accepted";
  EXPECT_EQ(message.rfind("bad.yaml", 0), 0u) << message;
  EXPECT_NE(message.find(r.must_contain), std::string::npos) << r.what << ": " << message;
  if (r.line > 0) {
    EXPECT_NE(message.find("bad.yaml:" + std::to_string(r.line) + ":"), std::string::npos)
        << r.what << ": " << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryListedRejection, ModelRejection,
    ::testing::Values(
        Rejection{"not YAML", "bodies:\n", "bodies: [unclosed\n", "not valid YAML", 0},
        Rejection{"top level not a map", "name: tiny\n", "- a\n- b\nname: tiny\n", "", 0},
        Rejection{"missing name", "name: tiny\n", "", "name", 0},
        Rejection{"bad name", "name: tiny", "name: tiny model", "name", 1},
        Rejection{"missing end_effector", "end_effector:\n  body: arm\n  point: [1, 2, 0.6]\n"
                  "  controlled: [x, y, z, yaw]\n", "", "end_effector", 0},
        Rejection{"missing joints", "joints:", "joints_typo:", "joints", 0},
        Rejection{"missing mobile_bases", "mobile_bases:", "mobile_basis:", "mobile_bases", 0},
        Rejection{"missing position", "    position: [1, 2, 0.1]\n", "", "bodies[0].position", 4},
        Rejection{"missing pose", "    pose: [1, 2, 0.5]\n", "", "mobile_bases[0].pose", 10},
        Rejection{"missing actuation", "    actuation: complete\n", "", "actuation", 10},
        Rejection{"missing axis", "    axis: [0, 0, 2]\n", "", "joints[0].axis", 15},
        Rejection{"missing point", "    point: [1, 2, 0.1]\n", "", "joints[0].point", 15},
        Rejection{"wrong type: position a string", "position: [1, 2, 0.1]", "position: up",
                  "bodies[0].position", 5},
        Rejection{"wrong length", "position: [1, 2, 0.1]", "position: [1, 2]",
                  "bodies[0].position", 5},
        Rejection{"not a number", "pose: [1, 2, 0.5]", "pose: [1, two, 0.5]",
                  "mobile_bases[0].pose[1]", 13},
        Rejection{"bodies not a list", "bodies:\n", "bodies: 3\nold_bodies:\n", "bodies", 3},
        Rejection{"non-finite number", "point: [1, 2, 0.6]", "point: [1, .nan, 0.6]",
                  "end_effector.point[1]", 25},
        Rejection{"infinite number", "rpy: [0.1, 0.2, 0.3]", "rpy: [0.1, .inf, 0.3]",
                  "bodies[1].rpy[1]", 8},
        Rejection{"duplicate body name", "  - name: arm\n", "  - name: post\n", "duplicate name 'post'", 6},
        Rejection{"base named like a body", "  - name: base0\n", "  - name: arm\n",
                  "duplicate name 'arm'", 10},
        Rejection{"unknown body in joint", "between: [post, arm]", "between: [post, hand]",
                  "unknown body 'hand'", 20},
        Rejection{"same body twice", "between: [post, arm]", "between: [arm, arm]",
                  "same body 'arm' twice", 20},
        Rejection{"between of one name", "between: [post, arm]", "between: [post]",
                  "joints[1].between", 20},
        Rejection{"zero axis", "axis: [0, 0, 2]", "axis: [0, 0, 0]", "joints[0].axis", 18},
        Rejection{"zero universal axis", "axes: [[1, 0, 0], [0, 1, 0]]",
                  "axes: [[1, 0, 0], [0, 0, 0]]", "joints[1].axes[1]", 22},
        Rejection{"universal axes not perpendicular", "axes: [[1, 0, 0], [0, 1, 0]]",
                  "axes: [[1, 0, 0], [0.1, 1, 0]]", "perpendicular", 22},
        Rejection{"unknown joint type", "type: universal", "type: helical", "unknown joint type 'helical'", 19},
        Rejection{"unknown base type", "type: omni", "type: legged", "unknown base type 'legged'", 11},
        Rejection{"unknown actuation", "actuation: complete", "actuation: partial",
                  "unknown actuation 'partial'", 12},
        Rejection{"end-effector on unknown body", "body: arm", "body: hand", "unknown body 'hand'", 24},
        Rejection{"unknown end-effector component", "controlled: [x, y, z, yaw]",
                  "controlled: [x, y, z, spin]", "unknown component 'spin'", 26},
        Rejection{"component listed twice", "controlled: [x, y, z, yaw]",
                  "controlled: [x, y, x, yaw]", "listed twice", 26},
        Rejection{"no mobile base", "mobile_bases:\n  - name: base0\n    type: omni\n"
                  "    actuation: complete\n    pose: [1, 2, 0.5]\n", "mobile_bases: []\n",
                  "at least one mobile base", 9},
        Rejection{"body not connected to a base", "  - type: universal\n    between: [post, arm]\n"
                  "    point: [1, 2, 0.5]\n    axes: [[1, 0, 0], [0, 1, 0]]\n", "",
                  "body 'arm' is not connected", 6}),
    [](const auto& info) {
      std::string name = std::regex_replace(info.param.what, std::regex("[^A-Za-z0-9]"), "_");
      return name;
    });

TEST(ModelLoader, UnreadableFile) {
  try {
    LoadModel("/nonexistent/dir/model.yaml");
    FAIL() << "accepted a missing file";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/model.yaml"), std::string::npos);
  }
  EXPECT_THROW(LoadModel(CCMA_MODELS_DIR), ModelError);  // a directory
}

TEST(ModelLoader, EmptyFile) { EXPECT_NE(ErrorOf("").find("empty"), std::string::npos); }

TEST(ModelLoader, LoadsEveryReferenceModel) {
  for (const char* name : {"4dof_reduced", "4dof_complete", "6dof_symmetric", "6dof_asymmetric",
                           "6dof_six_agents"}) {
    std::vector<std::string> warnings;
    const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml", &warnings);
    EXPECT_EQ(m.name, name);
    EXPECT_TRUE(warnings.empty()) << name;
  }
}

}  // namespace
}  // namespace ccma
