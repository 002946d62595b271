// Numerical mobility (`ccma check`): the reference table of
// shared/reference_models/README.md, small models counted by hand, the
// sparse analysis against the dense one, and generated models of up to 1000
// agents against their closed form. Built on it: the end-effector
// components the controls move (analyses/moved_components.h) and the
// comparison of configurations up to idle motions
// (analyses/configuration_difference.h).
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "analyses/configuration_difference.h"
#include "analyses/internal/sparse_mobility.h"
#include "analyses/mobility.h"
#include "analyses/moved_components.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "tests/hinge_model.h"

namespace ccma {
namespace mobility_test {

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
  // The joints whose coordinate each changes: the post's (base2-post2,
  // joint6) turns carrying the link, then the link's (post2-link2, joint7)
  // turns alone; the legs' other joints hold still.
  EXPECT_EQ(r.free_motions[0].joints, std::vector<int>{m.FindJoint("joint6")});
  EXPECT_EQ(r.free_motions[1].joints, std::vector<int>{m.FindJoint("joint7")});
  // The bundled model itself is rigid: no free motion to name.
  const Model full = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  EXPECT_TRUE(AnalyzeMobility(full, State::Home(full), full.home_controls()).free_motions.empty());
}

// The body names of each free motion in `r`.
Names BodyNames(const Model& m, const MobilityReport& r) {
  Names names;
  for (const FreeMotion& motion : r.free_motions) {
    names.emplace_back();
    for (const int b : motion.bodies) names.back().push_back(m.bodies[b].name);
  }
  return names;
}

// The sparse analysis (used beyond kDenseMobilityStateSize) gives the dense
// one's ranks, DOF, body sets of the free motions and smallest singular
// value, on every bundled model and on the hand-counted ones.
void ExpectSparseMatchesDense(const Model& m) {
  SCOPED_TRACE(m.name);
  const MobilityReport dense = AnalyzeMobility(m, State::Home(m), m.home_controls());
  MobilityReport sparse;
  AnalyzeMobilitySparse(m, State::Home(m), m.home_controls(), 1e-8, &sparse);
  EXPECT_EQ(sparse.constraint_rank, dense.constraint_rank);
  EXPECT_EQ(sparse.dof_with_controls_fixed, dense.dof_with_controls_fixed);
  EXPECT_EQ(sparse.rigid_with_controls_fixed, dense.rigid_with_controls_fixed);
  EXPECT_EQ(sparse.dof_with_controls_free, dense.dof_with_controls_free);
  EXPECT_EQ(sparse.end_effector_dof, dense.end_effector_dof);
  EXPECT_EQ(sparse.end_effector_dof_nonholonomic, dense.end_effector_dof_nonholonomic);
  if (dense.rigid_with_controls_fixed) {
    EXPECT_NEAR(sparse.smallest_singular_value, dense.smallest_singular_value, 1e-7 * dense.smallest_singular_value);
  } else {
    EXPECT_EQ(sparse.smallest_singular_value, 0.0);
  }
  EXPECT_TRUE(sparse.free_motions_listed);
  EXPECT_EQ(BodyNames(m, sparse), BodyNames(m, dense));
  for (const FreeMotion& motion : sparse.free_motions) EXPECT_NEAR(motion.direction.norm(), 1, 1e-12);
}

TEST(SparseMobility, MatchesTheDenseAnalysisOnTheBundledModels) {
  for (const char* name : {"4dof_reduced", "4dof_complete", "4dof_differential", "6dof_symmetric", "6dof_asymmetric",
                           "6dof_six_agents", "hybrid_ccma", "planar_3rpr", "stewart_gough_6ups"}) {
    ExpectSparseMatchesDense(LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"));
  }
}

TEST(SparseMobility, MatchesTheDenseAnalysisOnMechanismsThatMove) {
  std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const std::string joint = "  - {type: revolute, between: [link2, ee]";
  const size_t at = text.find(joint);
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find('\n', at) + 1 - at);
  ExpectSparseMatchesDense(LoadModelFromString(text, "4dof_reduced_without_joint.yaml"));
  StewartOptions options;
  options.agents = 4;  // complete bases: rigid; 12 agents: reduced bases
  ExpectSparseMatchesDense(LoadModelFromString(GenerateStewartModel(options), "stewart_4.yaml"));
}

// The generated family (formats/model_generator.h) from 6 agents: N reduced
// bases, each a body, with a post and a link (3N + 1 bodies with the
// end-effector); per leg two revolutes (5 rows each), a spherical (3) and
// the base's 9 rows: 24 N rows. Each leg R-R-S has 5 DOF and closes 6
// constraints on the end-effector, so with N >= 6 legs the state is rigid
// (rank 18 N + 6). With the 2 N effective controls (x, y per reduced base)
// free, each leg has one internal motion besides the end-effector's 6:
// N + 6 free motions, all 6 end-effector DOF driven, and omni bases add no
// lateral restriction.
void ExpectClosedForm(int agents) {
  SCOPED_TRACE(agents);
  StewartOptions options;
  options.agents = agents;
  const Model m = LoadModelFromString(GenerateStewartModel(options), "generated.yaml");
  ASSERT_EQ(m.num_bodies(), 3 * agents + 1);
  ASSERT_EQ(m.state_size(), 18 * agents + 6);
  const MobilityReport r = AnalyzeMobility(m, State::Home(m), m.home_controls());
  EXPECT_EQ(r.constraint_rows, 24 * agents);
  EXPECT_EQ(r.constraint_rank, 18 * agents + 6);
  EXPECT_EQ(r.dof_with_controls_fixed, 0);
  EXPECT_TRUE(r.rigid_with_controls_fixed);
  EXPECT_EQ(r.dof_with_controls_free, agents + 6);
  EXPECT_EQ(r.end_effector_dof, 6);
  EXPECT_EQ(r.end_effector_dof_nonholonomic, 6);
  EXPECT_TRUE(r.free_motions.empty());
  EXPECT_LT(r.energy, 1e-24);
  EXPECT_GT(r.smallest_singular_value, 1e-2);  // 0.037 at 6 agents, 0.065 at 50
  EXPECT_LT(r.smallest_singular_value, 1);
}

TEST(SparseMobility, GeneratedFamilyMatchesItsClosedForm) {
  for (const int agents : {6, 12, 50}) ExpectClosedForm(agents);
}

// 1000 agents: a dense SVD of the 24000 x 18006 Jacobian needed more than
// 12 GB and ended in std::bad_alloc; the sparse analysis takes seconds.
TEST(SparseMobility, AThousandAgentsMatchTheClosedForm) { ExpectClosedForm(1000); }

// 100 agents with one leg's spherical joint taken out: that leg hangs from
// its base (its post spins carrying the link, the link swings alone), the
// 99 others hold the end-effector.
TEST(SparseMobility, NamesTheFreeMotionsOfALargeMechanism) {
  StewartOptions options;
  options.agents = 100;
  std::string text = GenerateStewartModel(options);
  const size_t at = text.find("  - {type: spherical, between: [link37, ee]");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find('\n', at) + 1 - at);
  const Model m = LoadModelFromString(text, "generated.yaml");
  ASSERT_GT(m.state_size(), kDenseMobilityStateSize);
  const MobilityReport r = AnalyzeMobility(m, State::Home(m), m.home_controls());
  EXPECT_EQ(r.constraint_rank, m.state_size() - 2);
  EXPECT_EQ(r.dof_with_controls_fixed, 2);
  EXPECT_EQ(r.smallest_singular_value, 0.0);
  EXPECT_TRUE(r.free_motions_listed);
  EXPECT_EQ(BodyNames(m, r), (Names{{"post37", "link37"}, {"link37"}}));
  ASSERT_EQ(r.free_motions.size(), 2u);
  EXPECT_NEAR(r.free_motions[0].direction.dot(r.free_motions[1].direction), 0, 1e-12);
}

