// Numerical mobility (`ccma check`): the reference table of
// shared/reference_models/README.md, and small models counted by hand.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analyses/mobility.h"
#include "formats/model_loader.h"

namespace ccma {
namespace {

struct Expected {
  std::string name;
  int bodies, state_size, controls, effective_controls, end_effector_dof;
  bool rigid;
};

class ReferenceTable : public ::testing::TestWithParam<Expected> {};

TEST_P(ReferenceTable, MatchesThePaperTable) {
  const Expected& e = GetParam();
  const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + e.name + ".yaml");
  const MobilityReport r = AnalyzeMobility(m, State::Home(m), m.home_controls());
  EXPECT_EQ(m.num_bodies(), e.bodies);
  EXPECT_EQ(m.state_size(), e.state_size);
  EXPECT_EQ(m.num_controls(), e.controls);
  EXPECT_EQ(static_cast<int>(m.effective_control_indices().size()), e.effective_controls);
  EXPECT_EQ(r.rigid_with_controls_fixed, e.rigid);
  EXPECT_EQ(r.end_effector_dof, e.end_effector_dof);
  EXPECT_LT(r.energy, 1e-30);
  EXPECT_GT(r.smallest_singular_value, 1e-3);  // well away from singular
}

void PrintTo(const Expected& e, std::ostream* os) { *os << e.name; }

INSTANTIATE_TEST_SUITE_P(FiveReferenceModels, ReferenceTable,
                         ::testing::Values(Expected{"4dof_reduced", 10, 60, 9, 6, 4, true},
                                           Expected{"4dof_complete", 10, 60, 9, 9, 4, true},
                                           Expected{"6dof_symmetric", 10, 60, 9, 9, 6, true},
                                           Expected{"6dof_asymmetric", 11, 66, 9, 9, 6, true},
                                           Expected{"6dof_six_agents", 19, 114, 18, 12, 6, true}),
                         [](const auto& info) { return info.param.name; });

MobilityReport Analyze(const std::string& text) {
  const Model m = LoadModelFromString(text, "hand.yaml");
  return AnalyzeMobility(m, State::Home(m), m.home_controls());
}

// The names of the bodies each free motion moves.
std::vector<std::vector<std::string>> MovingBodies(const std::string& text) {
  const Model m = LoadModelFromString(text, "hand.yaml");
  const MobilityReport r = AnalyzeMobility(m, State::Home(m), m.home_controls());
  std::vector<std::vector<std::string>> names;
  for (const FreeMotion& motion : r.free_motions) {
    names.emplace_back();
    for (const int b : motion.bodies) names.back().push_back(m.bodies[b].name);
  }
  return names;
}

using Names = std::vector<std::vector<std::string>>;

TEST(Mobility, PrismaticLiftOnOneBase) {
  // base -fixed- mast -prismatic(z)- carriage. Controls fixed: the carriage
  // slides (1 DOF). Controls free: x, y, yaw from the base, z from the slide.
  const std::string text = R"(name: lift
bodies:
  - {name: mast, position: [0, 0, 0.5]}
  - {name: carriage, position: [0.1, 0, 0.4], rpy: [0, 1.5707963267948966, 0]}
mobile_bases:
  - {name: b, actuation: complete, pose: [0, 0, 0.3]}
joints:
  - {type: fixed, between: [b, mast], point: [0, 0, 0.1]}
  - {type: prismatic, between: [mast, carriage], point: [0.1, 0, 0.4], axis: [0, 0, 1]}
end_effector: {body: carriage, point: [0.2, 0, 0.4], controlled: [x, y, z, yaw]}
)";
  const MobilityReport r = Analyze(text);
  EXPECT_EQ(r.dof_with_controls_fixed, 1);
  EXPECT_FALSE(r.rigid_with_controls_fixed);
  EXPECT_EQ(r.dof_with_controls_free, 4);
  EXPECT_EQ(r.end_effector_dof, 4);
  EXPECT_EQ(MovingBodies(text), (Names{{"carriage"}}));
}

