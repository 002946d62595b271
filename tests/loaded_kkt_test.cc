// The loaded equilibrium's Newton matrix assembled block by block
// (problems/internal/loaded_kkt.h) and what the compensated control builds
// on it (problems/internal/compensated_newton.h, ControlProblem::CorrectTo).
//
// The matrix is checked against central differences of the equilibrium's
// residual r(y) = -(force - A^T mu) at seeded multipliers, at the rigid
// assembly where every spring is unstretched (there the spring directions
// are the deviations' exact derivatives): H is the symmetric part of r's
// Jacobian, its skew part the rotations' own (0 at an equilibrium); with
// the rows' curvature dropped the same check fails (the checker can fail). A, g and e against the dense linear system of
// problems/internal/compliant_equilibrium.h at a seeded deflected state.
#include <random>

#include <gtest/gtest.h>

#include "ccma/internal/constraint_set.h"
#include "ccma/internal/joint_spring_directions.h"
#include "ccma/loads.h"
#include "ccma/rotation.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "problems/compensated_control.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "problems/internal/compliant_equilibrium.h"
#include "problems/internal/loaded_kkt.h"
#include "problems/internal/loaded_newton.h"

namespace ccma {
namespace loaded_kkt_test {

// The generated 6-agent CCMA with compliant bases and hinges (different
// stiffness about each axis) and a 1.5 kg payload.
Model CompliantSixAgents() {
  StewartOptions options;
  options.agents = 6;
  Model model = LoadModelFromString(GenerateStewartModel(options), "generated.yaml");
  model.end_effector.payload.mass = 1.5;
  for (MobileBase& base : model.mobile_bases) base.stiffness.k = Eigen::Vector3d(3e4, 2e4, 600);
  for (Joint& joint : model.joints) {
    if (joint.type == JointType::kRevolute) joint.stiffness.rotation = {2.5e3, 1.5e3};
  }
  return model;
}

// That model assembled at its home controls, and its KKT layout.
class LoadedKktAssembly : public ::testing::Test {
 protected:
  LoadedKktAssembly() : model(CompliantSixAgents()), forward(model), system(model, forward.constraints()) {}
  void SetUp() override { ASSERT_TRUE(forward.Solve(model.home_controls()).assembled); }
  // x at the rigid assembly, nothing yielded.
  LoadedPoint Rigid() const {
    return {forward.state(), Eigen::VectorXd::Zero(static_cast<Eigen::Index>(system.compliant_controls().size()))};
  }

