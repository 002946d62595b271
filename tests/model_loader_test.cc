// The model-file contract (shared/model_format.md): what loads, what each
// body's local geometry becomes, and every rejection with its message.
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <algorithm>
#include <ctime>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "ccma/internal/constraint_set.h"
#include "ccma/limits.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "formats/closure_file.h"
#include "formats/obstacles_file.h"
#include "ccma/rotation.h"
#include "bundled_models.h"
#include "tests/model_text.h"
#include "tests/tool_run.h"

namespace ccma {
namespace model_loader_test {

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

std::string ErrorOf(const std::string& text) { return testing::LoadErrorOf(text); }

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
        Rejection{"unknown base type", "type: omni", "type: tracked", "unknown base type 'tracked' (known: omni, differential, legged)", 11},
        Rejection{"unknown actuation", "actuation: complete", "actuation: partial",
                  "unknown actuation 'partial'", 12},
        Rejection{"end-effector on unknown body", "body: arm", "body: hand", "unknown body 'hand'", 24},
        Rejection{"unknown end-effector component", "controlled: [x, y, z, yaw]",
                  "controlled: [x, y, z, spin]", "unknown component 'spin'", 26},
        Rejection{"component listed twice", "controlled: [x, y, z, yaw]",
                  "controlled: [x, y, x, yaw]", "listed twice", 26},
        Rejection{"misspelt mobile_bases", "mobile_bases:", "mobile_basis:",
                  "unknown key 'mobile_basis' (did you mean 'mobile_bases'?)", 9},
        Rejection{"body not connected to a base", "  - type: universal\n    between: [post, arm]\n"
                  "    point: [1, 2, 0.5]\n    axes: [[1, 0, 0], [0, 1, 0]]\n", "",
                  "body 'arm' is not connected", 6}),
    [](const auto& info) {
      std::string name = std::regex_replace(info.param.what, std::regex("[^A-Za-z0-9]"), "_");
      return name;
    });

// No mobile base and no actuated joint: no actuator (the joint that held
// base0 now holds the post on the ground).
TEST(ModelLoader, AModelNeedsAnActuator) {
  std::string text = Replace(kValid,
                             "mobile_bases:\n  - name: base0\n    type: omni\n"
                             "    actuation: complete\n    pose: [1, 2, 0.5]\n",
                             "mobile_bases: []\n");
  text = Replace(text, "between: [base0, post]", "between: [world, post]");
  EXPECT_EQ(ErrorOf(text).rfind("bad.yaml:9: mobile_bases: a model needs at least one actuator", 0), 0u)
      << ErrorOf(text);
  // The same with the revolute actuated: it loads, with one control.
  const std::string actuated = Replace(text, "axis: [0, 0, 2]", "axis: [0, 0, 2]\n    actuated: true");
  ASSERT_EQ(ErrorOf(actuated), "");
  const Model m = LoadModelFromString(actuated, "ok.yaml");
  EXPECT_EQ(m.num_bases(), 0);
  EXPECT_EQ(m.num_controls(), 1);
  EXPECT_EQ(m.joints[0].control, 0);
  EXPECT_EQ(m.joints[0].body_a, kWorld);
  EXPECT_EQ(m.joints[0].name, "joint0");
}

TEST(ModelLoader, UnreadableFile) {
  try {
    LoadModel("/nonexistent/dir/model.yaml");
    FAIL() << "accepted a missing file";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/model.yaml"), std::string::npos);
  }
  EXPECT_THROW(LoadModel(CCMA_MODELS_DIR), ModelError);  // a directory
}

// yaml-cpp keeps both pairs of a repeated key and a lookup takes the first:
// every repeat is an error naming both lines, in model, obstacles and
// closure files alike, at any depth, and a repeat through an alias too.
TEST(ModelLoader, RepeatedKeysNameBothLines) {
  EXPECT_EQ(ErrorOf(Replace(kValid, "name: tiny\n", "name: tiny\nname: other\n")),
            "bad.yaml:2: key 'name' given twice in one mapping (first at line 1); remove one");
  EXPECT_EQ(ErrorOf(Replace(kValid, "  - name: post\n", "  - name: post\n    name: pole\n")),
            "bad.yaml:5: key 'name' given twice in one mapping (first at line 4); remove one");
  const std::string obstacles = "obstacles:\n  - {type: cylinder, name: a, center: [3, 3], radius: 0.1, height: 1}\n";
  const std::string twice = ErrorOf(std::string(kValid) + obstacles + obstacles);
  EXPECT_NE(twice.find("key 'obstacles' given twice in one mapping"), std::string::npos) << twice;
  EXPECT_EQ(ErrorOf(Replace(kValid, "axis: [0, 0, 2]", "axis: [0, 0, 2]\n    axis: [1, 0, 0]")),
            "bad.yaml:19: key 'axis' given twice in one mapping (first at line 18); remove one");
  EXPECT_NE(ErrorOf(std::string(kValid) + "x-anchor: &a {k: 1, k: 2}\nx-alias: *a\n").find("key 'k' given twice"),
            std::string::npos);
  const std::string dir = ccma::testing::TestDir();
  std::ofstream(dir + "/twice_obstacles.yaml") << obstacles << obstacles;
  Model model = LoadModelFromString(kValid, "tiny.yaml");
  try {
    AddObstaclesFromFile(dir + "/twice_obstacles.yaml", &model);
    ADD_FAILURE() << "a repeated key was accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("twice_obstacles.yaml:3: key 'obstacles' given twice"), std::string::npos)
        << e.what();
  }
  try {
    ParseClosureFile("name_mot: [a]\nname_mot: [b]\n", "robot.closures.yaml");
    ADD_FAILURE() << "a repeated key was accepted";
  } catch (const ModelError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("robot.closures.yaml:2: key 'name_mot' given twice", 0), 0u) << e.what();
  }
}

