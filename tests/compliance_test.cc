// Linear compliance in statics (analyses/compliance.h, `ccma statics`):
// Gosselin's stiffness mapping C = Jx diag(1/k) Jx^T on a Stewart-Gough
// platform and a planar 3-RPR (Jx = dX/du by finite differences of re-solved
// forward problems), springs in series on a cantilever, a mobile base's
// closed form, the four-agent CCMA's yielded bases re-assembled, virtual work
// of the compliant mechanism, and rigid models left as they were.
#include <cmath>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <Eigen/LU>

#include "analyses/payload.h"
#include "analyses/statics.h"
#include "bundled_models.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/dense_factorizations.h"
#include "ccma/loads.h"
#include "ccma/rotation.h"
#include "formats/model_loader.h"
#include "problems/forward_problem.h"
#include "problems/internal/compliant_equilibrium.h"
#include "model_text.h"
#include "tool_run.h"
#include "tests/tool_run.h"

namespace ccma {
namespace compliance_test {

using testing::InsertAfterEach;
using testing::ReadModel;

// X = [p; rotation vector] differences: dX/du by central differences of
// forward problems re-solved at u +- h e_i.
Eigen::MatrixXd ControlJacobianByDifferences(const Model& model, const Eigen::VectorXd& u, double h) {
  ForwardProblem forward(model);
  Eigen::MatrixXd J(6, u.size());
  for (int i = 0; i < u.size(); ++i) {
    Eigen::VectorXd up = u, down = u;
    up[i] += h;
    down[i] -= h;
    EXPECT_TRUE(forward.Solve(up).assembled);
    const EndEffectorPose plus = forward.end_effector();
    EXPECT_TRUE(forward.Solve(down).assembled);
    const EndEffectorPose minus = forward.end_effector();
    J.block<3, 1>(0, i) = (plus.position - minus.position) / (2 * h);
    J.block<3, 1>(3, i) = QuaternionLog(Eigen::Quaterniond(plus.rotation * minus.rotation.transpose())) / (2 * h);
  }
  return J;
}

StaticsReport StaticsAtHome(const Model& model, const ExternalWrench& wrench = {}) {
  ForwardProblem forward(model);
  EXPECT_TRUE(forward.Solve(model.home_controls()).assembled);
  return ComputeStatics(model, forward.state(), forward.controls(), wrench);
}

// Gosselin: the legs are the only springs, so C = Jx diag(1/k) Jx^T.
void ExpectGosselin(const Model& model, const std::vector<double>& k) {
  const StaticsReport r = StaticsAtHome(model);
  ASSERT_TRUE(r.compliant);
  const Eigen::MatrixXd Jx = ControlJacobianByDifferences(model, model.home_controls(), 1e-4);
  Eigen::VectorXd inverse_k(static_cast<int>(k.size()));
  for (size_t i = 0; i < k.size(); ++i) inverse_k[static_cast<int>(i)] = 1.0 / k[i];
  const Eigen::MatrixXd expected = Jx * inverse_k.asDiagonal() * Jx.transpose();
  const Eigen::Matrix<double, 6, 6>& C = r.compliance.ee_compliance;
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_LT((C - expected).cwiseAbs().maxCoeff(), 1e-6 * scale) << "C\n" << C << "\nexpected\n" << expected;
  EXPECT_EQ((C - C.transpose()).cwiseAbs().maxCoeff(), 0.0);  // symmetric exactly
  EXPECT_TRUE(r.compliance.held);
  EXPECT_TRUE(r.balanced);
}

TEST(Compliance, StewartGoughLegStiffnessIsGosselinsMapping) {
  const std::vector<double> k = {1e5, 2e5, 0.5e5, 1.5e5, 3e5, 0.8e5};
  std::vector<std::string> extra;
  for (double v : k) extra.push_back(" stiffness: " + std::to_string(v) + ",");
  const Model model = LoadModelFromString(
      InsertAfterEach(ReadModel("stewart_gough_6ups"), "type: prismatic, actuated: true,", extra), "sg.yaml");
  ExpectGosselin(model, k);
  const StaticsReport r = StaticsAtHome(model);
  ASSERT_TRUE(r.compliance.stiffness_defined);  // six legs hold all six directions
  const Eigen::Matrix<double, 6, 6> product = r.compliance.ee_stiffness * r.compliance.ee_compliance;
  EXPECT_LT((product - Eigen::Matrix<double, 6, 6>::Identity()).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(Compliance, PlanarThreeRprIsGosselinsMappingAndRigidOutOfPlane) {
  const std::vector<double> k = {1e5, 2e5, 3e5};
  std::vector<std::string> extra;
  for (double v : k) extra.push_back(" stiffness: " + std::to_string(v) + ",");
  const Model model = LoadModelFromString(
      InsertAfterEach(ReadModel("planar_3rpr"), "type: prismatic, actuated: true,", extra), "rpr.yaml");
  ExpectGosselin(model, k);
  const StaticsReport r = StaticsAtHome(model);
  const Eigen::Matrix<double, 6, 6>& C = r.compliance.ee_compliance;
  for (int out_of_plane : {2, 3, 4}) {  // z, roll, pitch
    EXPECT_LT(C.row(out_of_plane).cwiseAbs().maxCoeff(), 1e-12 * C.cwiseAbs().maxCoeff()) << out_of_plane;
  }
  EXPECT_GT(C(0, 0), 0.0);
  EXPECT_FALSE(r.compliance.stiffness_defined);
  EXPECT_NE(r.compliance.stiffness_note.find("singular"), std::string::npos);
  EXPECT_NEAR(r.compliance.most_compliant_direction.z(), 0.0, 1e-9);  // the softest push is in the plane
}

// The lowest stiffness allowed on one leg of the compliant Stewart-Gough
// example (1e-6 N/m against 5e7 N/m of bearing play): the linear answer is
// balanced and held (a deflection of kilometres, which the report calls
// outside the linear range), and the stiffness that cannot be inverted is
// said to be ill-conditioned, not held rigidly. A planar robot's
// out-of-plane directions are still held rigidly.
TEST(Compliance, OneVerdictAtTheLowestStiffness) {
  const std::string text = testing::Slurp(std::string(CCMA_SOURCE_DIR) + "/examples/statics/stewart_gough_compliant.yaml");
  for (const char* k : {"1.0e-6", "1.0e-2", "1.0"}) {
    std::string soft = text;
    const std::string leg = "actuated: true, stiffness: 2.0e5, limits: [-0.1, 0.1], between: [leg0_lower";
    ASSERT_NE(soft.find(leg), std::string::npos);
    soft.replace(soft.find(leg), leg.size(),
                 std::string("actuated: true, stiffness: ") + k + ", limits: [-0.1, 0.1], between: [leg0_lower");
    const StaticsReport r = StaticsAtHome(LoadModelFromString(soft, "soft.yaml"));
    EXPECT_TRUE(r.balanced) << k << ": " << r.residual;
    EXPECT_TRUE(r.compliance.held) << k;
    EXPECT_GT(r.compliance.max_body_m, 1.0) << k;
    EXPECT_NE(r.compliance.range_note.find("not small"), std::string::npos) << k;
    if (!r.compliance.stiffness_defined) {
      EXPECT_EQ(r.compliance.stiffness_note.find("rigidly"), std::string::npos) << r.compliance.stiffness_note;
      EXPECT_NE(r.compliance.stiffness_note.find("ill-conditioned"), std::string::npos) << r.compliance.stiffness_note;
    }
  }
  const StaticsReport stiff = StaticsAtHome(LoadModel(std::string(CCMA_SOURCE_DIR) + "/examples/statics/stewart_gough_compliant.yaml"));
  EXPECT_TRUE(stiff.compliance.range_note.empty());
  const Model planar = LoadModelFromString(
      InsertAfterEach(ReadModel("planar_3rpr"), "type: prismatic, actuated: true,", {" stiffness: 1e-6,", " stiffness: 1e5,", " stiffness: 1e5,"}),
      "rpr.yaml");
  EXPECT_NE(StaticsAtHome(planar).compliance.stiffness_note.find("rigidly"), std::string::npos);
}

using testing::Cantilever;

TEST(Compliance, SpringsInSeriesOnACantileverAddTheirCompliances) {
  const double k1 = 2e3, k2 = 5e3, kt = 4e5, a = 0.3, L = 1.2, F = 7.0;
  ExternalWrench down;
  down.force = Eigen::Vector3d(0, 0, -F);
  for (const bool with_translation : {false, true}) {
    const std::string weld = with_translation ? "{rotation: 5000, translation: 400000}" : "{rotation: 5000}";
    const Model model = LoadModelFromString(Cantilever(k1, a, weld, L), "cantilever.yaml");
    const StaticsReport r = StaticsAtHome(model, down);
    const double compliance = L * L / k1 + (L - a) * (L - a) / k2 + (with_translation ? 1 / kt : 0.0);
    EXPECT_NEAR(r.compliance.deflection[2], -F * compliance, 1e-12) << with_translation;
    EXPECT_NEAR(r.compliance.ee_compliance(2, 2), compliance, 1e-14);
    EXPECT_NEAR(r.compliance.ee_compliance(4, 4), 1 / k1 + 1 / k2, 1e-14);  // pitch
    EXPECT_NEAR(r.compliance.most_compliant, compliance, 1e-14);
    EXPECT_NEAR(r.compliance.most_compliant_direction.z(), 1.0, 1e-12);
    // The motor holds F L; the weld holds F and the moment F (L - a) on the beam.
    EXPECT_NEAR(std::abs(r.actuators[0].effort), F * L, 1e-9);
    EXPECT_NEAR(r.joints[1].force.z(), F, 1e-9);
    EXPECT_NEAR(r.joints[1].moment.y(), -F * (L - a), 1e-9);
    EXPECT_TRUE(r.determinate);
    EXPECT_TRUE(r.balanced);
  }
}

// One omni base (k = [kx, ky, ktheta]) carries a welded post; the end-effector
// is R out along x: a push F along y yields F / ky plus R^2 F / ktheta.
TEST(Compliance, AMobileBaseYieldsAlongItsControls) {
  const double kx = 2e4, ky = 3e4, kt = 500, R = 0.4;
  const std::string text =
      "name: one_base\ngravity: [0, 0, 0]\nbodies:\n  - {name: post, position: [0.2, 0, 0.5]}\n"
      "mobile_bases:\n  - {name: base0, type: omni, actuation: complete, pose: [0, 0, 0], stiffness: [20000, 30000, "
      "500]}\njoints:\n  - {type: fixed, between: [base0, post], point: [0, 0, 0.2]}\n"
      "end_effector: {body: post, point: [0.4, 0, 0.9], controlled: [x, y, z, yaw]}\n";
  const Model model = LoadModelFromString(text, "one_base.yaml");
  ExternalWrench push;
  push.force = Eigen::Vector3d(0, 10, 0);
  const StaticsReport r = StaticsAtHome(model, push);
  const Eigen::Matrix<double, 6, 6>& C = r.compliance.ee_compliance;
  EXPECT_NEAR(C(0, 0), 1 / kx, 1e-15);
  EXPECT_NEAR(C(1, 1), 1 / ky + R * R / kt, 1e-15);
  EXPECT_NEAR(C(1, 5), R / kt, 1e-15);
  EXPECT_NEAR(C(5, 5), 1 / kt, 1e-15);
  EXPECT_LT(C(2, 2), 1e-18);  // the floor holds it vertically
  EXPECT_NEAR(r.compliance.deflection[1], 10 * (1 / ky + R * R / kt), 1e-15);
  // Efforts: the base's y motor holds -10 N and its heading -R 10 N*m (e = -k delta).
  EXPECT_NEAR(r.actuators[1].effort, -10.0, 1e-9);
  EXPECT_NEAR(r.actuators[2].effort, -10.0 * R, 1e-9);
  EXPECT_FALSE(r.compliance.stiffness_defined);
}

// The springs' energy minus the wrench's work, V(u') = 1/2 (u' - u0)^T K
// (u' - u0) - w . (X(u') - X(u0)) with X from the rigid forward problem, is
// stationary at the yielded controls u along every control change the
// mechanism allows (dC/ds ds + dC/du du = 0): central differences of V over
// re-solved forward problems, against the size of either term.
void ExpectEnergyStationary(const Model& model, const Eigen::VectorXd& u, const ExternalWrench& w,
                            const std::string& stem) {
  const Eigen::VectorXd u0 = model.home_controls();
  Eigen::VectorXd k(model.num_controls());
  for (int c = 0; c < k.size(); ++c) k[c] = model.mobile_bases[static_cast<size_t>(c / 3)].stiffness.k[c % 3];
  ForwardProblem forward(model);
  EXPECT_TRUE(forward.Solve(u0).assembled);
  const EndEffectorPose home = forward.end_effector();
  auto energy = [&](const Eigen::VectorXd& v) {
    EXPECT_LT(forward.Solve(v).residual_energy, 1e-20);
    const EndEffectorPose pose = forward.end_effector();
    const Eigen::Vector3d turn = QuaternionLog(Eigen::Quaterniond(pose.rotation * home.rotation.transpose()));
    const Eigen::VectorXd d = v - u0;
    return 0.5 * d.dot(k.asDiagonal() * d) - w.force.dot(pose.position - home.position) - w.moment.dot(turn);
  };
  EXPECT_TRUE(forward.Solve(u).assembled);
  Eigen::VectorXd C;
  Eigen::MatrixXd J_s, J_u;
  ConstraintSet(model).Evaluate(forward.state(), u, &C, &J_s, &J_u);
  Eigen::MatrixXd J(J_s.rows(), J_s.cols() + J_u.cols());
  J << J_s, J_u;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(J);  // its kernel basis: directions the forward problem assembles exactly
  lu.setThreshold(1e-10);
  const Eigen::MatrixXd allowed = lu.kernel().bottomRows(J_u.cols());
  const Eigen::VectorXd force = k.asDiagonal() * (u - u0);  // the springs' pull, -effort
  int stretching = 0;
  for (int i = 0; i < allowed.cols(); ++i) {
    if (allowed.col(i).norm() < 1e-6) continue;  // an idle motion: the controls stay
    const Eigen::VectorXd du = allowed.col(i).normalized();
    const double h = 1e-4;
    const double slope = (energy(u + h * du) - energy(u - h * du)) / (2 * h);
    EXPECT_LT(std::abs(slope), 1e-4 * force.norm()) << stem << " direction " << i;
    if (std::abs(force.dot(du)) > 1e-2 * force.norm()) ++stretching;  // a direction that tests something
  }
  const int checked = stretching;
  EXPECT_GT(checked, 0) << stem;
}

// The four-agent CCMA with stiff bases: the bases' yields (delta = -effort /
// k) re-assembled by the rigid forward problem put the end-effector where the
// linear deflection says, the mechanism assembles there (compatible), and the
// energy is stationary there (ExpectEnergyStationary).
TEST(Compliance, FourAgentBasesYieldCompatiblyAndMoveTheEndEffectorAsPredicted) {
  for (const std::string stem : {"4dof_complete", "4dof_reduced"}) {
    const std::string text = InsertAfterEach(ReadModel(stem), "type: omni,",
                                             {" stiffness: [2.0e4, 3.0e4, 600],", " stiffness: [1.0e4, 1.0e4, 400],",
                                              " stiffness: [3.0e4, 2.0e4, 900],"});
    const Model model = LoadModelFromString(text, stem + ".yaml");
    ExternalWrench w;
    w.force = Eigen::Vector3d(0.003, -0.002, -0.004);
    w.moment = Eigen::Vector3d(0.0, 0.0, 0.001);
    const StaticsReport r = StaticsAtHome(model, w);
    ASSERT_TRUE(r.compliant);
    Eigen::VectorXd u = model.home_controls();
    for (int c = 0; c < model.num_controls(); ++c) {
      u[c] -= r.actuators[static_cast<size_t>(c)].effort / model.mobile_bases[static_cast<size_t>(c / 3)].stiffness.k[c % 3];
    }
    ForwardProblem forward(model);
    ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
    const EndEffectorPose before = forward.end_effector();
    const ForwardResult yielded = forward.Solve(u);
    EXPECT_LT(yielded.residual_energy, 1e-20) << stem;  // the yields are compatible
    const Eigen::Vector3d moved = forward.end_effector().position - before.position;
    const Eigen::Vector3d predicted = r.compliance.deflection.head<3>();
    EXPECT_GT(predicted.norm(), 1e-8) << stem;
    EXPECT_LT((moved - predicted).norm(), 1e-4 * predicted.norm()) << stem << "\n" << moved << "\n" << predicted;
    ExpectEnergyStationary(model, u, w, stem);
  }
}

// Payload capacity of a compliant mechanism comes from the efforts `ccma
// statics` reports for it (the springs' sharing of the loads, unique), not
// from the rigid minimum-norm ones: with the capacity's payload on, the
// limiting base pushes exactly at its limit. The rigid 4-agent CCMA is
// statically indeterminate, so the two capacities differ.
TEST(Compliance, PayloadCapacityFollowsTheCompliantEfforts) {
  const std::string rigid_text =
      InsertAfterEach(ReadModel("4dof_reduced"), "type: omni,", {" push_limit: 40,", " push_limit: 35,", " push_limit: 45,"});
  const std::string text = InsertAfterEach(rigid_text, "type: omni,",
                                           {" stiffness: [2.0e4, 3.0e4, 600],", " stiffness: [1.0e4, 1.0e4, 400],",
                                            " stiffness: [3.0e4, 2.0e4, 900],"});
  const Model rigid = LoadModelFromString(rigid_text, "rigid.yaml");
  const Model model = LoadModelFromString(text, "compliant.yaml");
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  const State& s = forward.state();
  const Eigen::VectorXd& u = forward.controls();
  ASSERT_FALSE(ComputeStatics(rigid, s, u, {}).determinate);
  const PayloadCapacity capacity = ComputePayloadCapacity(model, s, u);
  ASSERT_TRUE(capacity.defined && !capacity.unbounded) << capacity.why;
  const PayloadCapacity rigid_capacity = ComputePayloadCapacity(rigid, s, u);
  ASSERT_TRUE(rigid_capacity.defined);
  EXPECT_GT(std::abs(capacity.mass - rigid_capacity.mass), 1e-3 * capacity.mass);
  Model loaded = model;
  if (!(model.end_effector.payload.mass > 0)) loaded.end_effector.payload.com_B = model.end_effector.p_B;
  loaded.end_effector.payload.mass += capacity.mass;
  const StaticsReport r = ComputeStatics(loaded, s, u, {});
  int at = -1;
  for (int k = 0; k < model.num_bases(); ++k) {
    if (model.mobile_bases[static_cast<size_t>(k)].name == capacity.limiting) at = k;
  }
  ASSERT_GE(at, 0) << capacity.limiting;
  const int first = model.base_control(at);
  const double push = std::hypot(r.control_efforts[first], r.control_efforts[first + 1]);
  EXPECT_NEAR(push, model.mobile_bases[static_cast<size_t>(at)].push_limit, 1e-9 * push);
}

// Virtual work in the compliant mechanism: along every motion the rigid rows
// allow, the loads and the springs do no work (f - H y is orthogonal to it),
// and the reported reactions balance every body.
TEST(Compliance, LoadsAndSpringsDoNoWorkAlongAllowedMotions) {
  const std::string text = InsertAfterEach(ReadModel("6dof_asymmetric"), "type: omni,",
                                           {" stiffness: [2.0e4, 3.0e4, 600],", " stiffness: [1.0e4, 1.0e4, 400],",
                                            " stiffness: [3.0e4, 2.0e4, 900],"});
  Model model = LoadModelFromString(text, "6dof.yaml");
  for (Joint& joint : model.joints) {
    if (joint.type == JointType::kRevolute) joint.stiffness.rotation = {3e3, 4e3};
  }
  model.end_effector.payload.mass = 2.0;
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  const ConstraintSet set(model);
  const CompliantEquilibrium system(model, set, forward.state(), forward.controls());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(system.size());
  f.head(model.state_size()) = GeneralizedLoads(model, forward.state());
  const Eigen::VectorXd y = system.Displacement(f);
  const Eigen::VectorXd g = f - system.SpringForce(y);
  MinimumNormSolver cod;
  cod.setThreshold(1e-10).compute(system.A());
  const Eigen::MatrixXd Z = cod.nullSpace();
  ASSERT_GT(Z.cols(), 0);
  EXPECT_LT((Z.transpose() * g).cwiseAbs().maxCoeff(), 1e-9 * f.cwiseAbs().maxCoeff());
  EXPECT_LT((system.A() * y).cwiseAbs().maxCoeff(), 1e-12);  // the deflection keeps the rigid rows
  const StaticsReport r = ComputeStatics(model, forward.state(), forward.controls());
  EXPECT_TRUE(r.balanced);
  EXPECT_TRUE(r.determinate);  // the springs decide how the redundant legs share the load
}

// An arm on a free vertical hinge: with the base held by its springs the arm
// still spins freely, which moves the end-effector: not held, said in a flag
// and a warning, no stiffness, and no NaN anywhere.
TEST(Compliance, AMechanismItsSpringsDoNotHoldIsReportedWithoutNaN) {
  const std::string path = ccma::testing::TestDir() + "/free_arm.yaml";
  std::ofstream(path) << "name: free_arm\nbodies:\n  - {name: post, position: [0, 0, 0.5]}\n"
                         "  - {name: arm, position: [0.3, 0, 1.0], mass: 1}\nmobile_bases:\n"
                         "  - {name: base0, type: omni, actuation: complete, pose: [0, 0, 0], stiffness: [2.0e4, 2.0e4, "
                         "500]}\njoints:\n  - {type: fixed, between: [base0, post], point: [0, 0, 0.2]}\n"
                         "  - {name: spin, type: revolute, between: [post, arm], point: [0, 0, 1.0], axis: [0, 0, 1]}\n"
                         "end_effector: {body: arm, point: [0.6, 0, 1.0], controlled: [x, y, z]}\n";
  const testing::ToolRun run = testing::RunTool({"statics", "--model=" + path});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.out.find("NaN"), std::string::npos);
  EXPECT_EQ(run.out.find("nan"), std::string::npos);
  const nlohmann::json out = nlohmann::json::parse(run.out);
  EXPECT_FALSE(out.at("deflection").at("held").get<bool>());
  EXPECT_TRUE(out.at("ee_stiffness").is_null());
  EXPECT_NE(out.at("ee_stiffness_note").get<std::string>().find("not held"), std::string::npos);
  EXPECT_NE(run.err.find("ccma statics: warning: the loaded mechanism is not held"), std::string::npos) << run.err;
  const Model model = LoadModel(path);
  const StaticsReport r = StaticsAtHome(model);
  EXPECT_TRUE(r.compliance.ee_compliance.allFinite());
  EXPECT_FALSE(r.compliance.held);
}

// Two actuated vertical slides at the same point carry one weight: rigid,
// any split is an equilibrium (indeterminate, the minimum-norm one is half
// each); compliant, the motors share it in proportion to their stiffness.
// A tripod of telescopic legs, spherical at both ends, apex 1 m above the
// centre of three feet on the unit circle (examples/statics/tripod.yaml, its
// coordinates exact here), each leg's motor a spring of stiffness k along it.
std::string SprungTripod(double k) {
  std::ostringstream text;
  text.precision(17);
  text << "name: sprung_tripod\nbodies:\n  - {name: top, position: [0, 0, 1], mass: 3}\n";
  std::ostringstream joints;
  joints.precision(17);
  for (int i = 0; i < 3; ++i) {
    const double a = M_PI / 2 + 2 * M_PI * i / 3, c = std::cos(a), s = std::sin(a);
    text << "  - {name: low" << i << ", position: [" << 0.75 * c << ", " << 0.75 * s << ", 0.25]}\n"
         << "  - {name: up" << i << ", position: [" << 0.25 * c << ", " << 0.25 * s << ", 0.75]}\n";
    joints << "  - {type: spherical, between: [world, low" << i << "], point: [" << c << ", " << s << ", 0]}\n"
           << "  - {name: leg" << i << ", type: prismatic, actuated: true, stiffness: " << k << ", between: [low" << i
           << ", up" << i << "], point: [" << 0.5 * c << ", " << 0.5 * s << ", 0.5], axis: [" << -c << ", " << -s
           << ", 1]}\n"
           << "  - {type: spherical, between: [up" << i << ", top], point: [0, 0, 1]}\n";
  }
  text << "joints:\n" << joints.str() << "end_effector: {body: top, point: [0, 0, 1], controlled: [x, y, z]}\n";
  return text.str();
}

// The tripod's apex spins freely on its three ball joints, which moves
// nothing it controls (x, y, z): held, with the controlled block's stiffness
// the legs' k * sum n n^T = k diag(3/4, 3/4, 3/2) (legs at 45 degrees); the
// whole end-effector's stiffness is not given, and says why. check calls
// the free spins harmless, not ill-posed.
TEST(Compliance, ATripodsFreeApexIsHeldInWhatItControls) {
  const double k = 2e4;
  const std::string path = ccma::testing::TestDir() + "/sprung_tripod.yaml";
  std::ofstream(path) << SprungTripod(k);
  const testing::ToolRun run = testing::RunTool({"statics", "--model=" + path});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.err.find("not held"), std::string::npos) << run.err;
  const nlohmann::json out = nlohmann::json::parse(run.out);
  EXPECT_TRUE(out.at("deflection").at("held").get<bool>());
  EXPECT_NEAR(out.at("deflection").at("end_effector")[2].get<double>(), -3 * 9.81 / (1.5 * k), 1e-15);
  EXPECT_TRUE(out.at("ee_stiffness").is_null());
  EXPECT_NE(out.at("ee_stiffness_note").get<std::string>().find("does not control"), std::string::npos);
  const nlohmann::json& K = out.at("controlled_stiffness");
  ASSERT_EQ(K.size(), 3u);
  const double hand[3] = {0.75 * k, 0.75 * k, 1.5 * k};
  for (int r = 0; r < 3; ++r) {
    ASSERT_EQ(K[r].size(), 3u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(K[r][c].get<double>(), r == c ? hand[r] : 0.0, 1e-9 * k) << r << c;
  }
  const testing::ToolRun check = testing::RunTool({"check", "--model=" + path});
  ASSERT_EQ(check.status, 0) << check.err;
  EXPECT_EQ(check.err.find("ill-posed"), std::string::npos) << check.err;
  EXPECT_NE(check.err.find("none moves what the model controls (x, y, z)"), std::string::npos) << check.err;
  // Controlling the apex's roll too makes its free spin a failure: not held.
  std::string rolled = SprungTripod(k);
  rolled.replace(rolled.find("controlled: [x, y, z]"), 21, "controlled: [x, y, z, roll]");
  std::ofstream(path) << rolled;
  const testing::ToolRun spun = testing::RunTool({"statics", "--model=" + path});
  ASSERT_EQ(spun.status, 0) << spun.err;
  const nlohmann::json spun_out = nlohmann::json::parse(spun.out);
  EXPECT_FALSE(spun_out.at("deflection").at("held").get<bool>());
  EXPECT_TRUE(spun_out.at("controlled_stiffness").is_null());
  const testing::ToolRun spun_check = testing::RunTool({"check", "--model=" + path});
  EXPECT_NE(spun_check.err.find("ill-posed"), std::string::npos) << spun_check.err;
}

TEST(Compliance, SpringsShareARedundantLoadInProportionToTheirStiffness) {
  const double k1 = 1e4, k2 = 3e4, W = 5 * 9.81;
  const std::string legs =
      "  - {name: left, type: prismatic, actuated: true, STIFF1between: [world, slider], point: [0, 0, 0], "
      "axis: [0, 0, 1]}\n"
      "  - {name: right, type: prismatic, actuated: true, STIFF2between: [world, slider], point: [0, 0, 0], "
      "axis: [0, 0, 1]}\n";
  const std::string head = "name: slides\nbodies:\n  - {name: slider, position: [0, 0, 0.5], mass: 5}\njoints:\n";
  const std::string tail = "end_effector: {body: slider, point: [0, 0, 0.5], controlled: [z]}\n";
  auto text = [&](const std::string& s1, const std::string& s2) {
    std::string t = head + legs + tail;
    t.replace(t.find("STIFF1"), 6, s1);
    t.replace(t.find("STIFF2"), 6, s2);
    return t;
  };
  const StaticsReport rigid = StaticsAtHome(LoadModelFromString(text("", ""), "rigid.yaml"));
  EXPECT_FALSE(rigid.determinate);
  EXPECT_NEAR(rigid.actuators[0].effort, W / 2, 1e-9);
  const std::string springs = "translation: 1.0e6, rotation: 1.0e4}, ";
  const StaticsReport r = StaticsAtHome(LoadModelFromString(
      text("stiffness: {axis: 1.0e4, " + springs, "stiffness: {axis: 3.0e4, " + springs), "compliant.yaml"));
  EXPECT_TRUE(r.determinate);
  EXPECT_NEAR(r.actuators[0].effort, W * k1 / (k1 + k2), 1e-9);
  EXPECT_NEAR(r.actuators[1].effort, W * k2 / (k1 + k2), 1e-9);
  EXPECT_NEAR(r.compliance.deflection[2], -W / (k1 + k2), 1e-12);
  EXPECT_NEAR(r.joints[0].force.z() + r.joints[1].force.z(), W, 1e-9);
}

// Virtual work with rigid controls: along every motion (w, du) the rigid rows
// allow (A w + A_u du = 0), the efforts, the loads and the springs do no work
// together: e . du = w . (H y - f).
TEST(Compliance, EffortsOfRigidControlsObeyVirtualWork) {
  Model model = LoadModelFromString(ReadModel("6dof_asymmetric"), "6dof.yaml");
  for (Joint& joint : model.joints) {
    if (joint.type == JointType::kRevolute) joint.stiffness.rotation = {3e3, 4e3};
  }
  model.end_effector.payload.mass = 2.0;
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  const ConstraintSet set(model);
  const CompliantEquilibrium system(model, set, forward.state(), forward.controls());
  ASSERT_TRUE(system.compliant_controls().empty());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(system.size());
  f.head(model.state_size()) = GeneralizedLoads(model, forward.state());
  const Eigen::VectorXd y = system.Displacement(f);
  const StaticsReport r = ComputeStatics(model, forward.state(), forward.controls());
  Eigen::VectorXd e(model.num_controls());
  for (int c = 0; c < e.size(); ++c) e[c] = r.actuators[static_cast<size_t>(c)].effort;
  MinimumNormSolver cod;
  cod.setThreshold(1e-10).compute(system.A());
  std::mt19937 rng(36);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd du(model.num_controls());
    for (int c = 0; c < du.size(); ++c) du[c] = normal(rng);
    const Eigen::VectorXd w = cod.solve(-system.A_u() * du);
    ASSERT_LT((system.A() * w + system.A_u() * du).norm(), 1e-9) << "a feasible motion";
    const double work = w.dot(system.SpringForce(y) - f);
    EXPECT_NEAR(e.dot(du), work, 1e-8 * (1 + std::abs(work))) << trial;
  }
}

// A model without stiffness keys: statics has none of the compliance keys
// (its JSON is the rigid one, byte for byte: checked against the tool before
// compliance when it was added).
TEST(Compliance, RigidModelsReportNoComplianceKeys) {
  for (const std::string& stem : testing::BundledModels()) {
    const testing::ToolRun run =
        testing::RunTool({"statics", "--model=" + std::string(CCMA_MODELS_DIR) + "/" + stem + ".yaml"});
    ASSERT_EQ(run.status, 0) << stem << run.err;
    const nlohmann::json out = nlohmann::json::parse(run.out);
    for (const char* key : {"deflection", "ee_compliance", "ee_stiffness", "ee_stiffness_note", "most_compliant",
                            "compliant_reactions"}) {
      EXPECT_FALSE(out.contains(key)) << stem << " " << key;
    }
  }
}

TEST(Compliance, TheToolReportsTheComplianceKeys) {
  const std::string path = ccma::testing::TestDir() + "/cantilever_tool.yaml";
  std::ofstream(path) << Cantilever(2e3, 0.3, "{rotation: 5000}", 1.2);
  const testing::ToolRun run = testing::RunTool({"statics", "--model=" + path, "--wrench=0,0,-7,0,0,0"});
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json out = nlohmann::json::parse(run.out);
  EXPECT_TRUE(out.at("compliant_reactions").get<bool>());
  EXPECT_NEAR(out.at("deflection").at("end_effector")[2].get<double>(), -7 * (1.44 / 2e3 + 0.81 / 5e3), 1e-12);
  EXPECT_TRUE(out.at("deflection").at("held").get<bool>());
  EXPECT_EQ(out.at("ee_compliance").size(), 6u);
  EXPECT_TRUE(out.at("ee_stiffness").is_null());  // y and roll, yaw are held rigidly
  EXPECT_FALSE(out.at("ee_stiffness_note").get<std::string>().empty());
  EXPECT_NEAR(out.at("most_compliant").at("compliance").get<double>(), 1.44 / 2e3 + 0.81 / 5e3, 1e-14);
}

}  // namespace
}  // namespace ccma
