// Design parameters (analyses/design.h): ds/dp and dX_EE/dp against central
// differences of RE-SOLVED forward problems on perturbed models (1e-6
// relative) at seeded random reachable controls on several bundled models;
// the same check rejects a wrong dG/dp; applying parameters round-trips; and
// `ccma design` makes the bundled 4-DOF system reach targets above its
// z-range, verified on the written model by a separate ControlProblem.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ccma/internal/constraint_set.h"
#include "formats/model_loader.h"
#include "ccma/rotation.h"
#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "analyses/design.h"
#include "tests/tool_run.h"

namespace ccma {
namespace design_test {

using testing::RunTool;
using testing::Slurp;
using testing::ToolRun;

constexpr double kRelativeTolerance = 1e-6;
constexpr double kStep = 1e-5;  // finite-difference step in p [m]

Model LoadReference(const std::string& name) {
  return LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
}

double RelativeError(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric) {
  return (analytic - numeric).cwiseAbs().maxCoeff() / std::max(numeric.cwiseAbs().maxCoeff(), 1e-12);
}

// A mix of every parameter kind: the full point of joint 0 (a base
// attachment in every bundled model), the length from the first joint
// sharing a body with joint 2 to joint 2... and one coordinate of the last joint.
DesignParameters MixedParameters(const Model& model) {
  DesignParameters params;
  std::string why;
  EXPECT_TRUE(AddJointCoordinates(model, model.joints[0].name + ".point", &params, &why)) << why;
  const int n = static_cast<int>(model.joints.size());
  bool length = false;
  for (int b = 2; b < n - 1 && !length; ++b) {
    for (int a = 1; a < n - 1 && !length; ++a) {
      if (a == b) continue;
      DesignParameters trial = params;
      if (AddLinkLength(model, model.joints[a].name + ":" + model.joints[b].name, &trial, &why)) {
        params = trial;
        length = true;
      }
    }
  }
  EXPECT_TRUE(length) << model.name;
  EXPECT_TRUE(AddJointCoordinates(model, model.joints[n - 1].name + ".z", &params, &why)) << why;
  return params;
}

// Seeded random reachable controls that deform the mechanism (a rigid move
// of the whole system would leave every joint at its home relative pose,
// where moving a shared joint point changes nothing): the controls that put
// the end-effector at a seeded random pose near home (ControlProblem), with
// the state they assemble to.
struct Reached {
  Eigen::VectorXd u;
  State s;
  bool reached = false;
};
Reached RandomReachableControls(const Model& model, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1, 1);
  ControlProblem control(model);
  control.SetControls(model.home_controls());
  PoseTarget target = control.CurrentPose();
  for (int i = 0; i < 3; ++i) target.position[i] += 0.03 * uniform(rng);
  for (int i = 0; i < 3; ++i) target.rpy[i] += 0.05 * uniform(rng);
  const ControlResult r = control.MoveTo(target);
  return {control.controls(), control.forward().state(), r.converged && r.assembled};
}

// "1.2e-09", for the test report (RecordProperty).
std::string Scientific(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2e", x);
  return buffer;
}

struct Numeric {
  Eigen::MatrixXd ds_dp, dX_dp;
};

// Central differences of the forward problem re-solved on the perturbed
// models (p +- h e_k) at the same controls, from the assembled state.
Numeric CentralDifferences(const Model& model, const DesignParameters& params, const State& s,
                           const Eigen::VectorXd& u) {
  const Eigen::VectorXd p = ParameterValues(model, params);
  Numeric out{Eigen::MatrixXd(s.tangent_size(), params.size()), Eigen::MatrixXd(6, params.size())};
  for (int k = 0; k < params.size(); ++k) {
    State side[2];
    EndEffectorPose pose[2];
    for (int i = 0; i < 2; ++i) {
      Eigen::VectorXd pk = p;
      pk[k] += i == 0 ? kStep : -kStep;
      const Model perturbed = ApplyParameters(model, params, pk);
      ForwardProblem forward(perturbed);
      forward.Restore(s, u);
      const ForwardResult r = forward.Solve(u);
      EXPECT_TRUE(r.converged) << model.name << " " << params.list[k].label;
      side[i] = forward.state();
      pose[i] = forward.end_effector();
    }
    out.ds_dp.col(k) = side[0].Minus(side[1]) / (2 * kStep);
    out.dX_dp.col(k).head<3>() = (pose[0].position - pose[1].position) / (2 * kStep);
    out.dX_dp.col(k).tail<3>() =
        QuaternionLog(Eigen::Quaterniond(pose[0].rotation * pose[1].rotation.transpose())) / (2 * kStep);
  }
  return out;
}

class ParameterSensitivities : public ::testing::TestWithParam<std::string> {};

TEST_P(ParameterSensitivities, MatchReSolvedCentralDifferences) {
  const Model model = LoadReference(GetParam());
  const DesignParameters params = MixedParameters(model);
  ASSERT_GE(params.size(), 5);
  for (unsigned seed : {1u, 2u, 3u}) {
    const Reached at = RandomReachableControls(model, seed);
    ASSERT_TRUE(at.reached) << GetParam() << " seed " << seed;
    const Eigen::VectorXd& u = at.u;
    const State& s = at.s;
    ParameterSensitivity sens;
    ASSERT_TRUE(ComputeParameterSensitivity(model, params, ParameterValues(model, params), s, u, &sens));
    const Numeric numeric = CentralDifferences(model, params, s, u);
    // The parameters really move the mechanism (a check of zeros proves nothing).
    EXPECT_GT(numeric.ds_dp.cwiseAbs().maxCoeff(), 1e-2);
    RecordProperty("ds_dp_relative_error_seed" + std::to_string(seed), Scientific(RelativeError(sens.ds_dp, numeric.ds_dp)));
    RecordProperty("dX_dp_relative_error_seed" + std::to_string(seed), Scientific(RelativeError(sens.dX_dp, numeric.dX_dp)));
    EXPECT_LT(RelativeError(sens.ds_dp, numeric.ds_dp), kRelativeTolerance) << GetParam() << " seed " << seed;
    EXPECT_LT(RelativeError(sens.dX_dp, numeric.dX_dp), kRelativeTolerance) << GetParam() << " seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(BundledModels, ParameterSensitivities,
                         ::testing::Values("4dof_reduced", "4dof_complete", "6dof_six_agents", "6dof_symmetric"));

// The same comparison fails for a wrong dG/dp: one body's rows dropped (a
// forgotten block) and a 0.1 % scale error (a wrong step or unit).
TEST(ParameterSensitivities, CheckRejectsAWrongEnergyGradientJacobian) {
  const Model model = LoadReference("4dof_reduced");
  const DesignParameters params = MixedParameters(model);
  const Reached at = RandomReachableControls(model, 7);
  ASSERT_TRUE(at.reached);
  const Eigen::VectorXd& u = at.u;
  const State& s = at.s;
  const Eigen::VectorXd p = ParameterValues(model, params);
  const Eigen::MatrixXd dG_dp = EnergyGradientParameterJacobian(model, params, p, s, u);
  const Numeric numeric = CentralDifferences(model, params, s, u);
  const ConstraintSet constraints(model);
  Eigen::MatrixXd ds_dp;
  double rcond = 0;
  ASSERT_TRUE(SolveStateParameterSensitivity(constraints, s, u, dG_dp, &ds_dp, &rcond));
  EXPECT_LT(RelativeError(ds_dp, numeric.ds_dp), kRelativeTolerance);

  Eigen::MatrixXd dropped = dG_dp;
  const int body = model.joints[0].body_b;  // the post on base0
  dropped.middleRows(6 * body, 6).setZero();
  ASSERT_TRUE(SolveStateParameterSensitivity(constraints, s, u, dropped, &ds_dp, &rcond));
  EXPECT_GT(RelativeError(ds_dp, numeric.ds_dp), 1e-2);

  ASSERT_TRUE(SolveStateParameterSensitivity(constraints, s, u, 1.001 * dG_dp, &ds_dp, &rcond));
  EXPECT_GT(RelativeError(ds_dp, numeric.ds_dp), 100 * kRelativeTolerance);
}

// Applying parameters: the values read back are those set, both body-frame
// copies of a moved joint name the same world point, a length moves the
// joint along its line, and nothing else changes.
TEST(DesignParameters, ApplyRoundTripsAndMovesOnlyTheNamedJoints) {
  const Model model = LoadReference("4dof_reduced");
  DesignParameters params;
  std::string why;
  ASSERT_TRUE(AddLinkLength(model, "joint1:joint2", &params, &why)) << why;
  ASSERT_TRUE(AddJointCoordinates(model, "joint3.point", &params, &why)) << why;
  const Eigen::VectorXd p0 = ParameterValues(model, params);
  EXPECT_NEAR(p0[0], 0.5, 1e-8);  // the bundled link: 0.25 up, 0.433 across
  Eigen::VectorXd p = p0;
  p[0] = 0.7;
  p.tail<3>() += Eigen::Vector3d(0.01, -0.02, 0.03);
  const Model changed = ApplyParameters(model, params, p);
  EXPECT_LT((ParameterValues(changed, params) - p).norm(), 1e-12);
  for (int j : {2, 3}) {
    const Joint& joint = changed.joints[j];
    const Body& b = changed.bodies[joint.body_b];
    EXPECT_LT((b.R_WB_home * joint.p_B + b.p_WB_home - JointPointWorld(changed, j)).norm(), 1e-12);
  }
  const Eigen::Vector3d along = JointPointWorld(changed, 2) - JointPointWorld(model, 1);
  EXPECT_NEAR(along.norm(), 0.7, 1e-12);
  EXPECT_LT(along.normalized().cross(JointPointWorld(model, 2) - JointPointWorld(model, 1)).norm(), 1e-12);
  for (int j = 0; j < static_cast<int>(model.joints.size()); ++j) {
    if (j == 2 || j == 3) continue;
    EXPECT_EQ(changed.joints[j].p_A, model.joints[j].p_A) << j;
    EXPECT_EQ(changed.joints[j].p_B, model.joints[j].p_B) << j;
  }
  // Rejections name the item.
  DesignParameters bad;
  EXPECT_FALSE(AddJointCoordinates(model, "joint99.x", &bad, &why));
  EXPECT_NE(why.find("joint99"), std::string::npos);
  EXPECT_FALSE(AddJointCoordinates(model, "joint1.w", &bad, &why));
  EXPECT_FALSE(AddLinkLength(model, "joint0:joint8", &bad, &why));  // no shared body
  EXPECT_FALSE(AddLinkLength(model, "joint1-joint2", &bad, &why));
  EXPECT_FALSE(AddJointCoordinates(model, "joint2.z", &params, &why));  // already varied
  // A joint is varied once (docs/design.md): another coordinate of a joint
  // already varied, or of a length's anchor, is refused and nothing added.
  DesignParameters one;
  ASSERT_TRUE(AddJointCoordinates(model, "joint4.x", &one, &why)) << why;
  for (const char* item : {"joint4.z", "joint4.point", "joint4.x"}) {
    EXPECT_FALSE(AddJointCoordinates(model, item, &one, &why)) << item;
    EXPECT_NE(why.find("joint4"), std::string::npos) << why;
  }
  EXPECT_EQ(one.size(), 1);
  EXPECT_FALSE(AddJointCoordinates(model, "joint1.y", &params, &why));  // anchors length:joint1:joint2
  EXPECT_EQ(params.size(), 4);
}

// Reaches `target` from home on `model` with a fresh ControlProblem.
bool ReachedFromHome(const Model& model, const PoseTarget& target, double* error) {
  ControlProblem control(model);
  if (!control.SetControls(model.home_controls()).assembled) return false;
  const ControlResult r = control.MoveTo(target);
  *error = r.error;
  return r.converged && r.assembled && r.error < 1e-6;
}

// The example of docs/design.md: the bundled 4-DOF system cannot lift its
// end-effector to the targets of models/targets/4dof_high_z.csv (the
// paper's stated limitation); `ccma design` lengthening the three posts
// (the link from the base joint to the post-top joint) makes every target
// reachable, checked on the written file by a separate ControlProblem per
// target. The same with the post-top points' heights as the parameters.
class DesignExample : public ::testing::TestWithParam<std::string> {};

TEST_P(DesignExample, LengthensThePostsSoThatHighTargetsBecomeReachable) {
  const std::string models = CCMA_MODELS_DIR;
  const std::string targets_path = models + "/targets/4dof_high_z.csv";
  const std::string out = ccma::testing::TestDir() + "/design_4dof_high_z.yaml";
  const ToolRun r = RunTool({"design", "--model=" + models + "/4dof_reduced.yaml", "--targets=" + targets_path,
                             "--out=" + out, GetParam()});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);
  EXPECT_TRUE(json["converged"].get<bool>()) << r.out;
  ASSERT_EQ(json["reached"].size(), 3u);
  ASSERT_EQ(json["changed"].size(), 3u);

  const Model before = LoadReference("4dof_reduced");
  const Model after = LoadModel(out);
  std::vector<PoseTarget> targets;
  for (const Waypoint& w : LoadWaypoints(targets_path)) targets.push_back({w.position, w.rpy});
  ASSERT_EQ(targets.size(), 3u);
  for (size_t t = 0; t < targets.size(); ++t) {
    double error = 0;
    EXPECT_FALSE(ReachedFromHome(before, targets[t], &error)) << "target " << t << " was already reachable";
    EXPECT_GT(error, 1e-3) << t;  // the bundled legs fall centimetres short
    EXPECT_TRUE(ReachedFromHome(after, targets[t], &error)) << "target " << t << " error " << error;
    EXPECT_TRUE(json["reached"][t].get<bool>());
    EXPECT_FALSE(json["reached_before"][t].get<bool>());
    EXPECT_GE(json["targets"][t]["min_singular_value"].get<double>(), 0.02);
  }
  // Only the three post-top z numbers changed: same line count, the other
  // lines byte for byte.
  std::istringstream a(Slurp(models + "/4dof_reduced.yaml")), b(Slurp(out));
  int differing = 0;
  for (std::string la, lb; std::getline(a, la);) {
    ASSERT_TRUE(static_cast<bool>(std::getline(b, lb)));
    if (la != lb) {
      ++differing;
      EXPECT_NE(la.find("between: [post"), std::string::npos) << la;
    }
  }
  EXPECT_EQ(differing, 3);
  for (int j : {1, 4, 7}) {
    EXPECT_GT(JointPointWorld(after, j).z(), 0.4) << j;
    EXPECT_EQ(JointPointWorld(after, j).head<2>(), JointPointWorld(before, j).head<2>()) << j;
  }
}

INSTANTIATE_TEST_SUITE_P(PostLengthsOrPoints, DesignExample,
                         ::testing::Values("--vary_length=joint0:joint1,joint3:joint4,joint6:joint7",
                                           "--vary=joint1.z,joint4.z,joint7.z"));

// Hostile input: exit 2, nothing on stdout, the flag or item named.
TEST(DesignCommand, RejectsBadInputNamingTheFlag) {
  const std::string models = CCMA_MODELS_DIR;
  const std::string model = "--model=" + models + "/4dof_reduced.yaml";
  const std::string targets = "--targets=" + models + "/targets/4dof_high_z.csv";
  const std::string out = "--out=" + ccma::testing::TestDir() + "/design_bad.yaml";
  struct Case {
    std::vector<std::string> args;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {{"design", model, targets, out, "--vary=nosuch.z"}, "nosuch"},
      {{"design", model, targets, out, "--vary=joint1.w"}, "--vary"},
      {{"design", model, targets, out, "--vary=joint1.x,joint1.z"}, "'joint1.z': the point of joint 'joint1'"},
      {{"design", model, targets, out, "--vary_length=joint0:joint8"}, "--vary_length"},
      {{"design", model, targets, out}, "--vary"},
      {{"design", model, targets, out, "--vary=joint1.z", "--max_change=0"}, "max_change"},
      {{"design", model, targets, out, "--vary=joint1.z", "--min_singular_value=nan"}, "min_singular_value"},
      {{"design", model, "--targets=" + models + "/4dof_reduced.yaml", out, "--vary=joint1.z"}, "4dof_reduced.yaml"},
  };
  for (const Case& c : cases) {
    const ToolRun r = RunTool(c.args);
    EXPECT_EQ(r.status, 2) << c.args.back() << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
  }
}

// A model saved with a UTF-8 byte-order mark is designed and patched exactly
// as without it (the numbers used to be patched 3 bytes early and the result
// refused); the written file keeps its mark.
TEST(DesignCommand, AByteOrderMarkChangesNothing) {
  const std::string models = CCMA_MODELS_DIR;
  const std::string plain_model = models + "/4dof_reduced.yaml";
  const std::string bom_model = ccma::testing::TestDir() + "/design_bom.yaml";
  const std::string bom = "\xEF\xBB\xBF";
  std::ofstream(bom_model, std::ios::binary) << bom << Slurp(plain_model);
  const std::string plain_out = ccma::testing::TestDir() + "/design_plain_out.yaml";
  const std::string bom_out = ccma::testing::TestDir() + "/design_bom_out.yaml";
  const std::string targets = "--targets=" + models + "/targets/4dof_high_z.csv";
  const std::string vary = "--vary=joint1.z,joint4.z,joint7.z";
  const ToolRun plain = RunTool({"design", "--model=" + plain_model, targets, "--out=" + plain_out, vary});
  const ToolRun marked = RunTool({"design", "--model=" + bom_model, targets, "--out=" + bom_out, vary});
  ASSERT_EQ(plain.status, 0) << plain.err;
  ASSERT_EQ(marked.status, 0) << marked.err;
  const nlohmann::json a = nlohmann::json::parse(plain.out), b = nlohmann::json::parse(marked.out);
  EXPECT_TRUE(b["converged"].get<bool>()) << marked.out;
  EXPECT_EQ(a["changed"], b["changed"]);
  EXPECT_EQ(a["reached"], b["reached"]);
  EXPECT_EQ(a["iterations"], b["iterations"]);
  const std::string plain_text = Slurp(plain_out);
  EXPECT_NE(plain_text, Slurp(plain_model));  // something was patched
  EXPECT_EQ(Slurp(bom_out), bom + plain_text);
}

// --out is checked before the design runs: 150 targets take the loop about a
// minute, a directory or a missing folder as --out is refused at once.
TEST(DesignCommand, ABadOutIsRefusedBeforeTheRun) {
  const std::string models = CCMA_MODELS_DIR;
  const std::string targets = ccma::testing::TestDir() + "/design_many_targets.csv";
  {
    std::ofstream csv(targets);
    csv << "time,x,y,z,roll,pitch,yaw\n";
    for (int i = 0; i < 150; ++i) csv << i << ",0," << 0.0002 * i << ",0.95,0,0,0\n";
  }
  const std::string dir = ccma::testing::TestDir() + "/design_out_dir";
  std::filesystem::create_directories(dir);
  for (const auto& [out, expected] : std::vector<std::pair<std::string, std::string>>{
           {dir, "is a directory"}, {dir + "/missing/new.yaml", "cannot write"}}) {
    const ToolRun r = RunTool({"design", "--model=" + models + "/4dof_reduced.yaml", "--targets=" + targets,
                               "--out=" + out, "--vary=joint1.z,joint4.z,joint7.z"});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("'" + out + "'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_LT(r.seconds, 5 * ccma::testing::kTestTimeFactor) << "the design ran before --out was checked";
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));  // no temporary file left behind
}

}  // namespace
}  // namespace ccma
