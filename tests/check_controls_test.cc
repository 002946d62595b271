// `ccma check`'s independent_controls (documents/check_document.h,
// analyses/mobility.h ClassifyControls): silent where every effective
// control moves alone, a note for the paper's over-actuated systems, a
// warning for dependent controls (a Stewart platform whose legs end in single
// revolutes, four quadrupeds under one rigid platform).
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "ccma/ccma.h"
#include "documents/check_document.h"

namespace ccma::documents {
namespace check_controls_test {

Model Bundled(const std::string& name) { return LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"); }

bool Says(const std::vector<std::string>& lines, const std::string& text) {
  for (const std::string& line : lines) {
    if (line.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(CheckControls, IndependentControlsAreSilent) {
  for (const char* name : {"6dof_asymmetric", "6dof_six_agents", "6dof_symmetric", "6dof_three_legged", "planar_3rpr",
                           "stewart_gough_6ups", "4dof_two_legged"}) {
    const Model model = Bundled(name);
    const Document doc = CheckDocument(model);
    EXPECT_EQ(doc.json["independent_controls"].get<int>(), static_cast<int>(model.effective_control_indices().size()))
        << name;
    EXPECT_FALSE(Says(doc.warnings, "independent")) << name;
    EXPECT_TRUE(doc.notes.empty()) << name;
  }
}

// The paper's 4-DOF systems: three or four agents carry one platform whose
// end-effector has 4 DOF (x, y, z, yaw): 4 independent directions, by design.
TEST(CheckControls, ThePapersOverActuatedSystemsGetANote) {
  for (const char* name : {"4dof_reduced", "4dof_complete", "hybrid_ccma"}) {
    const Document doc = CheckDocument(Bundled(name));
    EXPECT_EQ(doc.json["independent_controls"].get<int>(), 4) << name;
    EXPECT_FALSE(Says(doc.warnings, "independent")) << name;
    ASSERT_EQ(doc.notes.size(), 1u) << name;
    EXPECT_NE(doc.notes[0].find("over-actuated by design: 4 of the"), std::string::npos) << doc.notes[0];
    EXPECT_EQ(doc.json["note"], doc.notes[0]);
  }
}

// Each leg's ball joint at the platform replaced by a vertical revolute (UPR
// legs, 4 DOF each): the six leg lengths no longer move the platform
// independently.
TEST(CheckControls, AStewartPlatformWithRevoluteTopsWarns) {
  std::ifstream in(std::string(CCMA_MODELS_DIR) + "/stewart_gough_6ups.yaml");
  std::stringstream text;
  text << in.rdbuf();
  const std::string upr = std::regex_replace(text.str(), std::regex(R"(type: spherical, (between: \[leg\d_upper, platform\], point: \[[^\]]*\]))"),
                                             "type: revolute, $1, axis: [0, 0, 1]");
  ASSERT_NE(upr, text.str());
  const Model model = LoadModelFromString(upr, "stewart_upr.yaml");
  const Document doc = CheckDocument(model);
  const int independent = doc.json["independent_controls"].get<int>();
  EXPECT_LT(independent, 6);
  EXPECT_TRUE(Says(doc.warnings, "only " + std::to_string(independent) + " of the 6 effective controls are independent"))
      << doc.json.dump();
  EXPECT_NE(doc.json["warning"].get<std::string>().find("independent"), std::string::npos);
  EXPECT_TRUE(doc.notes.empty());
}

// Four quadrupeds (6 controls each) under one rigid platform: 24 controls,
// 22 independent (two combinations of them are fixed by the platform).
TEST(CheckControls, FourQuadrupedsUnderOnePlatformWarn) {
  LeggedOptions options;
  options.agents = 4;
  const Model model = LoadModelFromString(GenerateLeggedModel(options), "legged4.yaml");
  const Document doc = CheckDocument(model);
  EXPECT_EQ(doc.json["controls"].get<int>(), 24);
  EXPECT_EQ(doc.json["independent_controls"].get<int>(), 22);
  EXPECT_TRUE(Says(doc.warnings, "only 22 of the 24 effective controls are independent"));
}

}  // namespace check_controls_test
}  // namespace ccma::documents