// 300 agents with 220 legs hanging (their spherical joints taken out): 440
// free motions, state size 5406; 5406 x 440^2 is above kMaxFreeMotionWork,
// so they are counted but not listed.
TEST(SparseMobility, CountsButDoesNotListTooManyFreeMotions) {
  StewartOptions options;
  options.agents = 300;
  std::string text = GenerateStewartModel(options);
  for (int leg = 0; leg < 220; ++leg) {
    const size_t at = text.find("  - {type: spherical, between: [link" + std::to_string(leg) + ", ee]");
    ASSERT_NE(at, std::string::npos) << leg;
    text.erase(at, text.find('\n', at) + 1 - at);
  }
  const Model m = LoadModelFromString(text, "generated.yaml");
  const MobilityReport r = AnalyzeMobility(m, State::Home(m), m.home_controls());
  EXPECT_EQ(r.dof_with_controls_fixed, 440);
  EXPECT_GT(static_cast<double>(m.state_size()) * 440 * 440, kMaxFreeMotionWork);
  EXPECT_FALSE(r.free_motions_listed);
  EXPECT_TRUE(r.free_motions.empty());
  EXPECT_FALSE(r.rigid_with_controls_fixed);
}

// The work bound: above kMaxMobilityStateSize (20,000 bodies) the analysis
// refuses before any work (the bodies need no joints for that).
TEST(SparseMobility, RefusesAboveTheStateSizeBound) {
  Model m;
  m.name = "many_bodies";
  m.bodies.resize(kMaxMobilityStateSize / 6 + 1);
  try {
    AnalyzeMobility(m, State::Home(m), Eigen::VectorXd());
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "mobility analysis: state size 120006 (20001 bodies) is above the bound of 120000 (20000 bodies)");
  }
}

