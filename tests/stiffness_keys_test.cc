// The `stiffness` keys of model files (model_format.md, "Compliance"): what
// they load into, and every malformed value refused with file:line: key,
// through the loader and through the tool (exit 2, nothing on stdout).
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "tests/model_text.h"
#include "tool_run.h"
#include "tests/tool_run.h"

namespace ccma {
namespace stiffness_keys_test {

// Line 6: the base; line 8: the actuated revolute; line 9: the weld.
const char* const kText =
    "name: springs\n"                                                                                  // 1
    "bodies:\n"                                                                                        // 2
    "  - {name: hub, position: [0.1, 0, 0.5]}\n"                                                       // 3
    "  - {name: beam, position: [0.6, 0, 0.5]}\n"                                                      // 4
    "mobile_bases:\n"                                                                                  // 5
    "  - {name: base0, type: omni, actuation: complete, pose: [0, 0, 0]BASE}\n"                        // 6
    "joints:\n"                                                                                        // 7
    "  - {name: motor, type: revolute, actuated: true, between: [base0, hub], point: [0, 0, 0.5], axis: [0, 1, 0]MOTOR}\n"
    "  - {name: weld, type: fixed, between: [hub, beam], point: [0.3, 0, 0.5]WELD}\n"                  // 9
    "end_effector: {body: beam, point: [1, 0, 0.5], controlled: [x, y, z]}\n";                         // 10

std::string With(const std::string& base, const std::string& motor, const std::string& weld) {
  std::string text = kText;
  text.replace(text.find("BASE"), 4, base);
  text.replace(text.find("MOTOR"), 5, motor);
  text.replace(text.find("WELD"), 4, weld);
  return text;
}

std::string ErrorOf(const std::string& text) { return testing::LoadErrorOf(text); }

TEST(StiffnessKeys, LoadIntoTheModel) {
  const Model m = LoadModelFromString(
      With(", stiffness: [2.0e4, 3.0e4, 500]", ", stiffness: {axis: 1.0e3, translation: 1.0e7, rotation: [5.0e4, 6.0e4]}",
           ", stiffness: {rotation: [1, 2, 3]}"),
      "ok.yaml");
  EXPECT_EQ(m.mobile_bases[0].stiffness.k, Eigen::Vector3d(2e4, 3e4, 500));
  EXPECT_EQ(m.joints[0].stiffness.axis, 1e3);
  EXPECT_EQ(m.joints[0].stiffness.translation, (std::vector<double>{1e7, 1e7, 1e7}));
  EXPECT_EQ(m.joints[0].stiffness.rotation, (std::vector<double>{5e4, 6e4}));
  EXPECT_TRUE(m.joints[1].stiffness.translation.empty());
  EXPECT_EQ(m.joints[1].stiffness.rotation, (std::vector<double>{1, 2, 3}));
  EXPECT_TRUE(m.compliant());
  const Model motor_only = LoadModelFromString(With("", ", stiffness: 2.5e3", ""), "ok.yaml");
  EXPECT_EQ(motor_only.joints[0].stiffness.axis, 2.5e3);
  EXPECT_FALSE(LoadModelFromString(With("", "", ""), "ok.yaml").compliant());
}

// A legged base's `stiffness` is that of its x, y and heading, as a wheeled
// base's; its height, roll and pitch stay rigid.
TEST(StiffnessKeys, ALeggedBaseTakesTheWheeledBasesThree) {
  LeggedOptions options;
  const std::string text = testing::InsertAfterEach(GenerateLeggedModel(options), "    type: legged\n",
                                                    {"    stiffness: [2.0e4, 3.0e4, 500]\n"});
  const Model m = LoadModelFromString(text, "legged.yaml");
  EXPECT_EQ(m.mobile_bases[0].stiffness.k, Eigen::Vector3d(2e4, 3e4, 500));
  EXPECT_FALSE(m.mobile_bases[1].stiffness.given());
  EXPECT_TRUE(m.compliant());
  const std::string six = testing::InsertAfterEach(GenerateLeggedModel(options), "    type: legged\n",
                                                   {"    stiffness: [2.0e4, 3.0e4, 500, 1, 2, 3]\n"});
  EXPECT_NE(ErrorOf(six).find("must be a list of 3 positive numbers"), std::string::npos) << ErrorOf(six);
}

struct Bad {
  const char* base;
  const char* motor;
  const char* weld;
  const char* where;  // "bad.yaml:LINE: key"
  const char* what;
};

class StiffnessRejection : public ::testing::TestWithParam<Bad> {};

TEST_P(StiffnessRejection, NamesFileLineAndKey) {
  const Bad& b = GetParam();
  const std::string error = ErrorOf(With(b.base, b.motor, b.weld));
  EXPECT_EQ(error.rfind(b.where, 0), 0u) << error;
  EXPECT_NE(error.find(b.what), std::string::npos) << error;
}

INSTANTIATE_TEST_SUITE_P(
    EveryMalformedValue, StiffnessRejection,
    ::testing::Values(
        Bad{", stiffness: [1, 2]", "", "", "bad.yaml:6: mobile_bases[0].stiffness", "list of 3"},
        Bad{", stiffness: 5", "", "", "bad.yaml:6: mobile_bases[0].stiffness", "list of 3"},
        Bad{", stiffness: [1, 2, 0]", "", "", "bad.yaml:6: mobile_bases[0].stiffness[2]", "positive"},
        Bad{", stiffness: [-1, 2, 3]", "", "", "bad.yaml:6: mobile_bases[0].stiffness[0]", "positive"},
        Bad{", stiffness: [1, .nan, 3]", "", "", "bad.yaml:6: mobile_bases[0].stiffness[1]", "finite"},
        Bad{", stiffness: [1, 2, .inf]", "", "", "bad.yaml:6: mobile_bases[0].stiffness[2]", "finite"},
        Bad{", stiffness: [1, two, 3]", "", "", "bad.yaml:6: mobile_bases[0].stiffness[1]", "must be a number"},
        Bad{", stiffness: [1, 2, 1e30]", "", "", "bad.yaml:6: mobile_bases[0].stiffness[2]", "must lie in"},
        Bad{"", ", stiffness: 0", "", "bad.yaml:8: joints[0].stiffness", "positive"},
        Bad{"", ", stiffness: -3", "", "bad.yaml:8: joints[0].stiffness", "positive"},
        Bad{"", ", stiffness: .nan", "", "bad.yaml:8: joints[0].stiffness", "finite"},
        Bad{"", ", stiffness: soft", "", "bad.yaml:8: joints[0].stiffness", "must be a number"},
        Bad{"", ", stiffness: [1, 2]", "", "bad.yaml:8: joints[0].stiffness", "mapping"},
        Bad{"", ", stiffness: {}", "", "bad.yaml:8: joints[0].stiffness", "mapping"},
        Bad{"", ", stiffness: {twist: 5}", "", "bad.yaml:8: joints[0].stiffness", "unknown key 'twist'"},
        Bad{"", ", stiffness: {axis: 0}", "", "bad.yaml:8: joints[0].stiffness.axis", "positive"},
        Bad{"", ", stiffness: {rotation: [1, 2, 3]}", "", "bad.yaml:8: joints[0].stiffness.rotation", "list of 2"},
        Bad{"", ", stiffness: {translation: [1, 2]}", "", "bad.yaml:8: joints[0].stiffness.translation", "list of 3"},
        Bad{"", ", stiffness: {translation: [1, 0, 2]}", "", "bad.yaml:8: joints[0].stiffness.translation[1]",
            "positive"},
        Bad{"", ", stiffness: {rotation: {a: 1}}", "", "bad.yaml:8: joints[0].stiffness.rotation", "list of 2"},
        Bad{"", "", ", stiffness: 5", "bad.yaml:9: joints[1].stiffness", "actuated joint's motor"},
        Bad{"", "", ", stiffness: {axis: 5}", "bad.yaml:9: joints[1].stiffness.axis", "only an actuated joint"},
        Bad{"", "", ", stiffness: {rotation: 1e14}", "bad.yaml:9: joints[1].stiffness.rotation", "must lie in"},
        Bad{"", "", ", stiffness: {rotation: [1, 2]}", "bad.yaml:9: joints[1].stiffness.rotation", "list of 3"}));

TEST(StiffnessKeys, ASphericalJointHasNoRotationStiffness) {
  std::string text = With("", "", ", stiffness: {rotation: 5}");
  text.replace(text.find("type: fixed"), 11, "type: spherical");
  const std::string error = ErrorOf(text);
  EXPECT_EQ(error.rfind("bad.yaml:9: joints[1].stiffness.rotation", 0), 0u) << error;
  EXPECT_NE(error.find("allows every rotation"), std::string::npos) << error;
}

TEST(StiffnessKeys, APrismaticJointTakesTwoTranslations) {
  std::string text = With("", "", ", stiffness: {translation: [1, 2], rotation: [3, 4, 5]}");
  text.replace(text.find("type: fixed"), 11, "type: prismatic, axis: [1, 0, 0]");
  const Model m = LoadModelFromString(text, "ok.yaml");
  EXPECT_EQ(m.joints[1].stiffness.translation, (std::vector<double>{1, 2}));
  text.replace(text.find("[1, 2]"), 6, "[1, 2, 3]");
  EXPECT_NE(ErrorOf(text).find("joints[1].stiffness.translation: must be a number or a list of 2"), std::string::npos)
      << ErrorOf(text);
}

TEST(StiffnessKeys, TheToolRefusesAMalformedStiffnessWithExitTwo) {
  const std::string path = ccma::testing::TestDir() + "/bad_stiffness.yaml";
  std::ofstream(path) << With("", "", ", stiffness: {rotation: [1, -2, 3]}");
  const testing::ToolRun run = testing::RunTool({"statics", "--model=" + path});
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_NE(run.err.find("bad_stiffness.yaml:9: joints[1].stiffness.rotation[1]"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace ccma