// yaml-cpp quotes the offending byte in its own message ("unknown escape
// character: \x01"): it reaches the user escaped, one printable line (found
// by fuzzing the closure file).
TEST(ModelLoader, YamlParserMessagesArePrintable) {
  const std::string message = ErrorOf(Replace(kValid, "name: tiny", "name: \"a\\\x01" "b\""));
  EXPECT_EQ(message.rfind("bad.yaml:1: not valid YAML: unknown escape character: \\x01", 0), 0u) << message;
  for (const char c : message) EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f) << message;
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

// ------------------------------------------------------------------------
// Hostile input: every case is rejected with file:line: key: what, quickly,
// without a crash.

// A scratch directory of this test process, removed at exit.
class ScratchDir {
 public:
  ScratchDir() {
    path_ = std::filesystem::path(ccma::testing::TestDir()) /
            ("ccma_loader_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string File(const std::string& name) const { return (path_ / name).string(); }
  std::string path() const { return path_.string(); }

 private:
  static inline int counter_ = 0;
  std::filesystem::path path_;
};

// The error message of LoadModel(path), or "" when it loads; `seconds` is
// set to how long that took.
std::string FileErrorOf(const std::string& path, double* seconds = nullptr) {
  const auto start = std::chrono::steady_clock::now();
  std::string message;
  try {
    LoadModel(path);
  } catch (const ModelError& e) {
    message = e.what();
  }
  if (seconds != nullptr) {
    *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return message;
}

struct Hostile {
  std::string what;
  std::string from, to;  // the edit applied to kValid
  std::string expected;  // the message must contain this (file:line: key: what)
};

void PrintTo(const Hostile& h, std::ostream* os) { *os << h.what; }

class HostileModel : public ::testing::TestWithParam<Hostile> {};

TEST_P(HostileModel, IsRejectedWithFileLineKey) {
  const Hostile& h = GetParam();
  const std::string message = ErrorOf(Replace(kValid, h.from, h.to));
  EXPECT_NE(message.find(h.expected), std::string::npos)
      << h.what << "\n  got:      " << message << "\n  expected: " << h.expected;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
}

const std::string kRule = "must be 1-64 characters from [A-Za-z0-9_-]";

INSTANTIATE_TEST_SUITE_P(
    Names, HostileModel,
    ::testing::Values(
        Hostile{"space in model name", "name: tiny", "name: tiny model",
                "bad.yaml:1: name: 'tiny model' " + kRule},
        Hostile{"space in body name", "  - name: post\n", "  - name: a b\n",
                "bad.yaml:4: bodies[0].name: 'a b' " + kRule},
        Hostile{"quote in body name", "  - name: post\n", "  - name: a'b\n",
                "bad.yaml:4: bodies[0].name: 'a'b' " + kRule},
        Hostile{"code in base name", "  - name: base0\n",
                "  - name: \"'.system('touch X').'\"\n",
                "bad.yaml:10: mobile_bases[0].name: ''.system('touch X').'' " + kRule},
        Hostile{"unicode body name", "  - name: arm\n", "  - name: \"bra\u00e7o\"\n",
                "bad.yaml:6: bodies[1].name: 'bra\\xc3\\xa7o' " + kRule},
        Hostile{"newline in body name", "  - name: arm\n", "  - name: \"ar\\nm\"\n",
                "bad.yaml:6: bodies[1].name: 'ar\\x0am' " + kRule},
        Hostile{"nul in body name", "  - name: arm\n", "  - name: \"ar\\0m\"\n",
                "bad.yaml:6: bodies[1].name: 'ar\\x00m' " + kRule},
        Hostile{"65 characters", "name: tiny", "name: " + std::string(65, 'n'),
                "bad.yaml:1: name: '" + std::string(40, 'n') + "...' (65 bytes) " + kRule},
        Hostile{"empty name", "  - name: post\n", "  - name: ''\n",
                "bad.yaml:4: bodies[0].name: '' " + kRule},
        Hostile{"list as a name", "  - name: post\n", "  - name: [a]\n",
                "bad.yaml:4: bodies[0].name: must be a name of 1-64 characters"},
        Hostile{"bad joint name", "  - type: revolute\n", "  - name: j 0\n    type: revolute\n",
                "bad.yaml:15: joints[0].name: 'j 0' " + kRule},
        Hostile{"duplicate joint names", "    axis: [0, 0, 2]\n  - type: universal\n",
                "    axis: [0, 0, 2]\n    name: j\n  - name: j\n    type: universal\n",
                "bad.yaml:20: joints[1].name: duplicate joint name 'j' (first defined at "
                "bad.yaml:19)"},
        Hostile{"joint named like another's default name", "  - type: universal\n",
                "  - name: joint0\n    type: universal\n",
                "bad.yaml:19: joints[1].name: duplicate joint name 'joint0': it is the default "
                "name of the unnamed joints[0]"},
        Hostile{"world as a body", "  - name: post\n", "  - name: world\n",
                "bad.yaml:4: bodies[0].name: 'world' is reserved for the ground"},
        Hostile{"world as a base", "  - name: base0\n", "  - name: world\n",
                "bad.yaml:10: mobile_bases[0].name: 'world' is reserved for the ground"},
        Hostile{"long unknown body in between", "between: [post, arm]",
                "between: [post, " + std::string(5000, 'h') + "]",
                "bad.yaml:20: joints[1].between[1]: unknown body '" + std::string(40, 'h') +
                    "...' (5000 bytes)"}),
    [](const auto& info) {
      return std::regex_replace(info.param.what, std::regex("[^A-Za-z0-9]"), "_");
    });

INSTANTIATE_TEST_SUITE_P(
    Numbers, HostileModel,
    ::testing::Values(
        Hostile{"huge axis", "axis: [0, 0, 2]", "axis: [1e300, 1e300, 0]",
                "bad.yaml:18: joints[0].axis[0]: '1e300' must lie in [-10000, 10000] (unitless)"},
        Hostile{"tiny axis", "axis: [0, 0, 2]", "axis: [1e-200, 0, 0]",
                "bad.yaml:18: joints[0].axis: must not be the zero vector"},
        Hostile{"tiny universal axis", "axes: [[1, 0, 0], [0, 1, 0]]",
                "axes: [[1, 0, 0], [0, 1e-13, 0]]",
                "bad.yaml:22: joints[1].axes[1]: must not be the zero vector"},
        Hostile{"1e5 position", "position: [1, 2, 0.1]", "position: [1e5, 2, 0.1]",
                "bad.yaml:5: bodies[0].position[0]: '1e5' must lie in [-10000, 10000] (m)"},
        Hostile{"huge heading", "pose: [1, 2, 0.5]", "pose: [1, 2, -2e4]",
                "bad.yaml:13: mobile_bases[0].pose[2]: '-2e4' must lie in [-10000, 10000] (rad)"},
        Hostile{"huge rpy", "rpy: [0.1, 0.2, 0.3]", "rpy: [0.1, 1e308, 0.3]",
                "bad.yaml:8: bodies[1].rpy[1]: '1e308' must lie in [-10000, 10000] (rad)"},
        Hostile{"overflowing number", "point: [1, 2, 0.6]", "point: [1, 1e999, 0.6]",
                "bad.yaml:25: end_effector.point[1]:"},
        Hostile{"huge wheel radius", "    pose: [1, 2, 0.5]\n",
                "    pose: [1, 2, 0.5]\n    wheels:\n      - {angle: 0, distance: 0.1, radius: 1e9}\n",
                "bad.yaml:15: mobile_bases[0].wheels[0].radius: '1e9' must lie in "
                "[-10000, 10000] (m)"},
        Hostile{"cosine printed with %g", "axes: [[1, 0, 0], [0, 1, 0]]",
                "axes: [[1, 0, 0], [1e-5, 1, 0]]",
                "bad.yaml:22: joints[1].axes: the two axes must be perpendicular at home "
                "(cosine 1e-05)"},
        Hostile{"description too long", "description: one base, a post and an arm",
                "description: " + std::string(kMaxDescriptionLength + 1, 'd'),
                "bad.yaml:2: description: must be at most 4096 bytes, got 4097"},
        Hostile{"description a list", "description: one base, a post and an arm",
                "description: [a]", "bad.yaml:2: description: must be a string"},
        Hostile{"65 wheels", "    pose: [1, 2, 0.5]\n",
                [] {
                  std::string w = "    pose: [1, 2, 0.5]\n    wheels:\n";
                  for (int i = 0; i <= kMaxWheels; ++i) {
                    w += "      - {angle: " + std::to_string(i) + ", distance: 0.1, radius: 0.03}\n";
                  }
                  return w;
                }(),
                "bad.yaml:15: mobile_bases[0].wheels: 65 wheels; at most 64 are allowed"}),
    [](const auto& info) {
      return std::regex_replace(info.param.what, std::regex("[^A-Za-z0-9]"), "_");
    });

TEST(HostileModelText, NameOf20000CharactersIsRejectedWithoutCrash) {
  for (const std::string& key : {std::string("name: tiny"), std::string("  - name: post")}) {
    const std::string to = key.substr(0, key.size() - 4) + std::string(20000, 'x');
    const std::string message = ErrorOf(Replace(kValid, key, to));
    EXPECT_NE(message.find("'" + std::string(40, 'x') + "...' (20000 bytes) " + kRule),
              std::string::npos)
        << message;
    EXPECT_LT(message.size(), 200u) << "the message quotes only the start of the name";
  }
}

TEST(HostileModelText, SixtyFourCharactersAndEveryAllowedCharacterAreAccepted) {
  const std::string name = "Az09_-" + std::string(58, 'q');
  ASSERT_EQ(name.size(), kMaxNameLength);
  const std::string text = Replace(Replace(kValid, "name: tiny", "name: " + name),
                                   "  - type: revolute\n", "  - name: " + name + "\n    type: revolute\n");
  EXPECT_EQ(LoadModelFromString(text, "ok.yaml").name, name);
}

// Random names (fixed seed) from a mix of allowed and hostile bytes: the loader
// accepts exactly the names of 1-64 characters from [A-Za-z0-9_-].
TEST(HostileModelText, RandomNamesAgreeWithTheRule) {
  std::mt19937 random(20240611);
  const std::string alphabet =
      "abcXYZ019_-"
      " '\"\\:#[]{},&*!|>%@`\t.\x01\x7f\xc3\xa7";
  std::uniform_int_distribution<int> length(0, 70);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(alphabet.size()) - 1);
  std::bernoulli_distribution plain(0.9);
  int accepted = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::string name;
    const int n = length(random);
    for (int i = 0; i < n; ++i) name += alphabet[plain(random) ? pick(random) % 11 : pick(random)];
    bool valid = !name.empty() && name.size() <= kMaxNameLength && name != "post" &&
                 name != "base0" && name != "world";
    for (const char c : name) valid = valid && (std::isalnum(static_cast<unsigned char>(c)) != 0 ||
                                                c == '_' || c == '-');
    // Double-quoted YAML with every byte escaped: the loader sees `name` exactly.
    std::string quoted = "\"";
    for (const char c : name) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", static_cast<unsigned char>(c));
      quoted += escaped;
    }
    quoted += "\"";
    const std::string message = ErrorOf(Replace(kValid, "  - name: arm\n", "  - name: " + quoted + "\n"));
    // The end-effector and joint still say `arm`: a valid name fails later, on
    // "unknown body 'arm'", never on the name itself.
    const bool rejected_name = message.find("bad.yaml:6: bodies[1].name: ") != std::string::npos;
    EXPECT_EQ(rejected_name, !valid) << "name of " << name.size() << " bytes: " << message;
    if (valid) {
      ++accepted;
      EXPECT_NE(message.find("unknown body 'arm'"), std::string::npos) << message;
    }
  }
  EXPECT_GT(accepted, 10);
}