// ---- End-effector components the controls move (moved_components.h) ----

// The hinge of hinge_model.h at home: the omni base moves x, y and (turning,
// the point 0.2 m along y) -0.2 x + yaw; the hinge about x moves z = 0.2 q
// and roll = q together. Rows over (base x, y, theta, hinge): x [1 0 -0.2 0],
// y [0 1 0 0], z [0 0 0 0.2], roll [0 0 0 1], pitch 0, yaw [0 0 1 0]: roll
// adds nothing to x y z, yaw does.
TEST(MovedComponents, HingeOnAnOmniBaseMatchesItsClosedForm) {
  const Model m = LoadModelFromString(kHinge, "hinge.yaml");
  const ComponentSet xyz_roll = {true, true, true, true, false, false};
  const MovedComponents moved = AnalyzeMovedComponents(m, State::Home(m), m.home_controls(), xyz_roll);
  EXPECT_EQ(moved.chosen, (ComponentSet{true, true, true, false, false, true}));
  EXPECT_EQ(moved.rank, 4);
  EXPECT_EQ(moved.given_rank, 3);
  EXPECT_EQ(AnalyzeMovedComponents(m, State::Home(m), m.home_controls(), {false, false, false, true, false, false})
                .given_rank,
            1);
  EXPECT_EQ(AnalyzeMobility(m, State::Home(m), m.home_controls()).end_effector_dof, moved.rank);
}

// The sparse path (rank([A; X_S]) - rank(A)) agrees with the dense one on
// every one of the 64 sets of components, and the chosen set's size is
// check's end_effector_dof.
TEST(MovedComponents, SparseRanksMatchTheDenseOnesForEverySet) {
  for (const char* name : {"4dof_reduced", "planar_3rpr"}) {
    SCOPED_TRACE(name);
    const Model m = LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
    const State s = State::Home(m);
    const SparseEndEffectorRanks sparse(m, s, m.home_controls(), kMovedComponentTolerance);
    for (int bits = 0; bits < 64; ++bits) {
      ComponentSet set{};
      for (int c = 0; c < 6; ++c) set[c] = (bits >> c) & 1;
      EXPECT_EQ(sparse.Rank(set), AnalyzeMovedComponents(m, s, m.home_controls(), set).given_rank) << bits;
    }
    EXPECT_EQ(AnalyzeMovedComponents(m, s, m.home_controls(), {}).rank,
              AnalyzeMobility(m, s, m.home_controls()).end_effector_dof);
  }
  // planar_3rpr moves x, y and yaw only.
  const Model planar = LoadModel(std::string(CCMA_MODELS_DIR) + "/planar_3rpr.yaml");
  EXPECT_EQ(AnalyzeMovedComponents(planar, State::Home(planar), planar.home_controls(), {}).chosen,
            (ComponentSet{true, true, false, false, false, true}));
}

// Beyond kDenseMobilityStateSize: 50 generated agents drive all six.
TEST(MovedComponents, ALargeMechanismTakesTheSparsePath) {
  StewartOptions options;
  options.agents = 50;
  const Model m = LoadModelFromString(GenerateStewartModel(options), "generated.yaml");
  ASSERT_GT(m.state_size(), kDenseMobilityStateSize);
  const MovedComponents moved = AnalyzeMovedComponents(m, State::Home(m), m.home_controls(), {true, true});
  EXPECT_EQ(moved.chosen, (ComponentSet{true, true, true, true, true, true}));
  EXPECT_EQ(moved.rank, 6);
  EXPECT_EQ(moved.given_rank, 2);
}

// ---- Configurations compared up to idle motions (configuration_difference.h) ----

// A rod between two ball joints, one on a post welded to an omni base, one
// on the ground; its frame off its axis. The rod's spin about its axis is
// its one idle motion.
constexpr char kSpinningRod[] = R"(name: spinning_rod
bodies:
  - {name: post, position: [0.5, 0, 0.1]}
  - {name: rod, position: [0.25, 0.05, 0.3]}
mobile_bases:
  - {name: base0, type: omni, actuation: complete, pose: [0.5, 0, 0]}
