// Design for stiffness (analyses/design_objective.h): the gradients of the
// stiffness objective (the largest eigenvalue of the translational block of
// the end-effector's compliance) and the deflection objective (the
// end-effector's deflection under the loads) in the design, at seeded design
// parameters and targets, against central differences of the objective
// RE-SOLVED on perturbed designs (the target re-reached by Newton on the
// controls, the compliance re-computed); the checker rejects a wrong
// gradient; the command stiffens the example and `ccma statics` on the
// written model confirms it; a rigid model is refused; workspace maps of a
// compliant model carry the smallest stiffness per sample.
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analyses/design.h"
#include "analyses/design_objective.h"
#include "formats/model_loader.h"
#include "problems/control_problem.h"
#include "problems/internal/end_effector_error.h"
#include "tests/tool_run.h"

namespace ccma {
namespace design_stiffness_test {

constexpr double kTolerance = 1e-5;  // relative, analytic vs re-solved differences
// Design step of the re-solved differences [m]: small, since the largest
// eigenvalue curves sharply where the Stewart platform's two horizontal
// compliances nearly cross (the differences' own O(h^2) error is 4e-6
// relative at 1e-5 m, 1.6e-7 here).
constexpr double kDelta = 2e-6;

std::string ExamplePath(const std::string& file) { return std::string(CCMA_MODELS_DIR) + "/../examples/statics/" + file; }

// 4dof_reduced made compliant: seeded masses and payload, every base on
// springs [kx, ky, ktheta], every passive revolute joint with bearing play.
Model CompliantCcma(unsigned seed) {
  Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> mass(0.5, 3.0), offset(-0.05, 0.05), k(0.5, 2.0);
  for (Body& body : model.bodies) {
    body.inertia.mass = mass(rng);
    body.inertia.com_B = Eigen::Vector3d{offset(rng), offset(rng), offset(rng)};
  }
  model.end_effector.payload.mass = mass(rng);
  for (MobileBase& base : model.mobile_bases) base.stiffness.k = Eigen::Vector3d{2e4 * k(rng), 2e4 * k(rng), 3e3 * k(rng)};
  for (Joint& joint : model.joints) {
    if (joint.type == JointType::kRevolute && !joint.actuated) joint.stiffness.translation = {5e5 * k(rng), 5e5 * k(rng), 5e5 * k(rng)};
  }
  EXPECT_TRUE(model.compliant());
  return model;
}

// Two joints' points (a ground or first joint and one more): parameters that
// deform the mechanism.
DesignParameters StiffnessParameters(const Model& model, const std::string& a, const std::string& b) {
  DesignParameters params;
  std::string why;
  EXPECT_TRUE(AddJointCoordinates(model, a + ".point", &params, &why)) << why;
  EXPECT_TRUE(AddJointCoordinates(model, b + ".z", &params, &why)) << why;
  return params;
}

struct StiffnessSolved {
  State s;
  Eigen::VectorXd u;
  bool ok = false;
};

// A seeded target near home on `model`, reached by the control problem.
StiffnessSolved StiffnessReach(const Model& model, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1, 1);
  ControlProblem control(model);
  control.SetControls(model.home_controls());
  PoseTarget target = control.CurrentPose();
  for (int i = 0; i < 3; ++i) target.position[i] += 0.02 * uniform(rng);
  const ControlResult r = control.MoveTo(target);
  return {control.forward().state(), control.controls(), r.converged && r.assembled};
}

// The same target re-reached on a perturbed design: Newton on the controls
// with the minimum-norm step (the controls follow the design as the gradient
// assumes), every forward problem re-solved.
StiffnessSolved StiffnessReReach(const Model& perturbed, const StiffnessSolved& from, const PoseTarget& target) {
  ForwardProblem forward(perturbed);
  forward.Restore(from.s, from.u);
  Eigen::VectorXd u = from.u;
  for (int it = 0; it < 12; ++it) {
    if (!forward.Solve(u).converged) return {};
    Eigen::VectorXd e;
    Eigen::MatrixXd de_ds;
    EndEffectorError(perturbed).Evaluate(forward.state(), target, &e, &de_ds);
    if (e.norm() < 1e-13) break;
    u -= (de_ds * StateControlSensitivity(perturbed, forward.state(), u)).completeOrthogonalDecomposition().solve(e);
  }
  return {forward.state(), u, true};
}

// The checker: the largest gap between a gradient and the re-solved central
// differences, relative to the largest of the latter.
double GradientGap(const Eigen::VectorXd& g, const Eigen::VectorXd& numeric) {
  return (g - numeric).cwiseAbs().maxCoeff() / numeric.cwiseAbs().maxCoeff();
}

// The re-solved central differences of the objective at (at, p) per parameter.
Eigen::VectorXd ReSolvedDifferences(DesignObjective objective, const Model& model, const DesignParameters& params,
                                    const Eigen::VectorXd& p, const StiffnessSolved& at) {
  const Model at_p = ApplyParameters(model, params, p);
  const EndEffectorPose pose = ComputeEndEffectorPose(at_p, at.s);
  const PoseTarget target{pose.position, pose.rpy};
  Eigen::VectorXd numeric(params.size());
  for (int k = 0; k < params.size(); ++k) {
    double value[2];
    for (int side = 0; side < 2; ++side) {
      Eigen::VectorXd pk = p;
      pk[k] += side == 0 ? kDelta : -kDelta;
      const Model perturbed = ApplyParameters(model, params, pk);
      const StiffnessSolved re = StiffnessReReach(perturbed, at, target);
      EXPECT_TRUE(re.ok);
      const ObjectiveAtTarget v = EvaluateObjective(objective, perturbed, re.s, re.u, {});
      EXPECT_TRUE(v.defined) << v.why;
      value[side] = v.value;
    }
    numeric[k] = (value[0] - value[1]) / (2 * kDelta);
  }
  return numeric;
}

struct StiffnessCase {
  std::string name;
  DesignObjective objective;
};

class StiffnessGradients : public ::testing::TestWithParam<StiffnessCase> {};

TEST_P(StiffnessGradients, MatchReSolvedCentralDifferencesAtSeededDesigns) {
  const bool stewart = GetParam().name == "stewart";
  const Model model = stewart ? LoadModel(ExamplePath("stewart_gough_compliant.yaml")) : CompliantCcma(5);
  // The CCMA's base joints: moving a joint inside its loops would open them
  // at held controls, and the compliance of an overconstrained mechanism is
  // only defined where it is assembled.
  const DesignParameters params = stewart ? StiffnessParameters(model, "joint0", "joint9")
                                          : StiffnessParameters(model, "joint0", "joint3");
  const DesignObjective objective = GetParam().objective;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> offset(-0.01, 0.01);
  for (unsigned seed : {1u, 2u}) {
    Eigen::VectorXd p = ParameterValues(model, params);
    for (int k = 0; k < p.size(); ++k) p[k] += offset(rng);  // a seeded design, not the file's
    const StiffnessSolved at = StiffnessReach(ApplyParameters(model, params, p), seed);
    ASSERT_TRUE(at.ok) << GetParam().name << " seed " << seed;
    Eigen::VectorXd g;
    std::string why;
    ASSERT_TRUE(ObjectiveGradient(objective, model, params, p, at.s, at.u, {}, &g, &why)) << why;
    const Eigen::VectorXd numeric = ReSolvedDifferences(objective, model, params, p, at);
    const double value = EvaluateObjective(objective, ApplyParameters(model, params, p), at.s, at.u, {}).value;
    // The design must change the objective for the check to mean anything:
    // 0.5 % per 10 cm at least (these seeded designs: 0.7 to 0.8 %).
    EXPECT_GT(numeric.cwiseAbs().maxCoeff(), 0.05 * value) << numeric.transpose();
    const double error = GradientGap(g, numeric);
    RecordProperty("relative_error_seed" + std::to_string(seed), ::testing::PrintToString(error));
    EXPECT_LT(error, kTolerance) << GetParam().name << " seed " << seed << "\nanalytic " << g.transpose()
                                 << "\nnumeric  " << numeric.transpose();
  }
}

INSTANTIATE_TEST_SUITE_P(Models, StiffnessGradients,
                         ::testing::Values(StiffnessCase{"stewart", DesignObjective::kStiffness},
                                           StiffnessCase{"stewart", DesignObjective::kDeflection},
                                           StiffnessCase{"ccma", DesignObjective::kStiffness},
                                           StiffnessCase{"ccma", DesignObjective::kDeflection}),
                         [](const ::testing::TestParamInfo<StiffnessCase>& info) {
                           return info.param.name + "_" + DesignObjectiveName(info.param.objective);
                         });

// The checker rejects wrong gradients: 0.1 % too large, one entry's sign
// flipped, and the gradient at fixed controls (the design's partial
// derivative without the controls following the target, what a gradient
// that forgot du/dp would give).
TEST(StiffnessGradientChecker, RejectsWrongGradients) {
  const Model model = LoadModel(ExamplePath("stewart_gough_compliant.yaml"));
  const DesignParameters params = StiffnessParameters(model, "joint0", "joint9");
  const Eigen::VectorXd p = ParameterValues(model, params);
  const StiffnessSolved at = StiffnessReach(model, 3);
  ASSERT_TRUE(at.ok);
  Eigen::VectorXd g;
  std::string why;
  ASSERT_TRUE(ObjectiveGradient(DesignObjective::kStiffness, model, params, p, at.s, at.u, {}, &g, &why)) << why;
  const Eigen::VectorXd numeric = ReSolvedDifferences(DesignObjective::kStiffness, model, params, p, at);
  ASSERT_LT(GradientGap(g, numeric), kTolerance);
  EXPECT_GT(GradientGap(1.001 * g, numeric), 10 * kTolerance);
  Eigen::VectorXd flipped = g;
  int largest = 0;
  g.cwiseAbs().maxCoeff(&largest);
  flipped[largest] = -flipped[largest];
  EXPECT_GT(GradientGap(flipped, numeric), 1.0);
  // At fixed controls: re-solve the forward problem only.
  Eigen::VectorXd fixed(params.size());
  for (int k = 0; k < params.size(); ++k) {
    double value[2];
    for (int side = 0; side < 2; ++side) {
      Eigen::VectorXd pk = p;
      pk[k] += side == 0 ? kDelta : -kDelta;
      const Model perturbed = ApplyParameters(model, params, pk);
      ForwardProblem forward(perturbed);
      forward.Restore(at.s, at.u);
      ASSERT_TRUE(forward.Solve(at.u).converged);
      value[side] = EvaluateObjective(DesignObjective::kStiffness, perturbed, forward.state(), at.u, {}).value;
    }
    fixed[k] = (value[0] - value[1]) / (2 * kDelta);
  }
  EXPECT_GT(GradientGap(fixed, numeric), 10 * kTolerance);
}

double MostCompliant(const std::string& model) {
  const testing::ToolRun r = testing::RunTool({"statics", "--model=" + model});
  EXPECT_EQ(r.status, 0) << r.err;
  return nlohmann::json::parse(r.out)["most_compliant"]["compliance"].get<double>();
}

// The example made stiffer by moving its six ground joints (docs/statics.md,
// "Design for stiffness"); `ccma statics` on the written model confirms it
// at home (the first target).
TEST(StiffnessDesignCommand, StiffensTheExampleAndStaticsConfirmsIt) {
  const std::string out = ccma::testing::TestDir() + "/stiffness_designed.yaml";
  const testing::ToolRun run = testing::RunTool(
      {"design", "--model=" + ExamplePath("stewart_gough_compliant.yaml"),
       "--targets=" + ExamplePath("stewart_gough_compliant_targets.csv"), "--out=" + out, "--objective=stiffness",
       "--vary=joint0.point,joint3.point,joint6.point,joint9.point,joint12.point,joint15.point", "--max_change=0.1"});
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_EQ(j["objective"]["unit"], "m/N");
  const double before = j["objective"]["before"]["value"], after = j["objective"]["after"]["value"];
  EXPECT_LT(after, 0.5 * before);  // the softest direction at the worst target: more than twice as stiff
  const double home_before = MostCompliant(ExamplePath("stewart_gough_compliant.yaml"));
  const double home_after = MostCompliant(out);
  EXPECT_NEAR(home_before, 8.84e-6, 0.01e-6);  // docs/statics.md
  EXPECT_LT(home_after, 0.5 * home_before);
  EXPECT_LE(home_after, after * (1 + 1e-9));  // home is one of the targets: at most the worst
}

TEST(StiffnessDesignCommand, RigidModelIsRefused) {
  const testing::ToolRun run = testing::RunTool(
      {"design", "--model=" + std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml",
       "--targets=" + ExamplePath("4dof_payload_targets.csv"), "--out=" + ccma::testing::TestDir() + "/rigid.yaml",
       "--objective=deflection", "--vary=joint0.x"});
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_NE(run.err.find("has no stiffness keys"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace ccma

namespace ccma {
namespace design_stiffness_test {

// `ccma workspace` on a compliant model: stiffness_min_N_per_m per sample,
// 1 / `ccma statics`' most_compliant at that sample's controls where
// reached, 0 where not; a rigid model's map has no such column.
TEST(WorkspaceStiffnessColumn, IsStaticsMostCompliantInverted) {
  const std::string csv = ccma::testing::TestDir() + "/stiffness_map.csv";
  // z up to 0.75: beyond the legs' 0.1 m stroke, so some samples are unreachable.
  testing::ToolRun r = testing::RunTool({"workspace", "--model=" + ExamplePath("stewart_gough_compliant.yaml"),
                                         "--x=-0.05:0.05", "--z=0.45:0.75", "--resolution=3", "--out=" + csv});
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream rows(testing::Slurp(csv));
  std::string line;
  std::getline(rows, line);
  std::vector<std::string> header;
  for (std::stringstream cells(line); std::getline(cells, line, ',');) header.push_back(line);
  const auto column = [&header](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  ASSERT_LT(column("stiffness_min_N_per_m"), header.size());
  int reached = 0, unreached = 0;
  while (std::getline(rows, line)) {
    std::vector<std::string> cells;
    for (std::stringstream in(line); std::getline(in, line, ',');) cells.push_back(line);
    const double stiffness = std::stod(cells[column("stiffness_min_N_per_m")]);
    if (cells[column("reachable")] == "0") {
      EXPECT_EQ(stiffness, 0);
      ++unreached;
      continue;
    }
    std::string controls = "--controls=";
    for (int k = 0; k < 6; ++k) controls += (k ? "," : "") + cells[column("u" + std::to_string(k))];
    r = testing::RunTool({"statics", "--model=" + ExamplePath("stewart_gough_compliant.yaml"), controls});
    ASSERT_EQ(r.status, 0) << r.err;
    const double most = nlohmann::json::parse(r.out)["most_compliant"]["compliance"].get<double>();
    EXPECT_NEAR(stiffness * most, 1.0, 1e-9) << line;
    EXPECT_GT(stiffness, 5e4);  // 1.1e5 N/m at home (docs/statics.md)
    ++reached;
  }
  EXPECT_GE(reached, 3);
  EXPECT_GE(unreached, 1);
  r = testing::RunTool({"workspace", "--model=" + std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml", "--z=0.5:0.7",
                        "--resolution=3", "--out=" + csv});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(testing::Slurp(csv).find("stiffness"), std::string::npos);
}

}  // namespace
}  // namespace ccma