TEST(HostileModelText, AxesAreNormalisedWithoutOverflowOrUnderflow) {
  const Model big = LoadModelFromString(Replace(kValid, "axis: [0, 0, 2]", "axis: [1e4, 1e4, 0]"), "b.yaml");
  // a_B: the post's frame is the world's at home.
  EXPECT_NEAR((big.joints[0].a_B - Eigen::Vector3d(1, 1, 0).normalized()).norm(), 0, 1e-15);
  const Model small = LoadModelFromString(Replace(kValid, "axis: [0, 0, 2]", "axis: [0, 0, 1e-11]"), "s.yaml");
  EXPECT_NEAR(small.joints[0].a_A.norm(), 1.0, 1e-15);
  EXPECT_TRUE(small.joints[0].a_A.allFinite());
}

// Lists of `n` scalars: the count is checked before any entry is read.
std::string ScalarList(const std::string& key, int n) {
  std::string text = key + ":\n";
  text.reserve(text.size() + 4 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) text += "- 0\n";
  return text;
}

TEST(HostileModelText, CountsAreLimited) {
  const std::string bodies = ErrorOf(
      Replace(kValid, "bodies:\n", ScalarList("bodies", kMaxBodies + 1) + "old_bodies:\n"));
  EXPECT_NE(bodies.find("bad.yaml:4: bodies: 100001 bodies; at most 100000 are allowed"),
            std::string::npos)
      << bodies;
  const std::string joints = ErrorOf(
      Replace(kValid, "joints:\n", ScalarList("joints", kMaxJoints + 1) + "old_joints:\n"));
  EXPECT_NE(joints.find(": joints: 200001 joints; at most 200000 are allowed"), std::string::npos)
      << joints;
  // Bodies and bases together.
  std::string many = "name: many\nbodies:\n";
  for (int i = 0; i < kMaxBodies; ++i) many += "- {name: b" + std::to_string(i) + ", position: [0, 0, 0]}\n";
  many += "mobile_bases:\n- {name: base, actuation: complete, pose: [0, 0, 0]}\n";
  const std::string together = ErrorOf(many);
  EXPECT_NE(together.find("bad.yaml:" + std::to_string(kMaxBodies + 4) +
                          ": mobile_bases: 100000 bodies and 1 mobile bases; at most 100000 "
                          "together are allowed"),
            std::string::npos)
      << together;
}