joints:
  - {type: fixed, between: [base0, post], point: [0.5, 0, 0.1]}
  - {type: spherical, between: [post, rod], point: [0.5, 0, 0.2]}
  - {type: spherical, between: [world, rod], point: [0, 0, 0.4]}
end_effector: {body: post, point: [0.5, 0, 0.2], controlled: [x, y]}
)";

// `s` with body b turned by `angle` about the line through `c` along `axis`.
State Turned(const State& s, int b, const Eigen::Vector3d& c, const Eigen::Vector3d& axis, double angle) {
  const Eigen::AngleAxisd turn(angle, axis.normalized());
  State out = s;
  out.SetPose(b, Eigen::Quaterniond(turn) * s.q_WB(b), c + turn * (s.p_WB(b) - c));
  return out;
}

TEST(ConfigurationDifference, AnIdleSpinIsTheSameConfigurationAndARealChangeIsNot) {
  const Model m = LoadModelFromString(kSpinningRod, "spinning_rod.yaml");
  const int rod = m.FindBody("rod"), post = m.FindBody("post");
  const State home = State::Home(m);
  const Eigen::Vector3d p1(0.5, 0, 0.2), p2(0, 0, 0.4);
  const State spun = Turned(home, rod, p1, p2 - p1, 1.0);
  ASSERT_GT(spun.Minus(home).lpNorm<Eigen::Infinity>(), 0.5);  // raw states far apart
  const ConfigurationDifference idle = CompareConfigurations(m, home, spun, m.home_controls());
  EXPECT_TRUE(idle.same);
  EXPECT_EQ(idle.idle_bodies, std::vector<int>{rod});
  EXPECT_LT(idle.max_state_difference, 1e-12);  // the rod's two ends
  EXPECT_LT(idle.end_effector_distance, 1e-15);
  // The spun rod moved off its ends by 1 mm: its end points differ.
  State shifted = spun;
  shifted.SetPose(rod, spun.q_WB(rod), spun.p_WB(rod) + Eigen::Vector3d(0, 1e-3, 0));
  const ConfigurationDifference moved = CompareConfigurations(m, home, shifted, m.home_controls());
  EXPECT_FALSE(moved.same);
  EXPECT_NEAR(moved.max_state_difference, 1e-3, 1e-12);
  // The post turned about its vertical axis through the end-effector point:
  // the point stays, the end-effector's orientation does not.
  const State turned = Turned(home, post, Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d::UnitZ(), 1e-3);
  const ConfigurationDifference rotated = CompareConfigurations(m, home, turned, m.home_controls());
  EXPECT_FALSE(rotated.same);
  EXPECT_LT(rotated.end_effector_distance, 1e-15);
  EXPECT_NEAR(rotated.end_effector_rotation, 1e-3, 1e-12);
}

// The sparse path: 100 generated agents, leg 37's spherical joint taken
// out. Its post spins (about its base's vertical axis) carrying its link,
// and the link swings about its hinge at the post's top: idle motions.
TEST(ConfigurationDifference, IdleMotionsOfALargeMechanism) {
  StewartOptions options;
  options.agents = 100;
  std::string text = GenerateStewartModel(options);
  const size_t at = text.find("  - {type: spherical, between: [link37, ee]");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find('\n', at) + 1 - at);
  const Model m = LoadModelFromString(text, "generated.yaml");
  ASSERT_GT(m.state_size(), kDenseMobilityStateSize);
  const int post = m.FindBody("post37"), link = m.FindBody("link37");
  const State home = State::Home(m);
  const Joint* hinge = nullptr;
  for (const Joint& joint : m.joints) {
    if (joint.body_a == post && joint.body_b == link) hinge = &joint;
  }
  ASSERT_NE(hinge, nullptr);
  const Eigen::Vector3d top = home.R_WB(post) * hinge->p_A + home.p_WB(post);
  State b = Turned(home, link, top, home.R_WB(post) * hinge->a_A, 0.5);
  const Eigen::Vector3d foot(top.x(), top.y(), 0);
  b = Turned(Turned(b, post, foot, Eigen::Vector3d::UnitZ(), 0.3), link, foot, Eigen::Vector3d::UnitZ(), 0.3);
  const ConfigurationDifference d = CompareConfigurations(m, home, b, m.home_controls());
  EXPECT_TRUE(d.same);
  EXPECT_EQ(d.idle_bodies, (std::vector<int>{std::min(post, link), std::max(post, link)}));
  EXPECT_LT(d.max_state_difference, 1e-12);
}

}  // namespace
}  // namespace ccma
