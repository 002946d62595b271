// Design objectives (analyses/design_objective.h, payload.h): the payload
// capacity against its definition (efforts at the capacity sit exactly on
// the limiting limit), and the gradients of payload, peak_push and ee_std in
// the design against central differences of the objective RE-SOLVED on
// perturbed designs (the target re-reached by Newton on the controls), on
// models with bases, with actuated joints and with both; the comparison is
// tight enough to reject a 0.1 % error. Masses, payloads and limits are
// seeded.
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analyses/design.h"
#include "analyses/design_objective.h"
#include "analyses/payload.h"
#include "analyses/precision.h"
#include "analyses/statics.h"
#include "formats/model_loader.h"
#include "problems/control_problem.h"
#include "problems/internal/end_effector_error.h"
#include "tests/tool_run.h"

namespace ccma {
namespace design_objective_test {

constexpr double kTolerance = 1e-5;  // relative, analytic vs re-solved differences
constexpr double kDelta = 1e-4;      // design step of the differences [m]

Model LoadReference(const std::string& name) { return LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"); }

// Seeded masses on every body, a payload, and limits: +-limit on every
// actuated joint, a push limit on every base.
Model WithLoads(Model model, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> mass(0.5, 3.0), offset(-0.05, 0.05);
  for (Body& body : model.bodies) {
    body.inertia.mass = mass(rng);
    body.inertia.com_B = Eigen::Vector3d{offset(rng), offset(rng), offset(rng)};
  }
  model.end_effector.payload.mass = mass(rng);
  model.end_effector.payload.com_B = model.end_effector.p_B + Eigen::Vector3d{offset(rng), offset(rng), 0};
  for (Joint& joint : model.joints) {
    if (joint.actuated) joint.effort = {true, -400.0, 300.0};
  }
  for (MobileBase& base : model.mobile_bases) base.push_limit = 150;
  return model;
}

// The first joint's point and one more joint's z: parameters that deform
// the mechanism (not a rigid move).
DesignParameters Parameters(const Model& model) {
  DesignParameters params;
  std::string why;
  EXPECT_TRUE(AddJointCoordinates(model, model.joints[0].name + ".point", &params, &why)) << why;
  EXPECT_TRUE(AddJointCoordinates(model, model.joints[model.joints.size() - 1].name + ".z", &params, &why)) << why;
  return params;
}

struct Solved {
  State s;
  Eigen::VectorXd u;
  bool ok = false;
};

// The mechanism at a seeded target near home on `model`.
Solved ReachNearHome(const Model& model, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1, 1);
  ControlProblem control(model);
  control.SetControls(model.home_controls());
  PoseTarget target = control.CurrentPose();
  for (int i = 0; i < 3; ++i) target.position[i] += 0.03 * uniform(rng);
  const ControlResult r = control.MoveTo(target);
  return {control.forward().state(), control.controls(), r.converged && r.assembled};
}

// The same target re-reached on a perturbed design: from (s, u), Newton on
// the controls with the minimum-norm step (the controls follow the design
// as the gradient assumes), every forward problem re-solved.
Solved ReReach(const Model& perturbed, const Solved& from, const PoseTarget& target) {
  ForwardProblem forward(perturbed);
  forward.Restore(from.s, from.u);
  Eigen::VectorXd u = from.u;
  Solved out;
  for (int it = 0; it < 12; ++it) {
    if (!forward.Solve(u).converged) return out;
    Eigen::VectorXd e;
    Eigen::MatrixXd de_ds;
    EndEffectorError(perturbed).Evaluate(forward.state(), target, &e, &de_ds);
    if (e.norm() < 1e-13) break;
    const Eigen::MatrixXd de_du = de_ds * StateControlSensitivity(perturbed, forward.state(), u);
    u -= de_du.completeOrthogonalDecomposition().solve(e);
  }
  return {forward.state(), u, true};
}

struct Case {
  std::string model;
  DesignObjective objective;
};

class ObjectiveGradients : public ::testing::TestWithParam<Case> {};

TEST_P(ObjectiveGradients, MatchReSolvedCentralDifferences) {
  const Model model = WithLoads(LoadReference(GetParam().model), 5);
  const DesignObjective objective = GetParam().objective;
  const DesignParameters params = Parameters(model);
  const Eigen::VectorXd p0 = ParameterValues(model, params);
  const BasePoseNoise noise;
  for (unsigned seed : {1u, 2u}) {
    const Model at_p0 = ApplyParameters(model, params, p0);
    const Solved at = ReachNearHome(at_p0, seed);
    ASSERT_TRUE(at.ok) << GetParam().model << " seed " << seed;
    const EndEffectorPose pose = ComputeEndEffectorPose(at_p0, at.s);
    const PoseTarget target{pose.position, pose.rpy};
    Eigen::VectorXd g;
    std::string why;
    ASSERT_TRUE(ObjectiveGradient(objective, model, params, p0, at.s, at.u, noise, &g, &why)) << why;
    Eigen::VectorXd numeric(params.size());
    for (int k = 0; k < params.size(); ++k) {
      double value[2];
      for (int side = 0; side < 2; ++side) {
        Eigen::VectorXd p = p0;
        p[k] += side == 0 ? kDelta : -kDelta;
        const Model perturbed = ApplyParameters(model, params, p);
        const Solved re = ReReach(perturbed, at, target);
        ASSERT_TRUE(re.ok);
        const ObjectiveAtTarget v = EvaluateObjective(objective, perturbed, re.s, re.u, noise);
        ASSERT_TRUE(v.defined) << v.why;
        value[side] = v.value;
      }
      numeric[k] = (value[0] - value[1]) / (2 * kDelta);
    }
    const double scale = numeric.cwiseAbs().maxCoeff();
    EXPECT_GT(scale, objective == DesignObjective::kEndEffectorStd ? 1e-5 : 1e-2) << "the design must change the objective for the check to mean anything";
    const double error = (g - numeric).cwiseAbs().maxCoeff() / scale;
    RecordProperty("relative_error_seed" + std::to_string(seed), ::testing::PrintToString(error));
    EXPECT_LT(error, kTolerance)
        << GetParam().model << " seed " << seed << "\nanalytic " << g.transpose() << "\nnumeric  " << numeric.transpose();
    // The same check rejects a 0.1 % error.
    EXPECT_GT((1.001 * g - numeric).cwiseAbs().maxCoeff() / scale, 10 * kTolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Models, ObjectiveGradients,
    ::testing::Values(Case{"4dof_reduced", DesignObjective::kPayload}, Case{"4dof_reduced", DesignObjective::kPeakPush},
                      Case{"4dof_reduced", DesignObjective::kEndEffectorStd},
                      Case{"stewart_gough_6ups", DesignObjective::kPayload},
                      Case{"hybrid_ccma", DesignObjective::kPayload}, Case{"hybrid_ccma", DesignObjective::kPeakPush},
                      Case{"6dof_six_agents", DesignObjective::kEndEffectorStd}),
    [](const ::testing::TestParamInfo<Case>& info) {
      return info.param.model + "_" + DesignObjectiveName(info.param.objective);
    });

// The capacity is where the limiting effort meets its limit: statics with
// that payload puts it on the limit, every other effort within.
TEST(PayloadCapacity, PutsTheLimitingEffortOnItsLimit) {
  for (const std::string name : {"4dof_reduced", "stewart_gough_6ups", "hybrid_ccma"}) {
    const Model model = WithLoads(LoadReference(name), 9);
    const Solved at = ReachNearHome(model, 3);
    ASSERT_TRUE(at.ok) << name;
    const PayloadCapacity c = ComputePayloadCapacity(model, at.s, at.u);
    ASSERT_TRUE(c.defined) << name << ": " << c.why;
    ASSERT_GT(c.mass, 0) << name;
    Model loaded = model;
    loaded.end_effector.payload.mass = c.mass;
    const StaticsReport at_capacity = ComputeStatics(loaded, at.s, at.u);
    EXPECT_TRUE(at_capacity.within_limits) << name;
    loaded.end_effector.payload.mass = c.mass * (1 + 1e-6);
    const StaticsReport beyond = ComputeStatics(loaded, at.s, at.u);
    ASSERT_EQ(beyond.limiting.size(), 1u) << name;
    EXPECT_EQ(beyond.limiting[0], c.limiting) << name;
  }
}

// The command line: the example raises its payload by shortening the links
// (docs/statics.md), and statics on the written model reports more at
// home as well; an unknown objective is bad input (exit 2, nothing on
// stdout); an objective the model cannot define is a warning, not a value.
TEST(DesignObjectiveCommand, RaisesThePayloadOfTheExample) {
  const std::string examples = std::string(CCMA_MODELS_DIR) + "/../examples/statics/";
  const std::string out = ccma::testing::TestDir() + "/payload_designed.yaml";
  const testing::ToolRun run = testing::RunTool(
      {"design", "--model=" + examples + "4dof_payload.yaml", "--targets=" + examples + "4dof_payload_targets.csv",
       "--out=" + out, "--objective=payload", "--vary_length=joint2:joint1,joint5:joint4,joint8:joint7",
       "--max_change=0.3"});
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_TRUE(j["converged"].get<bool>());
  const double before = j["objective"]["before"]["value"], after = j["objective"]["after"]["value"];
  EXPECT_GT(after, before + 1.0);
  for (const auto& target : j["targets"]) EXPECT_TRUE(target["reached"].get<bool>());
  // The written model carries more at home too, by statics alone.
  const testing::ToolRun statics_before = testing::RunTool({"statics", "--model=" + examples + "4dof_payload.yaml"});
  const testing::ToolRun statics_after = testing::RunTool({"statics", "--model=" + out});
  ASSERT_EQ(statics_after.status, 0) << statics_after.err;
  EXPECT_GT(nlohmann::json::parse(statics_after.out)["payload_capacity"]["mass"].get<double>(),
            nlohmann::json::parse(statics_before.out)["payload_capacity"]["mass"].get<double>() + 1.0);

  const testing::ToolRun bad = testing::RunTool(
      {"design", "--model=" + examples + "4dof_payload.yaml", "--targets=" + examples + "4dof_payload_targets.csv",
       "--out=" + out, "--objective=stiffness", "--vary_length=joint2:joint1"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_TRUE(bad.out.empty());
  EXPECT_NE(bad.err.find("--objective"), std::string::npos) << bad.err;

  const testing::ToolRun undefined = testing::RunTool(
      {"design", "--model=" + std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml",
       "--targets=" + examples + "4dof_payload_targets.csv", "--out=" + out, "--objective=payload",
       "--vary_length=joint2:joint1"});
  ASSERT_EQ(undefined.status, 0) << undefined.err;
  const nlohmann::json u = nlohmann::json::parse(undefined.out);
  EXPECT_TRUE(u["objective"]["after"].is_null());
  EXPECT_NE(u["warning"].get<std::string>().find("effort_limits"), std::string::npos) << u["warning"];
}

}  // namespace
}  // namespace ccma