// A chain of bodies, each hanging from the previous one: loads in linear time
// and without deep recursion.
// A chain of n spherical joints, as model text.
std::string ChainModelText(int n) {
  std::ostringstream text;
  text << "name: chain\nbodies:\n";
  for (int i = 0; i < n; ++i) text << "- {name: b" << i << ", position: [0, 0, 1]}\n";
  text << "mobile_bases:\n- {name: base, actuation: complete, pose: [0, 0, 0]}\njoints:\n";
  text << "- {type: spherical, between: [base, b0], point: [0, 0, 1]}\n";
  for (int i = 1; i < n; ++i) {
    text << "- {type: spherical, between: [b" << i - 1 << ", b" << i << "], point: [0, 0, 1]}\n";
  }
  text << "end_effector: {body: b" << n - 1 << ", point: [0, 0, 1], controlled: [x]}\n";
  return text.str();
}

// Processor seconds of this process (not wall time: other work on the
// machine does not change it much).
double CpuSecondsToLoad(const std::string& text, int expected_bodies) {
  const std::clock_t start = std::clock();
  const Model m = LoadModelFromString(text, "chain.yaml");
  const double seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  EXPECT_EQ(m.num_bodies(), expected_bodies);
  return seconds;
}

// Loading grows no faster than n log n: four times the bodies cost less than
// eight times the processor time (a quadratic step would cost sixteen).
TEST(HostileModelText, LongChainsLoadInLinearTime) {
  const int n = 4000;
  const double small = CpuSecondsToLoad(ChainModelText(n), n + 1);
  const double large = CpuSecondsToLoad(ChainModelText(4 * n), 4 * n + 1);
  EXPECT_LT(large, 8.0 * std::max(small, 0.01)) << "n=" << n << ": " << small << " s, 4n: " << large << " s";
}

