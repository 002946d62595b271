// Statics (analyses/statics.h, `ccma statics`): closed forms (a symmetric
// tripod of two-force legs carries W/3 each vertically; a crank's holding
// torque), virtual work along feasible motions re-solved on every bundled
// model with seeded masses, payloads and wrenches, the equilibrium of every
// body from the reported reactions, limits, and the loader's keys.
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <Eigen/Geometry>

#include "analyses/statics.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/format.h"
#include "bundled_models.h"
#include "formats/model_loader.h"
#include "problems/forward_problem.h"
#include "ccma/internal/dense_factorizations.h"
#include "tool_run.h"
#include "tests/tool_run.h"

namespace ccma {
namespace statics_test {

// Three prismatic legs from the unit circle on the ground to an apex 1 m up,
// spherical at both ends; `mass` kg at the apex.
std::string Tripod(double mass, const std::string& leg_extra = "") {
  std::ostringstream m;
  m.precision(17);
  m << "name: tripod\nbodies:\n  - {name: top, position: [0, 0, 1], mass: " << mass << "}\n";
  std::ostringstream joints;
  joints.precision(17);
  for (int i = 0; i < 3; ++i) {
    const double a = M_PI / 2 + 2 * M_PI * i / 3, x = std::cos(a), y = std::sin(a);
    m << "  - {name: low" << i << ", position: [" << 0.75 * x << ", " << 0.75 * y << ", 0.25]}\n"
      << "  - {name: up" << i << ", position: [" << 0.25 * x << ", " << 0.25 * y << ", 0.75]}\n";
    joints << "  - {name: foot" << i << ", type: spherical, between: [world, low" << i << "], point: [" << x << ", "
           << y << ", 0]}\n"
           << "  - {name: leg" << i << ", type: prismatic, actuated: true" << leg_extra << ", between: [low" << i
           << ", up" << i << "], point: [" << 0.5 * x << ", " << 0.5 * y << ", 0.5], axis: [" << -x << ", " << -y
           << ", 1]}\n"
           << "  - {name: head" << i << ", type: spherical, between: [up" << i << ", top], point: [0, 0, 1]}\n";
  }
  m << "joints:\n" << joints.str() << "end_effector: {body: top, point: [0, 0, 1], controlled: [x, y, z]}\n";
  return m.str();
}

// The effort columns of a trajectory (EffortEvaluator: the efforts alone,
// one constraint set for every row) are ComputeStatics' efforts, on rigid
// and compliant models with masses, at home and at moved controls.
TEST(Statics, TheEffortEvaluatorGivesComputeStaticsEfforts) {
  for (const char* path : {"/examples/statics/stewart_gough_compliant.yaml", "/examples/statics/4dof_payload.yaml",
                           "/examples/statics/tripod.yaml"}) {
    const Model model = LoadModel(std::string(CCMA_SOURCE_DIR) + path);
    ASSERT_TRUE(HasLoads(model)) << path;
    const EffortEvaluator evaluator(model);
    ForwardProblem forward(model);
    ExternalWrench w;
    w.force = Eigen::Vector3d(1.5, -2, -7);
    w.moment = Eigen::Vector3d(0.1, 0.2, -0.3);
    for (const double move : {0.0, 0.01}) {
      Eigen::VectorXd u = model.home_controls();
      if (move > 0 && model.num_bases() == 0) u.array() += move;
      if (!forward.Solve(u).assembled) continue;
      const StaticsReport full = ComputeStatics(model, forward.state(), forward.controls(), w);
      const StaticsReport fast = evaluator.At(forward.state(), forward.controls(), w);
      ASSERT_EQ(full.control_efforts.size(), fast.control_efforts.size());
      EXPECT_LT((full.control_efforts - fast.control_efforts).cwiseAbs().maxCoeff(),
                1e-12 * (1 + full.control_efforts.cwiseAbs().maxCoeff()))
          << path;
      EXPECT_EQ(full.within_limits, fast.within_limits) << path;
      EXPECT_EQ(full.limiting, fast.limiting) << path;
      ASSERT_EQ(full.actuators.size(), fast.actuators.size());
    }
  }
}

TEST(Statics, SymmetricTripodLegsCarryAThirdOfTheWeightEach) {
  const Model model = LoadModelFromString(Tripod(3.0), "tripod.yaml");
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
  const StaticsReport r = ComputeStatics(model, forward.state(), forward.controls());
  EXPECT_TRUE(r.balanced);
  EXPECT_TRUE(r.determinate);
  const double W = 3.0 * 9.81;
  for (int i = 0; i < 3; ++i) {
    const double a = M_PI / 2 + 2 * M_PI * i / 3;
    const Eigen::Vector3d along(-std::cos(a), -std::sin(a), 1.0);  // foot to apex, vertical component 1
    const Eigen::Vector3d f = W / 3 * along;                          // up the leg, W/3 vertically
    const JointReaction& foot = r.joints[static_cast<size_t>(3 * i)];
    const JointReaction& head = r.joints[static_cast<size_t>(3 * i + 2)];
    EXPECT_LT((foot.force - f).norm(), 1e-9 * W) << foot.name;  // the ground pushes the leg up along it
    EXPECT_LT((head.force - f).norm(), 1e-9 * W) << head.name;  // the leg pushes the apex up along it
    EXPECT_LT(foot.moment.norm(), 1e-9 * W);                    // spherical: no moment
    EXPECT_NEAR(std::abs(r.actuators[static_cast<size_t>(i)].effort), W / 3 * std::sqrt(2.0), 1e-9 * W);
  }
}

TEST(Statics, CrankHoldingTorqueIsWeightTimesLever) {
  // A crank on a motorised horizontal hinge (axis y) at the origin, its mass
  // 0.4 m out along x: holding it at angle q takes m g 0.4 cos(q).
  const std::string text =
      "name: crank\nbodies:\n  - {name: arm, position: [0.2, 0, 0], mass: 2, com: [0.4, 0, 0]}\n"
      "joints:\n  - {name: hinge, type: revolute, actuated: true, between: [world, arm], point: [0, 0, 0], "
      "axis: [0, -1, 0]}\nend_effector: {body: arm, point: [0.5, 0, 0], controlled: [x, z]}\n";
  const Model model = LoadModelFromString(text, "crank.yaml");
  ForwardProblem forward(model);
  for (double q : {0.0, 0.3, -0.7, 1.2}) {
    Eigen::VectorXd u(1);
    u << q;
    ASSERT_TRUE(forward.Assemble(u).assembled);
    const StaticsReport r = ComputeStatics(model, forward.state(), forward.controls());
    // axis -y: q raises the arm; the motor holds it up against gravity.
    EXPECT_NEAR(r.actuators[0].effort, 2 * 9.81 * 0.4 * std::cos(q), 1e-9) << q;
    EXPECT_NEAR(r.joints[0].force.z(), 2 * 9.81, 1e-9);  // the ground carries the weight
  }
}

// A planar four-bar in the x-z plane: ground pivots A = 0 and D = (0.6, 0, 0),
// crank AB motorised (axis -y, as the crank above), coupler BC (1 kg at its
// middle), rocker DC (2 kg at C). Closed form, independent of ccma: B(q) is
// B0 turned by q about A, C(q) the intersection of the circles about B(q)
// (radius |BC|) and D (radius |DC|) on the branch of C0, and by virtual work
// the crank torque is tau = -sum m g . dp/dq over the two weights.
struct FourBar {
  Eigen::Vector3d A{0, 0, 0}, B0{0.1, 0, 0.173205081}, C0{0.669459271, 0, 0.393923101}, D{0.6, 0, 0};
  Eigen::Vector3d B(double q) const { return Eigen::AngleAxisd(q, -Eigen::Vector3d::UnitY()) * (B0 - A) + A; }
  Eigen::Vector3d C(double q) const {
    const Eigen::Vector3d b = B(q);
    const double r1 = (C0 - B0).norm(), r2 = (C0 - D).norm(), d = (D - b).norm();
    const double along = (r1 * r1 - r2 * r2 + d * d) / (2 * d), off = std::sqrt(r1 * r1 - along * along);
    const Eigen::Vector3d ex = (D - b) / d, ez = Eigen::Vector3d::UnitY().cross(ex);  // in-plane normal
    const Eigen::Vector3d c1 = b + along * ex + off * ez, c2 = b + along * ex - off * ez;
    return (c1 - C0).norm() < (c2 - C0).norm() ? c1 : c2;  // the branch of C0 (q stays small)
  }
  // The weights' potential derivative dV/dq = -(tau), by a central difference of the closed form.
  double Torque(double q) const {
    const double h = 1e-6, g = 9.81;
    auto V = [&](double x) { return g * (1.0 * 0.5 * (B(x) + C(x)).z() + 2.0 * C(x).z()); };
    return (V(q + h) - V(q - h)) / (2 * h);
  }
};

TEST(Statics, FourBarCrankTorqueByVirtualWork) {
  const FourBar bar;
  std::ostringstream text;
  const Eigen::Vector3d M = 0.5 * (bar.B0 + bar.C0), R = 0.5 * (bar.C0 + bar.D);
  text.precision(12);
  text << "name: four_bar\nbodies:\n"
       << "  - {name: crank, position: [" << 0.5 * bar.B0.x() << ", 0, " << 0.5 * bar.B0.z() << "]}\n"
       << "  - {name: coupler, position: [" << M.x() << ", 0, " << M.z() << "], mass: 1}\n"
       << "  - {name: rocker, position: [" << R.x() << ", 0, " << R.z() << "], mass: 2, com: [" << bar.C0.x()
       << ", 0, " << bar.C0.z() << "]}\njoints:\n"
       << "  - {name: crank_motor, type: revolute, actuated: true, between: [world, crank], point: [0, 0, 0], axis: [0, -1, 0]}\n"
       << "  - {type: revolute, between: [crank, coupler], point: [" << bar.B0.x() << ", 0, " << bar.B0.z()
       << "], axis: [0, -1, 0]}\n"
       << "  - {type: revolute, between: [coupler, rocker], point: [" << bar.C0.x() << ", 0, " << bar.C0.z()
       << "], axis: [0, -1, 0]}\n"
       << "  - {type: revolute, between: [world, rocker], point: [" << bar.D.x() << ", 0, " << bar.D.z()
       << "], axis: [0, -1, 0]}\nend_effector: {body: rocker, point: [" << bar.C0.x() << ", 0, " << bar.C0.z()
       << "], controlled: [x]}\n";
  const Model model = LoadModelFromString(text.str(), "four_bar.yaml");
  ForwardProblem forward(model);
  for (double q : {0.0, 0.15, -0.2, 0.3}) {
    Eigen::VectorXd u(1);
    u << q;
    ASSERT_TRUE(forward.Assemble(u).assembled) << q;
    // ccma's mechanism is the closed form's: the rocker's point C where the closed form puts it.
    const State& s = forward.state();
    const int rocker = 2;
    EXPECT_LT((s.R_WB(rocker) * model.bodies[rocker].inertia.com_B + s.p_WB(rocker) - bar.C(q)).norm(), 1e-9) << q;
    const StaticsReport r = ComputeStatics(model, s, forward.controls());
    const double tau = bar.Torque(q);
    ASSERT_GT(std::abs(tau), 0.1);
    EXPECT_NEAR(r.actuators[0].effort, tau, 1e-8 * std::abs(tau)) << q;
  }
}

// Seeded masses (0.5-2 kg, centres up to 0.1 m off each origin), a payload
// and a wrench on every body of a bundled model.
Model WithLoads(Model model, std::mt19937* rng) {
  std::uniform_real_distribution<double> mass(0.5, 2.0), offset(-0.1, 0.1);
  for (Body& body : model.bodies) body.inertia = {mass(*rng), Eigen::Vector3d(offset(*rng), offset(*rng), offset(*rng))};
  model.end_effector.payload = {mass(*rng), model.end_effector.p_B + Eigen::Vector3d(0.02, -0.01, 0.03)};
  return model;
}

// Feasible motions: the null space of [dC/ds dC/du] (directions in which the
// mechanism stays assembled), as (ds, du) columns.
Eigen::MatrixXd FeasibleMotions(const Model& model, const State& s, const Eigen::VectorXd& u) {
  const ConstraintSet set(model);
  Eigen::VectorXd C;
  Eigen::MatrixXd J_s, J_u;
  set.Evaluate(s, u, &C, &J_s, &J_u);
  Eigen::MatrixXd J(J_s.rows(), J_s.cols() + J_u.cols());
  J << J_s, J_u;
  JacobiSvd svd(J, Eigen::ComputeFullV);
  const int rank = static_cast<int>((svd.singularValues().array() > 1e-9 * svd.singularValues()[0]).count());
  return svd.matrixV().rightCols(J.cols() - rank);
}

TEST(Statics, VirtualWorkAlongEveryFeasibleMotionOfEveryBundledModel) {
  std::mt19937 rng(27);
  for (const std::string& name : testing::BundledModels()) {
    const Model model = WithLoads(LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"), &rng);
    ForwardProblem forward(model);
    ASSERT_TRUE(forward.Solve(model.home_controls()).assembled) << name;
    ExternalWrench wrench;
    wrench.force = Eigen::Vector3d(3, -2, 5);
    wrench.moment = Eigen::Vector3d(0.4, 0.1, -0.3);
    const StaticsReport r = ComputeStatics(model, forward.state(), forward.controls(), wrench);
    ASSERT_TRUE(r.balanced) << name << " " << r.residual;
    const Eigen::VectorXd& effort = r.control_efforts;
    const Eigen::VectorXd Q = GeneralizedLoads(model, forward.state(), wrench);
    const Eigen::MatrixXd motions = FeasibleMotions(model, forward.state(), forward.controls());
    ASSERT_GT(motions.cols(), 0) << name;
    const int n = model.state_size();
    for (int k = 0; k < motions.cols(); ++k) {
      const Eigen::VectorXd ds = motions.col(k).head(n), du = motions.col(k).tail(model.num_controls());
      // efforts . du = -(the loads' power), to 1e-8 relative.
      const double scale = effort.cwiseAbs().sum() * du.norm() + Q.cwiseAbs().sum() * ds.norm();
      EXPECT_NEAR(effort.dot(du), -Q.dot(ds), 1e-8 * scale) << name << " motion " << k;
    }
  }
}

TEST(Statics, EffortsMatchThePotentialsSlopeOfReSolvedMotions) {
  // Independent of the multipliers: move the controls along a feasible
  // direction, re-solve, and difference the potential energy of gravity and
  // of a constant force at the end-effector point.
  std::mt19937 rng(5);
  for (const std::string& name : testing::BundledModels()) {
    const Model model = WithLoads(LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"), &rng);
    ForwardProblem forward(model);
    ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
    const State home = forward.state();
    const Eigen::VectorXd u0 = forward.controls();
    ExternalWrench wrench;
    wrench.force = Eigen::Vector3d(-4, 1, 2);
    const StaticsReport r = ComputeStatics(model, home, u0, wrench);
    const Eigen::MatrixXd motions = FeasibleMotions(model, home, u0);
    const Eigen::VectorXd du = motions.col(0).tail(model.num_controls()).normalized();
    if (du.norm() == 0) continue;
    auto potential = [&](double h) {
      forward.SetState(home);
      EXPECT_LT(forward.Solve(u0 + h * du).residual_energy, 1e-12) << name;
      const State& s = forward.state();
      double V = -wrench.force.dot(forward.end_effector().position);
      for (int b = 0; b < model.num_bodies(); ++b) {
        const MassProperties& m = model.bodies[static_cast<size_t>(b)].inertia;
        V -= m.mass * model.gravity.dot(s.R_WB(b) * m.com_B + s.p_WB(b));
      }
      const int ee = model.end_effector.body;
      V -= model.end_effector.payload.mass *
           model.gravity.dot(s.R_WB(ee) * model.end_effector.payload.com_B + s.p_WB(ee));
      return V;
    };
    const double h = 1e-5, slope = (potential(h) - potential(-h)) / (2 * h);
    double power = 0;
    for (int c = 0; c < du.size(); ++c) power += r.control_efforts[c] * du[c];
    EXPECT_NEAR(power, slope, 1e-6 * (1 + std::abs(slope))) << name;
  }
}

TEST(Statics, EveryBodyIsInEquilibriumUnderTheReportedReactions) {
  std::mt19937 rng(9);
  for (const std::string& name : testing::BundledModels()) {
    const Model model = WithLoads(LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"), &rng);
    ForwardProblem forward(model);
    ASSERT_TRUE(forward.Solve(model.home_controls()).assembled);
    const State& s = forward.state();
    ExternalWrench wrench;
    wrench.force = Eigen::Vector3d(1, 2, -3);
    wrench.moment = Eigen::Vector3d(-0.2, 0.5, 0.1);
    const StaticsReport r = ComputeStatics(model, s, forward.controls(), wrench);
    const Eigen::VectorXd Q = GeneralizedLoads(model, s, wrench);
    for (int b = 0; b < model.num_bodies(); ++b) {
      if (model.bodies[static_cast<size_t>(b)].is_mobile_base()) continue;  // held by the ground too
      Eigen::Vector3d F = Q.segment<3>(6 * b + 3), M = Q.segment<3>(6 * b);  // about the origin
      for (size_t j = 0; j < model.joints.size(); ++j) {
        const Joint& joint = model.joints[j];
        const double sign = joint.body_b == b ? 1.0 : joint.body_a == b ? -1.0 : 0.0;
        const JointReaction& re = r.joints[j];
        F += sign * re.force;
        M += sign * (re.moment + (re.point - s.p_WB(b)).cross(re.force));
      }
      const double scale = 1 + Q.cwiseAbs().maxCoeff();
      EXPECT_LT(F.norm(), 1e-9 * scale) << name << " " << model.bodies[static_cast<size_t>(b)].name;
      EXPECT_LT(M.norm(), 1e-9 * scale) << name << " " << model.bodies[static_cast<size_t>(b)].name;
    }
  }
}

TEST(Statics, LimitsAndLoaderKeys) {
  const Model limited =
      LoadModelFromString(Tripod(3.0, ", effort_limits: [-10, 10]"), "tripod.yaml");  // legs carry 13.9 N
  ForwardProblem forward(limited);
  ASSERT_TRUE(forward.Solve(limited.home_controls()).assembled);
  const StaticsReport r = ComputeStatics(limited, forward.state(), forward.controls());
  EXPECT_TRUE(r.limits_given);
  EXPECT_FALSE(r.within_limits);
  EXPECT_EQ(r.limiting, std::vector<std::string>({"leg0", "leg1", "leg2"}));
  const Model fine = LoadModelFromString(Tripod(3.0, ", effort_limits: [-20, 20]"), "tripod.yaml");
  EXPECT_TRUE(ComputeStatics(fine, forward.state(), forward.controls()).within_limits);
  for (const auto& [extra, message] : std::vector<std::pair<std::string, std::string>>{
           {", effort_limits: [5, -5]", "must not exceed upper"},
           {", effort_limits: [1]", "must be [lower, upper]"}}) {
    try {
      LoadModelFromString(Tripod(3.0, extra), "bad.yaml");
      ADD_FAILURE() << extra;
    } catch (const ModelError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(LoadModelFromString(Tripod(-1.0), "bad.yaml"), ModelError);
}

// The current world position of a joint's point.
Eigen::Vector3d JointPoint(const Joint& joint, const State& s) {
  return joint.body_a == kWorld ? joint.p_A : Eigen::Vector3d(s.R_WB(joint.body_a) * joint.p_A + s.p_WB(joint.body_a));
}

TEST(Statics, StewartLegForcesAreTheInverseTransposedJacobianOfTheWrench) {
  // Leg i along n_i from its ground point to its platform point r_i: its
  // length rate is n_i . (v + w x r_i), row i of J = [n_i^T, (r_i x n_i)^T]
  // (r_i from the end-effector point). Virtual work: J^T efforts = -wrench.
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/stewart_gough_6ups.yaml");
  ForwardProblem forward(model);
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> leg(-0.05, 0.05), load(-50, 50);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd u = model.home_controls();
    for (int i = 0; i < u.size(); ++i) u[i] += trial == 0 ? 0.0 : leg(rng);
    ASSERT_TRUE(forward.Assemble(u).assembled);
    const State& s = forward.state();
    ExternalWrench w;
    w.force = Eigen::Vector3d{load(rng), load(rng), load(rng)};
    w.moment = Eigen::Vector3d{load(rng), load(rng), load(rng)} / 10;
    const StaticsReport r = ComputeStatics(model, s, forward.controls(), w);
    ASSERT_TRUE(r.determinate);
    Eigen::Matrix<double, 6, 6> J;
    Eigen::Matrix<double, 6, 1> efforts, wrench;
    wrench << w.force, w.moment;
    const Eigen::Vector3d p_WE = forward.end_effector().position;
    int row = 0;
    for (const Joint& joint : model.joints) {
      if (!joint.actuated) continue;
      Eigen::Vector3d ground, top;
      for (const Joint& other : model.joints) {
        if (other.body_b == joint.body_a) ground = JointPoint(other, s);
        if (other.body_a == joint.body_b) top = JointPoint(other, s);
      }
      const Eigen::Vector3d n = (top - ground).normalized(), r_i = top - p_WE;
      J.row(row) << n.transpose(), r_i.cross(n).transpose();
      efforts[row] = r.actuators[static_cast<size_t>(row)].effort;
      ++row;
    }
    ASSERT_EQ(row, 6);
    const Eigen::Matrix<double, 6, 1> expected = -J.transpose().inverse() * wrench;
    EXPECT_LT((efforts - expected).cwiseAbs().maxCoeff(), 1e-9 * (1 + expected.cwiseAbs().maxCoeff())) << trial;
  }
}

// The tripod's own 3 kg apex loads each leg with W/3 sqrt(2) = 13.87 N,
// beyond a 10 N limit: no payload is safe. The capacity is 0 (never
// negative), names the leg it breaks and says by how much.
TEST(Statics, PayloadCapacityIsZeroWhenTheUnloadedMechanismBreaksALimit) {
  const std::string dir = ccma::testing::TestDir();
  std::ofstream(dir + "/heavy_tripod.yaml") << Tripod(3.0, ", effort_limits: [-10, 10]");
  const testing::ToolRun run = testing::RunTool({"statics", "--model=" + dir + "/heavy_tripod.yaml"});
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json capacity = nlohmann::json::parse(run.out)["payload_capacity"];
  EXPECT_EQ(capacity["mass"].get<double>(), 0.0);
  EXPECT_EQ(capacity["limiting"].get<std::string>(), "leg0");
  const std::string note = capacity["note"].get<std::string>();
  const double per_leg = 3.0 * 9.81 / 3 * std::sqrt(2.0);
  EXPECT_NE(note.find("'leg0'"), std::string::npos) << note;
  EXPECT_NE(note.find(FormatG(per_leg)), std::string::npos) << note << " (expected " << FormatG(per_leg) << ")";
  EXPECT_NE(run.err.find(note), std::string::npos) << run.err;
  // Within its limits unloaded: a positive capacity and no note.
  std::ofstream(dir + "/light_tripod.yaml") << Tripod(3.0, ", effort_limits: [-20, 20]");
  const testing::ToolRun light = testing::RunTool({"statics", "--model=" + dir + "/light_tripod.yaml"});
  ASSERT_EQ(light.status, 0) << light.err;
  const nlohmann::json ok = nlohmann::json::parse(light.out)["payload_capacity"];
  EXPECT_GT(ok["mass"].get<double>(), 0.0);
  EXPECT_FALSE(ok.contains("note"));
}

TEST(Statics, TrajectoryRowsCarryTheEfforts) {
  const std::string dir = ccma::testing::TestDir();
  {
    std::ofstream(dir + "/tripod.yaml") << Tripod(3.0, ", effort_limits: [-20, 20]");
    std::ofstream(dir + "/path.csv") << "time,x,y,z,roll,pitch,yaw\n1,0,0,1.05,0,0,0\n";
  }
  const testing::ToolRun run = testing::RunTool(
      {"trajectory", "--model=" + dir + "/tripod.yaml", "--waypoints=" + dir + "/path.csv", "--out=" + dir + "/t.csv"});
  ASSERT_EQ(run.status, 0) << run.err;
  std::istringstream csv(testing::Slurp(dir + "/t.csv"));
  std::string header, line, last;
  std::getline(csv, header);
  EXPECT_NE(header.find(",effort_leg0_N,effort_leg1_N,effort_leg2_N,within_limits"), std::string::npos) << header;
  while (std::getline(csv, line)) last = line;
  std::vector<std::string> cells;
  std::stringstream row(last);
  for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
  ASSERT_GE(cells.size(), 4u);
  // Higher apex, steeper legs: each still carries W/3 vertically; along the
  // leg W/3 * L / h, with L the leg's length and h = 1.05 m.
  const double W = 3.0 * 9.81, L = std::hypot(1.0, 1.05);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(std::abs(std::stod(cells[cells.size() - 4 + i])), W / 3 * L / 1.05, 1e-6);
  EXPECT_EQ(cells.back(), "1");
  // Without masses or limits: no effort columns.
  {
    std::ofstream(dir + "/plain.yaml") << Tripod(0.0);
  }
  const testing::ToolRun plain = testing::RunTool(
      {"trajectory", "--model=" + dir + "/plain.yaml", "--waypoints=" + dir + "/path.csv", "--out=" + dir + "/p.csv"});
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_EQ(testing::Slurp(dir + "/p.csv").find("effort_"), std::string::npos);
}

}  // namespace
}  // namespace ccma