TEST(Mobility, TwoBasesCarryingABarOnSphericalJoints) {
  // Two complete bases, posts welded on, a bar between spherical joints.
  // Controls fixed: the bar spins about its own axis (1 DOF). Controls
  // free: 6 controls + that spin, minus 1 (the bar's length ties the bases'
  // distance) = 6 motions; the bar moves in x, y, yaw and spins (roll about
  // its axis) but cannot rise or pitch: 4 end-effector DOF.
  const std::string text = R"(name: bar
bodies:
  - {name: p0, position: [-0.5, 0, 0.2]}
  - {name: p1, position: [0.5, 0, 0.2]}
  - {name: bar, position: [0, 0, 0.4]}
mobile_bases:
  - {name: b0, actuation: complete, pose: [-0.5, 0, 0]}
  - {name: b1, actuation: complete, pose: [0.5, 0, 0]}
joints:
  - {type: fixed, between: [b0, p0], point: [-0.5, 0, 0]}
  - {type: fixed, between: [b1, p1], point: [0.5, 0, 0]}
  - {type: spherical, between: [p0, bar], point: [-0.5, 0, 0.4]}
  - {type: spherical, between: [p1, bar], point: [0.5, 0, 0.4]}
end_effector: {body: bar, point: [0, 0, 0.4], controlled: [x, y, yaw]}
)";
  const MobilityReport r = Analyze(text);
  EXPECT_EQ(r.dof_with_controls_fixed, 1);
  EXPECT_EQ(r.dof_with_controls_free, 6);
  EXPECT_EQ(r.end_effector_dof, 4);
  EXPECT_EQ(MovingBodies(text), (Names{{"bar"}}));  // the spin moves the bar alone
}

TEST(Mobility, UniversalWristOnAReducedBase) {
  // base -revolute(z)- post -universal- arm. Controls fixed: post spin and
  // the two universal angles (3 DOF). Controls free: x, y of the base too (5;
  // the reduced heading is no control). The end-effector point sits 0.1 m
  // above the wrist: orientation 3, position x, y; z only to second order.
  const std::string text = R"(name: wrist
bodies:
  - {name: post, position: [1, 2, 0.1]}
  - {name: arm, position: [1, 2, 0.5], rpy: [0.1, 0.2, 0.3]}
mobile_bases:
  - {name: base0, actuation: reduced, pose: [1, 2, 0.5]}
joints:
  - {type: revolute, between: [base0, post], point: [1, 2, 0.1], axis: [0, 0, 1]}
  - {type: universal, between: [post, arm], point: [1, 2, 0.5], axes: [[1, 0, 0], [0, 1, 0]]}
end_effector: {body: arm, point: [1, 2, 0.6], controlled: [x, y, z, yaw]}
)";
  const MobilityReport r = Analyze(text);
  EXPECT_EQ(r.dof_with_controls_fixed, 3);
  EXPECT_EQ(r.dof_with_controls_free, 5);
  EXPECT_EQ(r.end_effector_dof, 5);
  // The post's spin carries the arm; the two universal angles move the arm alone.
  EXPECT_EQ(MovingBodies(text), (Names{{"post", "arm"}, {"arm"}, {"arm"}}));
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// 4dof_reduced with the revolute joint between link2 and ee taken out: leg 2
// hangs from its base. Its post spins about the vertical axis carrying the
// link, and the link swings about the post's horizontal axis; the rest (two
// legs hold ee) stays rigid.
TEST(Mobility, AJointTakenOutNamesTheBodiesThatMove) {
  std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const std::string joint = "  - {type: revolute, between: [link2, ee]";
  const size_t at = text.find(joint);
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find('\n', at) + 1 - at);
  const Model m = LoadModelFromString(text, "4dof_reduced_without_joint.yaml");
  const MobilityReport r = AnalyzeMobility(m, State::Home(m), m.home_controls());
  EXPECT_EQ(r.dof_with_controls_fixed, 2);
  EXPECT_EQ(MovingBodies(text), (Names{{"post2", "link2"}, {"link2"}}));
  ASSERT_EQ(r.free_motions.size(), 2u);
  // Unit, orthogonal directions (a basis of the null space).
  EXPECT_NEAR(r.free_motions[0].direction.norm(), 1, 1e-12);
  EXPECT_NEAR(r.free_motions[1].direction.norm(), 1, 1e-12);
  EXPECT_NEAR(r.free_motions[0].direction.dot(r.free_motions[1].direction), 0, 1e-12);
  // The bundled model itself is rigid: no free motion to name.
  const Model full = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  EXPECT_TRUE(AnalyzeMobility(full, State::Home(full), full.home_controls()).free_motions.empty());
}

}  // namespace
}  // namespace ccma