TEST(HostileModelText, DeepFlowNestingIsRejected) {
  const std::string brackets = "name: tiny\nbodies: " + std::string(100000, '[') +
                               std::string(100000, ']') + "\n";
  EXPECT_NE(ErrorOf(brackets).find("bad.yaml:2: not valid YAML: nested more than 256 levels deep"),
            std::string::npos)
      << ErrorOf(brackets);
  std::string braces = "name: tiny\n\nbodies: ";
  for (int i = 0; i < 100000; ++i) braces += "{a: ";
  braces += "1" + std::string(100000, '}') + "\n";
  EXPECT_NE(ErrorOf(braces).find("bad.yaml:3: not valid YAML: nested more than 256 levels deep"),
            std::string::npos);
  // 256 levels are not refused by the depth check (yaml-cpp's own limit is higher).
  const std::string ok = "name: tiny\nbodies: " + std::string(256, '[') + std::string(256, ']') + "\n";
  EXPECT_EQ(ErrorOf(ok).find("nested"), std::string::npos) << ErrorOf(ok);
  // Brackets in comments do not count.
  const std::string comment = Replace(kValid, "bodies:\n", "bodies: # " + std::string(1000, '[') + "\n");
  EXPECT_EQ(ErrorOf(comment), "");
}

TEST(HostileModelText, DeepBlockNestingIsRejected) {
  // Block sequences on one line, 20000 levels.
  std::string dashes = "name: tiny\nbodies:\n";
  for (int i = 0; i < 20000; ++i) dashes += "- ";
  dashes += "x\n";
  const std::string dash_message = ErrorOf(dashes);
  EXPECT_NE(dash_message.find("bad.yaml:3: not valid YAML: nested too deeply"), std::string::npos)
      << dash_message;
  // An indented block map, 2000 levels (2 MB).
  std::string indented = "name: tiny\nbodies:\n";
  for (int i = 1; i <= 2000; ++i) indented += std::string(i, ' ') + "a:\n";
  indented += std::string(2001, ' ') + "1\n";
  const std::string indent_message = ErrorOf(indented);
  EXPECT_NE(indent_message.find("not valid YAML: nested too deeply"), std::string::npos)
      << indent_message;
  // Complex keys, 20000 levels.
  std::string keys = "name: tiny\nbodies:\n";
  for (int i = 0; i < 20000; ++i) keys += "? ";
  keys += "x\n";
  EXPECT_NE(ErrorOf(keys).find("not valid YAML: nested too deeply"), std::string::npos);
}

TEST(HostileModelText, TextOverTheSizeLimitIsRejected) {
  const std::string text = Replace(kValid, "description: one base, a post and an arm",
                                   "# " + std::string(kMaxModelFileBytes, 'c'));
  EXPECT_EQ(ErrorOf(text), "bad.yaml: larger than 4 MiB (the limit for a model file)");
}

TEST(HostileModelFile, DevZeroIsRejectedAtOnce) {
  double seconds = 0;
  const std::string message = FileErrorOf("/dev/zero", &seconds);
  EXPECT_EQ(message, "/dev/zero: not a regular file");
  EXPECT_LT(seconds, 1.0 * ccma::testing::kTestTimeFactor);
}

TEST(HostileModelFile, DirectoryIsRejected) {
  const ScratchDir dir;
  EXPECT_EQ(FileErrorOf(dir.path()), dir.path() + ": not a regular file (a directory)");
}

TEST(HostileModelFile, FifoIsRejectedWithoutBlocking) {
  const ScratchDir dir;
  const std::string fifo = dir.File("model.yaml");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  double seconds = 0;
  EXPECT_EQ(FileErrorOf(fifo, &seconds), fifo + ": not a regular file");
  EXPECT_LT(seconds, 1.0 * ccma::testing::kTestTimeFactor);
}

