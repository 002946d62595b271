// Implicit-function sensitivities against central finite differences of
// re-solved forward problems (1e-6 relative), at assembled controls and at
// controls the over-actuated 4-DOF models cannot assemble (E > 0), where the
// second-order terms sum_i C_i Hess(C_i) matter.
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "formats/model_loader.h"
#include "problems/control_problem.h"
#include "problems/internal/sensitivity.h"

namespace ccma {
namespace sensitivity_test {

constexpr double kRelativeTolerance = 1e-6;
constexpr double kStep = 1e-5;  // finite-difference step [m, rad]

Model LoadReference(const std::string& name) {
  return LoadModel(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
}

double RelativeError(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric) {
  return (analytic - numeric).cwiseAbs().maxCoeff() / std::max(numeric.cwiseAbs().maxCoeff(), 1e-12);
}

struct Fixture {
  Model model;
  std::unique_ptr<ForwardProblem> forward;
  std::vector<int> controls;
};

// The forward problem solved at `u`; E > 0 if the mechanism cannot reach u.
Fixture SolvedAt(const std::string& name, const Eigen::VectorXd& du) {
  Fixture f{LoadReference(name), nullptr, {}};
  f.forward = std::make_unique<ForwardProblem>(f.model);
  f.controls = f.model.effective_control_indices();
  f.forward->Assemble(f.model.home_controls() + du);
  return f;
}

// Central differences over the effective controls of g(forward problem
// re-solved at u +- h e_c from the same state).
template <typename Fn>
Eigen::MatrixXd CentralDifferences(Fixture& f, Fn g) {
  const State base = f.forward->state();
  const Eigen::VectorXd u = f.forward->controls();
  Eigen::MatrixXd out;
  for (size_t c = 0; c < f.controls.size(); ++c) {
    Eigen::MatrixXd side[2];
    for (int k = 0; k < 2; ++k) {
      Eigen::VectorXd moved = u;
      moved[f.controls[c]] += k == 0 ? kStep : -kStep;
      f.forward->SetState(base);
      f.forward->Solve(moved);
      side[k] = g(base);
    }
    const Eigen::MatrixXd column = (side[0] - side[1]) / (2 * kStep);
    if (c == 0) out.resize(column.rows(), f.controls.size());
    out.col(c) = column.col(0);
  }
  f.forward->Restore(base, u);
  return out;
}

struct Case {
  std::string model;
  bool assembled;  // false: controls perturbed so that E > 0
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.model << (c.assembled ? "" : " (E > 0)"); }

class Sensitivities : public ::testing::TestWithParam<Case> {
 protected:
  Eigen::VectorXd Perturbation(const Model& m) const {
    // A rigid move of all bases (always reachable), plus, for the E > 0 cases,
    // 5 mm on one base of an over-actuated system (not reachable).
    Eigen::VectorXd du = Eigen::VectorXd::Zero(m.num_controls());
    for (int k = 0; k < m.num_bases(); ++k) du[3 * k] = 0.01;
    if (!GetParam().assembled) du[1] += 0.005;
    return du;
  }
};

TEST_P(Sensitivities, StateSensitivityMatchesFiniteDifferences) {
  Fixture f = SolvedAt(GetParam().model, Perturbation(LoadReference(GetParam().model)));
  const double E = f.forward->Energy();
  if (GetParam().assembled) {
    ASSERT_LT(E, 1e-24);
  } else {
    ASSERT_GT(E, 1e-8) << "the case must not be assembled";
  }
  const Sensitivity s(f.forward->constraints(), f.forward->state(), f.forward->controls(), f.controls);
  EXPECT_FALSE(s.singular());
  const Eigen::MatrixXd analytic = s.StateSensitivity();
  const Eigen::MatrixXd numeric = CentralDifferences(
      f, [&](const State& base) { return Eigen::MatrixXd(f.forward->state().Minus(base)); });
  EXPECT_LT(RelativeError(analytic, numeric), kRelativeTolerance) << "E = " << E;
}

TEST_P(Sensitivities, ResidualEnergyGradientMatchesFiniteDifferences) {
  Fixture f = SolvedAt(GetParam().model, Perturbation(LoadReference(GetParam().model)));
  const Sensitivity s(f.forward->constraints(), f.forward->state(), f.forward->controls(), f.controls);
  const Eigen::VectorXd analytic = s.ResidualEnergyGradient();
  const Eigen::MatrixXd numeric = CentralDifferences(f, [&](const State&) {
    return Eigen::MatrixXd::Constant(1, 1, f.forward->Energy());
  });
  if (GetParam().assembled) {
    EXPECT_LT(analytic.cwiseAbs().maxCoeff(), 1e-12);  // E_r = 0 on the reachable set
    EXPECT_LT(numeric.cwiseAbs().maxCoeff(), 1e-6);
  } else {
    EXPECT_LT(RelativeError(analytic, numeric.transpose()), kRelativeTolerance);
  }
}

TEST_P(Sensitivities, ObjectiveGradientMatchesFiniteDifferences) {
  const Model m = LoadReference(GetParam().model);
  ControlProblem control(m);
  control.SetControls(m.home_controls() + Perturbation(m));
  PoseTarget target = control.CurrentPose();
  target.position += Eigen::Vector3d(0.01, -0.02, 0.015);
  target.rpy += Eigen::Vector3d(0.02, -0.01, 0.03);
  Eigen::VectorXd analytic;
  const double O = control.Objective(target, &analytic);
  ASSERT_GT(O, 1e-6);

  ControlOptions fd_options;
  fd_options.gradient = GradientMethod::kFiniteDifference;
  fd_options.finite_difference_step = kStep;
  ControlProblem fd(m, fd_options);
  fd.SetControls(m.home_controls() + Perturbation(m));
  Eigen::VectorXd numeric;
  EXPECT_NEAR(fd.Objective(target, &numeric), O, 1e-14);
  EXPECT_LT(RelativeError(analytic, numeric), kRelativeTolerance);
}

// The products with S = ds/du that the LM linearisation uses, by both of
// ImplicitProducts' paths (sparse entry lists, dense L^-1 P B), against the
// same products with S formed explicitly (StateSensitivity).
TEST_P(Sensitivities, ImplicitProductsMatchTheExplicitSensitivity) {
  Fixture f = SolvedAt(GetParam().model, Perturbation(LoadReference(GetParam().model)));
  const Sensitivity s(f.forward->constraints(), f.forward->state(), f.forward->controls(), f.controls);
  const Eigen::MatrixXd S = s.StateSensitivity();
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(6, S.rows());
  for (Eigen::Index c = 0; c < 6; ++c) {  // the end-effector-like rows: one body's columns
    for (Eigen::Index r = 0; r < 6; ++r) F(r, c) = normal(rng);
  }
  Eigen::VectorXd v(S.rows());
  for (Eigen::Index i = 0; i < v.size(); ++i) v[i] = normal(rng);
  Eigen::MatrixXd B(S.rows(), S.cols());
  for (size_t c = 0; c < f.controls.size(); ++c) B.col(c) = s.derivatives().dG_du.col(f.controls[c]);
  const Eigen::MatrixXd BtS = B.transpose() * S, FS = F * S;
  const Eigen::VectorXd Stv = S.transpose() * v;
  for (const auto path : {Sensitivity::ProductsPath::kSparse, Sensitivity::ProductsPath::kDense}) {
    SCOPED_TRACE(path == Sensitivity::ProductsPath::kSparse ? "sparse" : "dense");
    Sensitivity::Products products;
    ASSERT_TRUE(s.ImplicitProducts(F, v, &products, path));
    EXPECT_LT(RelativeError(products.BtS, BtS), 1e-9);
    EXPECT_LT(RelativeError(products.FS, FS), 1e-9);
    EXPECT_LT(RelativeError(products.Stv, Stv), 1e-9);
  }
}

INSTANTIATE_TEST_SUITE_P(
    ReferenceModels, Sensitivities,
    ::testing::Values(Case{"4dof_reduced", true}, Case{"4dof_reduced", false},
                      Case{"4dof_complete", true}, Case{"4dof_complete", false},
                      Case{"6dof_symmetric", true}, Case{"6dof_asymmetric", true},
                      Case{"6dof_six_agents", true}),
    [](const auto& info) {
      return info.param.model + (info.param.assembled ? "_assembled" : "_not_assembled");
    });

TEST(Sensitivities, SecondOrderTermsMatterWhenNotAssembled) {
  // Without sum_i C_i Hess(C_i) (Gauss-Newton Hessian J^T J only), ds/du is
  // measurably wrong at E > 0: the exact Hessian is needed, as the paper says.
  const Model m = LoadReference("4dof_complete");
  Eigen::VectorXd du = Eigen::VectorXd::Zero(m.num_controls());
  du[1] = 0.02;
  Fixture f = SolvedAt("4dof_complete", du);
  const Sensitivity s(f.forward->constraints(), f.forward->state(), f.forward->controls(), f.controls);
  const EnergyDerivatives& d = s.derivatives();
  const Eigen::MatrixXd JtJ = d.J_s.transpose() * d.J_s;
  Eigen::MatrixXd dG_du(d.H.rows(), f.controls.size());
  for (size_t c = 0; c < f.controls.size(); ++c) dG_du.col(c) = d.dG_du.col(f.controls[c]);
  const Eigen::MatrixXd gauss_newton = -JtJ.ldlt().solve(dG_du);
  const Eigen::MatrixXd numeric = CentralDifferences(
      f, [&](const State& base) { return Eigen::MatrixXd(f.forward->state().Minus(base)); });
  EXPECT_LT(RelativeError(s.StateSensitivity(), numeric), kRelativeTolerance);
  EXPECT_GT(RelativeError(gauss_newton, numeric), 100 * kRelativeTolerance);
}

}  // namespace
}  // namespace ccma