  const Model model;
  ForwardProblem forward;
  LoadedKkt system;
};

Eigen::VectorXd Seeded(Eigen::Index size, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-scale, scale);
  Eigen::VectorXd v(size);
  for (Eigen::Index i = 0; i < size; ++i) v[i] = value(rng);
  return v;
}

// K (both triangles, dense) assembled at x with the rows' multipliers mu
// (A order; w from them), eps_H = 1.
Eigen::MatrixXd DenseK(const Model& model, const ConstraintSet& set, LoadedKkt* system, const LoadedPoint& x,
                       const Eigen::VectorXd& u, const ExternalWrench& wrench, const Eigen::VectorXd& mu) {
  system->Assemble(model, set, x, u, wrench, system->SetOrder(mu), mu, 1.0, 1e-10);
  return Eigen::MatrixXd(system->K()).selfadjointView<Eigen::Lower>();
}

// mu with the compliant joints' rigid directions (the A rows that are not
// the constraint set's) set to 0.
Eigen::VectorXd OnSetRowsOnly(const LoadedKkt& system, Eigen::VectorXd mu) {
  for (size_t r = 0; r < system.set_rows().size(); ++r) {
    if (system.set_rows()[r] < 0) mu[static_cast<Eigen::Index>(r)] = 0;
  }
  return mu;
}

// The block-by-block K is the dense system's: at the rigid assembly (the
// springs unstretched) with multipliers on the constraint set's rows,
// H = S^T diag(k) S - sym(dQ/ds) + sum_i w_i Hess(C_i) (ConstraintSet's dense
// AddWeightedHessian), then A and the regularisations, as the dense
// linear system (problems/internal/compliant_equilibrium.h) has them.
TEST_F(LoadedKktAssembly, TheNewtonMatrixIsTheDenseSystemsWithTheRowsCurvature) {
  const ConstraintSet& set = forward.constraints();
  ExternalWrench wrench;
  wrench.force = Eigen::Vector3d(4, -3, -30);
  wrench.moment = Eigen::Vector3d(0.5, -0.2, 0.3);
  const LoadedPoint x = Rigid();
  const Eigen::VectorXd& u = forward.controls();
  const int n = system.state_size(), N = system.size(), m = system.rigid_rows();
  const CompliantEquilibrium dense(model, set, x.s, u, CompliantEquilibrium::Factorization::kNone);
  for (const unsigned seed : {3u, 17u}) {
    const Eigen::VectorXd mu = OnSetRowsOnly(system, Seeded(m, 50.0, seed));  // N or N*m per row
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(N + m, N + m);
    expected.topLeftCorner(N, N) = dense.S().transpose() * dense.k().asDiagonal() * dense.S();
    const Eigen::MatrixXd turning = GeneralizedLoadsJacobian(model, x.s, wrench);
    Eigen::MatrixXd H_s = -0.5 * (turning + turning.transpose());
    set.AddWeightedHessian(x.s, u, system.SetOrder(mu), &H_s);
    expected.topLeftCorner(n, n) += H_s;
    expected.topLeftCorner(N, N) += Eigen::MatrixXd::Identity(N, N);
    expected.bottomLeftCorner(m, N) = dense.A();
    expected.topRightCorner(N, m) = dense.A().transpose();
    expected.bottomRightCorner(m, m) = -1e-10 * Eigen::MatrixXd::Identity(m, m);
    const Eigen::MatrixXd K = DenseK(model, set, &system, x, u, wrench, mu);
    EXPECT_LT((K - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff()) << "seed " << seed;
    // The rows' curvature is there: without it the matrices differ.
    const Eigen::MatrixXd without = DenseK(model, set, &system, x, u, wrench, Eigen::VectorXd::Zero(m));
    EXPECT_GT((without - expected).cwiseAbs().maxCoeff(), 1.0) << "seed " << seed;
  }
}

// The compliant joints' curvature in K, the symmetric part of
// d/ds sum_r lambda_r D_r(s) with lambda the multipliers of their rigid
// directions (the springs' k e kept the same), against central differences
// of the analytic spring directions (ccma/internal/joint_spring_directions.h)
// at a seeded deflected state; a wrong weight fails the same check.
TEST_F(LoadedKktAssembly, TheSpringJointsCurvatureIsTheirDirectionsDerivative) {
  const ConstraintSet& set = forward.constraints();
  LoadedPoint x = Rigid();
  x.s.Plus(Seeded(system.state_size(), 1e-2, 11));
  const Eigen::VectorXd& u = forward.controls();
  const int n = system.state_size(), m = system.rigid_rows();
  const Eigen::VectorXd mu = Seeded(m, 50.0, 13);
  const Eigen::VectorXd on_set = OnSetRowsOnly(system, mu);
  const Eigen::MatrixXd curvature = (DenseK(model, set, &system, x, u, {}, mu) -
                                     DenseK(model, set, &system, x, u, {}, on_set)).topLeftCorner(n, n);
  // The same by central differences, joint by joint: lambda on each
  // compliant joint's rigid directions in A's order.
  const auto expected = [&](double weight) {
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n);
    int a = 0;  // A rows of the compliant joints' rigid directions, in order
    std::vector<int> direction_rows;
    for (size_t r = 0; r < system.set_rows().size(); ++r) {
      if (system.set_rows()[r] < 0) direction_rows.push_back(static_cast<int>(r));
    }
    for (const Joint& joint : model.joints) {
      if (!joint.stiffness.has_springs()) continue;
      const SpringDirections d0 = JointSpringDirections(joint, x.s);
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(d0.rows());
      for (int i = 0; i < d0.rows(); ++i) {
        const bool translation = i < d0.translations;
        if ((translation ? joint.stiffness.translation : joint.stiffness.rotation).empty()) {
          lambda[i] = weight * mu[direction_rows[static_cast<size_t>(a++)]];
        }
      }
      const int bodies[2] = {joint.body_a, joint.body_b};
      for (int side = 0; side < 2; ++side) {
        for (int k = 0; k < 6 && bodies[side] != kWorld; ++k) {
          Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
          step[6 * bodies[side] + k] = 1e-6;
          State plus = x.s, minus = x.s;
          plus.Plus(step);
          minus.Plus(-step);
          const Eigen::VectorXd column = (JointSpringDirections(joint, plus).D.topRows(d0.rows()).transpose() * lambda -
                                          JointSpringDirections(joint, minus).D.topRows(d0.rows()).transpose() * lambda) /
                                         2e-6;
          for (int other = 0; other < 2; ++other) {
            if (bodies[other] != kWorld) out.col(6 * bodies[side] + k).segment<6>(6 * bodies[other]) += column.segment<6>(6 * other);
          }
        }
      }
    }
    return out;
  };
  const Eigen::MatrixXd fd = expected(1.0), wrong = expected(1.1);
  EXPECT_GT(fd.cwiseAbs().maxCoeff(), 1.0);
  EXPECT_LT((curvature - 0.5 * (fd + fd.transpose())).cwiseAbs().maxCoeff(), 1e-5 * fd.cwiseAbs().maxCoeff());
  EXPECT_GT((curvature - 0.5 * (wrong + wrong.transpose())).cwiseAbs().maxCoeff(), 1e-2 * fd.cwiseAbs().maxCoeff());
}

// A, g and e at a deflected state: those of the dense linear system and the
// residuals the dense path uses.
TEST_F(LoadedKktAssembly, RowsAndStretchAreTheDenseSystems) {
  const ConstraintSet& set = forward.constraints();
  LoadedPoint x{forward.state(), Seeded(static_cast<Eigen::Index>(system.compliant_controls().size()), 1e-3, 5)};
  x.s.Plus(Seeded(system.state_size(), 1e-2, 7));
  const Eigen::VectorXd u = forward.controls();
  system.Assemble(model, set, x, u, {}, Eigen::VectorXd::Zero(set.num_rows()), {}, 1e-2, 1e-10);
  const Eigen::VectorXd u_eff = CommandedControls(u, system.compliant_controls(), x.delta);
  const CompliantEquilibrium dense(model, set, x.s, u_eff, CompliantEquilibrium::Factorization::kNone);
  EXPECT_LT((Eigen::MatrixXd(system.A()) - dense.A()).cwiseAbs().maxCoeff(), 1e-13);
  Eigen::VectorXd g, e;
  LoadedResiduals(model, set, x, u_eff, &g, &e);
  EXPECT_LT((system.g() - g).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((system.e() - e).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_GT(g.cwiseAbs().maxCoeff(), 1e-4);  // the rows do not hold there
  Eigen::VectorXd force = -dense.S().transpose() * (dense.k().asDiagonal() * e);
  force.head(system.state_size()) += GeneralizedLoads(model, x.s);
  EXPECT_LT((system.force() - force).cwiseAbs().maxCoeff(), 1e-9 * force.cwiseAbs().maxCoeff());
}

// A path step of compensated control: one rigid round, then Newton's method
// on the equilibrium and the controls together (2 rounds); with a
// secondary objective the control problem refuses direct corrections and
// the rounds of rigid control do it. Both put the loaded end-effector on
// the target.
TEST(CompensatedControl, TheNewtonFinishAndTheRoundsReachTheSameLoadedPose) {
  const Model model = CompliantSixAgents();
  for (const bool secondary : {false, true}) {
    ControlOptions options;
    if (secondary) options.secondary.travel_weight = 1.0;
    ControlProblem control(model, options);
    ASSERT_TRUE(control.SetControls(model.home_controls()).assembled);
    EXPECT_EQ(control.correctable(), !secondary);
    PoseTarget target = control.CurrentPose();
    target.position += Eigen::Vector3d(0.01, -0.005, 0.004);
    target.rpy += Eigen::Vector3d(0, 0, 0.01);
    const CompensatedResult r = MoveToCompensated(&control, target);
    ASSERT_TRUE(r.converged) << r.warning;
    if (!secondary) EXPECT_EQ(r.rounds, 2);
    if (secondary) EXPECT_GT(r.rounds, 2);
    const EndEffectorPose loaded = ComputeEndEffectorPose(model, r.loaded.state);
    EXPECT_LT((loaded.position - target.position).cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_LT((loaded.rpy - target.rpy).cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_GT(r.loaded.deflection.head<3>().norm(), 1e-4);
    // The rigid end-effector at the returned controls is the aim.
    const PoseTarget rigid = control.CurrentPose();
    EXPECT_LT((rigid.position - r.aim.position).cwiseAbs().maxCoeff(), 1e-9);
    // The equilibrium reported is the one a fresh solve finds at the controls.
    const LoadedEquilibrium again = SolveLoadedEquilibrium(model, control.forward().state(), control.controls());
    ASSERT_TRUE(again.converged);
    EXPECT_LT((again.deflection - r.loaded.deflection).cwiseAbs().maxCoeff(), 1e-10);
  }
}

// CorrectTo moves the controls straight to u where a control step would
// accept them, and refuses (nothing moved) on differential bases.
TEST(ControlProblem, CorrectToMovesOnlyWhereAStepWould) {
  const Model model = CompliantSixAgents();
  ControlProblem control(model);
  ASSERT_TRUE(control.SetControls(model.home_controls()).assembled);
  Eigen::VectorXd u = control.controls();
  u[0] += 1e-3;
  ASSERT_TRUE(control.CorrectTo(u));
  EXPECT_EQ(control.controls(), u);
  EXPECT_LT(control.forward().Energy(), 1e-20);
  const Model differential = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_differential.yaml");
  ControlProblem turning(differential);
  ASSERT_TRUE(turning.SetControls(differential.home_controls()).assembled);
  EXPECT_FALSE(turning.correctable());
  const State before = turning.forward().state();
  Eigen::VectorXd v = turning.controls();
  v[0] += 1e-3;
  EXPECT_FALSE(turning.CorrectTo(v));
  EXPECT_EQ(turning.controls(), differential.home_controls());
  EXPECT_EQ(turning.forward().state().Minus(before).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace loaded_kkt_test
}  // namespace ccma