TEST(HostileModelFile, SymlinksAreFollowed) {
  const ScratchDir dir;
  const std::string to_model = dir.File("model.yaml");
  const std::string to_zero = dir.File("zero.yaml");
  std::filesystem::create_symlink(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml", to_model);
  std::filesystem::create_symlink("/dev/zero", to_zero);
  EXPECT_EQ(LoadModel(to_model).name, "4dof_reduced");
  EXPECT_EQ(FileErrorOf(to_zero), to_zero + ": not a regular file");
}

TEST(HostileModelFile, MissingFileNamesThePath) {
  EXPECT_EQ(FileErrorOf("/nonexistent/dir/model.yaml"),
            "/nonexistent/dir/model.yaml: cannot open the model file (no such file)");
}

TEST(HostileModelFile, FileOverTheSizeLimitIsRejected) {
  const ScratchDir dir;
  const std::string big = dir.File("big.yaml");
  {
    std::ofstream out(big, std::ios::binary);
    out << kValid << "# ";
    const std::string chunk(1 << 20, 'c');
    for (int i = 0; i < 5; ++i) out << chunk;
  }
  double seconds = 0;
  EXPECT_EQ(FileErrorOf(big, &seconds), big + ": larger than 4 MiB (the limit for a model file)");
  EXPECT_LT(seconds, 1.0 * ccma::testing::kTestTimeFactor);
  // Exactly the limit still loads.
  std::string text = std::string(kValid) + "#";
  text.resize(kMaxModelFileBytes, 'c');
  std::ofstream(big, std::ios::binary | std::ios::trunc) << text;
  ASSERT_EQ(std::filesystem::file_size(big), kMaxModelFileBytes);
  EXPECT_EQ(FileErrorOf(big), "");
}

// Everything a model holds, exactly (no tolerance).
void ExpectIdentical(const Model& a, const Model& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  ASSERT_EQ(a.num_bodies(), b.num_bodies());
  for (int i = 0; i < a.num_bodies(); ++i) {
    EXPECT_EQ(a.bodies[i].name, b.bodies[i].name);
    EXPECT_EQ(a.bodies[i].R_WB_home, b.bodies[i].R_WB_home);
    EXPECT_EQ(a.bodies[i].p_WB_home, b.bodies[i].p_WB_home);
    EXPECT_EQ(a.bodies[i].base_index, b.bodies[i].base_index);
  }
  ASSERT_EQ(a.num_bases(), b.num_bases());
  for (int k = 0; k < a.num_bases(); ++k) {
    EXPECT_EQ(a.mobile_bases[k].name, b.mobile_bases[k].name);
    EXPECT_EQ(a.mobile_bases[k].body, b.mobile_bases[k].body);
    EXPECT_EQ(a.mobile_bases[k].actuation, b.mobile_bases[k].actuation);
    EXPECT_EQ(a.mobile_bases[k].home_pose, b.mobile_bases[k].home_pose);
    ASSERT_EQ(a.mobile_bases[k].wheels.size(), b.mobile_bases[k].wheels.size());
    for (std::size_t w = 0; w < a.mobile_bases[k].wheels.size(); ++w) {
      const Wheel& x = a.mobile_bases[k].wheels[w];
      const Wheel& y = b.mobile_bases[k].wheels[w];
      EXPECT_EQ(x.angle, y.angle);
      EXPECT_EQ(x.distance, y.distance);
      EXPECT_EQ(x.radius, y.radius);
      EXPECT_EQ(x.mounting, y.mounting);
      EXPECT_EQ(x.roller, y.roller);
    }
  }
  ASSERT_EQ(a.joints.size(), b.joints.size());
  for (std::size_t j = 0; j < a.joints.size(); ++j) {
    const Joint& x = a.joints[j];
    const Joint& y = b.joints[j];
    EXPECT_EQ(x.type, y.type);
    EXPECT_EQ(x.body_a, y.body_a);
    EXPECT_EQ(x.body_b, y.body_b);
    EXPECT_EQ(x.p_A, y.p_A);
    EXPECT_EQ(x.p_B, y.p_B);
    if (x.type != JointType::kSpherical) {
      EXPECT_EQ(x.a_A, y.a_A);
      EXPECT_EQ(x.a_B, y.a_B);
      EXPECT_EQ(x.b_B, y.b_B);
    }
    EXPECT_EQ(x.line, y.line);
  }
  EXPECT_EQ(a.end_effector.body, b.end_effector.body);
  EXPECT_EQ(a.end_effector.p_B, b.end_effector.p_B);
  EXPECT_EQ(a.end_effector.p_W_home, b.end_effector.p_W_home);
  EXPECT_EQ(a.end_effector.controlled, b.end_effector.controlled);
}

TEST(HostileModelText, ValidModelsStillLoadIdentically) {
  // The tiny model: every number as it was written; axes normalised as before.
  const Model m = LoadModelFromString(kValid, "tiny.yaml");
  EXPECT_EQ(m.joints[0].a_A, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(m.joints[1].a_A, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(m.mobile_bases[0].home_pose, Eigen::Vector3d(1, 2, 0.5));
  EXPECT_EQ(m.bodies[0].p_WB_home, Eigen::Vector3d(1, 2, 0.1));
  EXPECT_EQ(m.description, "one base, a post and an arm");
  // Named joints, wheels and the loaded file equal the text in memory.
  const std::string named = Replace(
      Replace(kValid, "  - type: revolute\n", "  - name: yaw-0\n    type: revolute\n"),
      "    pose: [1, 2, 0.5]\n",
      "    pose: [1, 2, 0.5]\n    wheels:\n"
      "      - {angle: 0, distance: 0.1, radius: 0.03}\n"
      "      - {angle: 2.0944, distance: 0.1, radius: 0.03, mounting: 0.1, roller: 0.7}\n"
      "      - {angle: 4.1888, distance: 0.1, radius: 0.03}\n");
  const Model with_names = LoadModelFromString(named, "named.yaml");
  ASSERT_EQ(with_names.mobile_bases[0].wheels.size(), 3u);
  EXPECT_EQ(with_names.mobile_bases[0].wheels[1].roller, 0.7);
  const ScratchDir dir;
  std::ofstream(dir.File("named.yaml")) << named;
  ExpectIdentical(LoadModel(dir.File("named.yaml")), with_names);
  // Every reference model: from its file and from its text, the same.
  for (const char* name : {"4dof_reduced", "4dof_complete", "6dof_symmetric", "6dof_asymmetric",
                           "6dof_six_agents"}) {
    const std::string path = std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml";
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    ExpectIdentical(LoadModel(path), LoadModelFromString(text.str(), path));
  }
}


// ------------------------------------------------------------------------
// Misspelt keys: an unknown key close to a known one is an error that names
// it and suggests the known key, checked before anything else in its mapping.

struct Misspelling {
  std::string what;
  std::string from, to;  // the edit applied to kValid
  std::string expected;  // the whole message
};

void PrintTo(const Misspelling& m, std::ostream* os) { *os << m.what; }

class MisspeltKey : public ::testing::TestWithParam<Misspelling> {};

TEST_P(MisspeltKey, IsAnUnknownKeyWithASuggestion) {
  const Misspelling& m = GetParam();
  EXPECT_EQ(ErrorOf(Replace(kValid, m.from, m.to)), m.expected) << m.what;
  // The same with warnings collected: still an error, not a warning.
  std::vector<std::string> warnings;
  EXPECT_THROW(LoadModelFromString(Replace(kValid, m.from, m.to), "bad.yaml", &warnings), ModelError);
}

INSTANTIATE_TEST_SUITE_P(
    EverySection, MisspeltKey,
    ::testing::Values(
        Misspelling{"between in a joint", "    between: [post, arm]", "    betwen: [post, arm]",
                    "bad.yaml:20: joints[1]: unknown key 'betwen' (did you mean 'between'?)"},
        Misspelling{"top level", "mobile_bases:", "mobile_basis:",
                    "bad.yaml:9: unknown key 'mobile_basis' (did you mean 'mobile_bases'?)"},
        Misspelling{"position in a body", "    position: [1, 2, 0.1]", "    positon: [1, 2, 0.1]",
                    "bad.yaml:5: bodies[0]: unknown key 'positon' (did you mean 'position'?)"},
        Misspelling{"swapped letters", "  - type: revolute", "  - tpye: revolute",
                    "bad.yaml:15: joints[0]: unknown key 'tpye' (did you mean 'type'?)"},
        Misspelling{"a tie lists both", "    axis: [0, 0, 2]", "    axs: [0, 0, 2]",
                    "bad.yaml:18: joints[0]: unknown key 'axs' (did you mean 'axes' or 'axis'?)"},
        Misspelling{"an optional key", "    rpy: [0.1, 0.2, 0.3]", "    rpx: [0.1, 0.2, 0.3]",
                    "bad.yaml:8: bodies[1]: unknown key 'rpx' (did you mean 'rpy'?)"},
        Misspelling{"optional actuated", "    axis: [0, 0, 2]", "    axis: [0, 0, 2]\n    acutated: true",
                    "bad.yaml:19: joints[0]: unknown key 'acutated' (did you mean 'actuated'?)"},
        Misspelling{"a base", "    pose: [1, 2, 0.5]", "    Pose: [1, 2, 0.5]",
                    "bad.yaml:13: mobile_bases[0]: unknown key 'Pose' (did you mean 'pose'?)"},
        Misspelling{"a wheel", "    pose: [1, 2, 0.5]",
                    "    pose: [1, 2, 0.5]\n    wheels:\n      - {angle: 0, distance: 0.1, raduis: 0.03}",
                    "bad.yaml:15: mobile_bases[0].wheels[0]: unknown key 'raduis' (did you mean 'radius'?)"},
        Misspelling{"the end-effector", "  controlled: [x, y, z, yaw]", "  controled: [x, y, z, yaw]",
                    "bad.yaml:26: end_effector: unknown key 'controled' (did you mean 'controlled'?)"},
        // Checked first: before the joint's (also wrong) type and name.
        Misspelling{"before other errors", "  - type: universal\n    between:",
                    "  - type: helical\n    name: a b\n    betwen:",
                    "bad.yaml:21: joints[1]: unknown key 'betwen' (did you mean 'between'?)"},
        Misspelling{"hostile text is quoted", "    between: [post, arm]", "    \"betw\\ten\": [post, arm]",
                    "bad.yaml:20: joints[1]: unknown key 'betw\\x09en' (did you mean 'between'?)"}),
    [](const auto& info) { return std::regex_replace(info.param.what, std::regex("[^A-Za-z0-9]"), "_"); });

// Keys far from every known key stay warnings (the format may be extended),
// also short ones two edits away ("note" is not "name"), and long ones.
TEST(ModelLoader, KeysFarFromKnownOnesStayWarnings) {
  std::vector<std::string> warnings;
  const std::string text = Replace(Replace(kValid, "  - name: arm\n", "  - name: arm\n    note: the forearm\n"),
                                   "name: tiny\n", "name: tiny\n" + std::string(1000, 'k') + ": 1\n");
  const auto start = std::chrono::steady_clock::now();
  const Model m = LoadModelFromString(text, "w.yaml", &warnings);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_EQ(m.bodies[1].name, "arm");
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0].rfind("w.yaml:2: " + std::string(40, 'k') + "...: unknown key, ignored", 0), 0u)
      << warnings[0];
  EXPECT_EQ(warnings[1], "w.yaml:8: bodies[1].note: unknown key, ignored");
}

// ------------------------------------------------------------------------
// Implausible magnitudes: warnings, and the model still loads unchanged.

std::vector<std::string> WarningsOf(const std::string& text) {
  std::vector<std::string> warnings;
  LoadModelFromString(text, "w.yaml", &warnings);
  return warnings;
}

// kValid written in millimetres: every length times 1000.
std::string InMillimetres() {
  std::string text = kValid;
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"position: [1, 2, 0.1]", "position: [1000, 2000, 100]"},
           {"position: [1, 2, 0.5]", "position: [1000, 2000, 500]"},
           {"pose: [1, 2, 0.5]", "pose: [1000, 2000, 0.5]"},
           {"point: [1, 2, 0.1]", "point: [1000, 2000, 100]"},
           {"point: [1, 2, 0.5]", "point: [1000, 2000, 500]"},
           {"point: [1, 2, 0.6]", "point: [1000, 2000, 600]"}}) {
    text = Replace(text, from, to);
  }
  return text;
}

TEST(ImplausibleMagnitudes, AModelInMillimetresWarnsOnceAndStillLoads) {
  std::vector<std::string> warnings;
  const Model m = LoadModelFromString(InMillimetres(), "w.yaml", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  // The first length above 100 m, and how many there are: 2 + 3 in the bodies,
  // 2 in the pose, 2 + 3 in the joint points, 3 in the end-effector point.
  EXPECT_EQ(warnings[0],
            "w.yaml:5: bodies[0].position[0]: 1000 m is implausible for a mobile mechanism; "
            "are the lengths in millimetres? (15 lengths above 100 m)");
  EXPECT_EQ(m.bodies[1].p_WB_home, Eigen::Vector3d(1000, 2000, 500));
  EXPECT_EQ(m.mobile_bases[0].home_pose, Eigen::Vector3d(1000, 2000, 0.5));
}

TEST(ImplausibleMagnitudes, AHeadingInDegreesWarns) {
  const std::vector<std::string> warnings = WarningsOf(Replace(kValid, "pose: [1, 2, 0.5]", "pose: [1, 2, 90]"));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "w.yaml:13: mobile_bases[0].pose[2]: 90 rad is more than a full turn; is the angle in degrees? "
            "(1 angle above 2 pi)");
}

TEST(ImplausibleMagnitudes, AnglesInDegreesAndMillimetresWarnOncePerKind) {
  std::string text = Replace(InMillimetres(), "rpy: [0.1, 0.2, 0.3]", "rpy: [0, -45, 30]");
  text = Replace(text, "axis: [0, 0, 2]", "axis: [0, 0, 2]\n    limits: [-90, 90]");
  const std::vector<std::string> warnings = WarningsOf(text);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0].rfind("w.yaml:5: bodies[0].position[0]: 1000 m is implausible", 0), 0u) << warnings[0];
  EXPECT_EQ(warnings[1],
            "w.yaml:8: bodies[1].rpy[1]: -45 rad is more than a full turn; is the angle in degrees? "
            "(4 angles above 2 pi)");
}

TEST(ImplausibleMagnitudes, ThresholdsAre100MetresAndAFullTurn) {
  EXPECT_TRUE(WarningsOf(Replace(kValid, "position: [1, 2, 0.1]", "position: [100, -100, 0.1]")).empty());
  EXPECT_EQ(WarningsOf(Replace(kValid, "position: [1, 2, 0.1]", "position: [1, -100.5, 0.1]")).size(), 1u);
  EXPECT_TRUE(WarningsOf(Replace(kValid, "pose: [1, 2, 0.5]", "pose: [1, 2, -6.2832]")).empty());
  EXPECT_EQ(WarningsOf(Replace(kValid, "pose: [1, 2, 0.5]", "pose: [1, 2, -6.3]")).size(), 1u);
  // Axes have no unit: any length is fine.
  EXPECT_TRUE(WarningsOf(Replace(kValid, "axis: [0, 0, 2]", "axis: [0, 0, 2000]")).empty());
  // A rejected model reports its error only.
  std::vector<std::string> warnings;
  EXPECT_THROW(LoadModelFromString(Replace(InMillimetres(), "body: arm", "body: hand"), "w.yaml", &warnings),
               ModelError);
  EXPECT_TRUE(warnings.empty());
}

TEST(ImplausibleMagnitudes, NoBundledOrGeneratedModelWarns) {
  std::vector<std::string> paths = {std::string(CCMA_MODELS_DIR) + "/../examples/my_first_mechanism.yaml"};
  for (const std::string& name : testing::BundledModels()) {
    paths.push_back(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
  }
  ASSERT_GE(paths.size(), 10u);
  for (const std::string& path : paths) {
    std::vector<std::string> warnings;
    LoadModel(path, &warnings);
    EXPECT_TRUE(warnings.empty()) << path << ": " << (warnings.empty() ? "" : warnings[0]);
  }
  for (const int agents : {3, 6, 12, 64}) {
    StewartOptions options;
    options.agents = agents;
    std::vector<std::string> warnings;
    LoadModelFromString(GenerateStewartModel(options), "generated", &warnings);
    if (agents >= 6) LoadModelFromString(GenerateStewartGoughModel(options), "generated", &warnings);
    EXPECT_TRUE(warnings.empty()) << agents << ": " << (warnings.empty() ? "" : warnings[0]);
  }
}

}  // namespace
}  // namespace ccma
