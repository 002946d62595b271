// Effort limits in control (problems/internal/effort_limit_constraint.h):
// the linearisation de/du against central differences of efforts re-solved
// at perturbed controls (statics on re-solved forward problems), a check
// that rejects a linearisation holding the state; and control keeping a
// motor's effort and a base's push within their limits, stopping exactly at
// the limit, naming it, with every step within it.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analyses/statics.h"
#include "formats/model_loader.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/loads.h"
#include "problems/internal/effort_limit_constraint.h"
#include "problems/internal/equilibrium.h"

namespace ccma {
namespace effort_limit_test {

Model LoadFile(const std::string& relative) { return LoadModel(std::string(CCMA_MODELS_DIR) + "/../" + relative); }

// Efforts and pushes the way statics reports them: joints by name, bases' |e_xy|.
double Value(const StaticsReport& report, const std::string& name, bool push) {
  double x = 0, y = 0;
  for (const ActuatorEffort& a : report.actuators) {
    if (a.name != name) continue;
    if (!push) return a.effort;
    if (a.kind == "base_x") x = a.effort;
    if (a.kind == "base_y") y = a.effort;
  }
  return std::hypot(x, y);
}

// The tripod (3 kg) with a +-20 N limit on every leg motor, and the
// 4dof payload example (its bases' push limits).
Model Tripod() {
  Model model = LoadFile("examples/statics/tripod.yaml");
  for (Joint& joint : model.joints) {
    if (joint.actuated) joint.effort = {true, -20.0, 20.0};
  }
  return model;
}

struct Probe {
  std::string model_file;
  std::string item;
  bool push;
};

class EffortLinearisation : public ::testing::TestWithParam<Probe> {};

// The active row of the item (d value / du over the effective controls)
// against central differences of statics on re-solved forward problems.
TEST_P(EffortLinearisation, MatchesReSolvedCentralDifferences) {
  const Model model = GetParam().model_file == "tripod" ? Tripod() : LoadFile(GetParam().model_file);
  ASSERT_TRUE(HasEffortLimits(model));
  const std::vector<int> effective = model.effective_control_indices();
  const EffortLimitConstraint constraint(model, effective);
  int item = -1;
  // Off the symmetric home: the controller at a nearby target. (The
  // constraint finds the state's motion itself: ds/du is not read.)
  ControlProblem control(model);
  control.SetControls(model.home_controls());
  PoseTarget target = control.CurrentPose();
  target.position += Eigen::Vector3d(0.02, -0.015, -0.01);
  ASSERT_TRUE(control.MoveTo(target).converged);
  const Eigen::VectorXd u = control.controls();
  const State s = control.forward().state();
  const Eigen::MatrixXd ds_du = Eigen::MatrixXd::Zero(s.tangent_size(), static_cast<Eigen::Index>(effective.size()));
  // The item's index: joints after bases, in model order (the constructor's order).
  int index = 0;
  for (const MobileBase& base : model.mobile_bases) {
    if (base.push_limit > 0 && base.name == GetParam().item) item = index;
    if (base.push_limit > 0) ++index;
  }
  for (const Joint& joint : model.joints) {
    if (joint.actuated && joint.effort.given && joint.name == GetParam().item) item = index;
    if (joint.actuated && joint.effort.given) ++index;
  }
  ASSERT_GE(item, 0);
  const double scale = GetParam().push ? model.mobile_bases[0].push_limit : 20.0;
  LinearConstraints rows;
  rows.A.setZero(1, static_cast<Eigen::Index>(effective.size()));
  rows.b.setZero(1);
  constraint.AppendRows(u, s, ds_du, {item}, 0, &rows);
  const Eigen::RowVectorXd analytic = rows.A.row(0) * scale;
  Eigen::RowVectorXd numeric(analytic.size());
  constexpr double h = 1e-6;
  for (size_t c = 0; c < effective.size(); ++c) {
    double side[2];
    for (int i = 0; i < 2; ++i) {
      ForwardProblem f(model);
      f.Restore(s, u);
      Eigen::VectorXd ui = u;
      ui[effective[c]] += i == 0 ? h : -h;
      ASSERT_TRUE(f.Solve(ui).converged);
      side[i] = Value(ComputeStatics(model, f.state(), ui), GetParam().item, GetParam().push);
    }
    numeric[static_cast<Eigen::Index>(c)] = (side[0] - side[1]) / (2 * h);
  }
  const double size = numeric.cwiseAbs().maxCoeff();
  ASSERT_GT(size, 1.0) << "the item's effort must change with the controls";
  EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff() / size, 1e-6) << analytic << "\n" << numeric;
  // The same comparison fails for a linearisation that holds the state
  // (the controls' direct effect only): the adjoint Lagrangian along (0, du).
  const ConstraintSet set(model);
  const Equilibrium eq(set, s, u);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(u.size());
  const StaticsReport here = ComputeStatics(model, s, u);
  for (size_t k = 0; k < here.actuators.size(); ++k) {
    const ActuatorEffort& a = here.actuators[k];
    if (a.name != GetParam().item) continue;
    if (!GetParam().push) w[static_cast<Eigen::Index>(k)] = 1;
    if (GetParam().push && a.kind != "base_theta") w[static_cast<Eigen::Index>(k)] = a.effort / Value(here, a.name, true);
  }
  const Equilibrium::Adjoint adjoint = eq.AdjointOf(w, GeneralizedLoads(model, s));
  Eigen::RowVectorXd held(analytic.size());
  for (size_t c = 0; c < effective.size(); ++c) {
    const Eigen::VectorXd du = 1e-6 * Eigen::VectorXd::Unit(u.size(), effective[c]);
    held[static_cast<Eigen::Index>(c)] =
        (EffortLagrangian(set, model, s, u + du, w, adjoint) - EffortLagrangian(set, model, s, u - du, w, adjoint)) / 2e-6;
  }
  EXPECT_GT((held - numeric).cwiseAbs().maxCoeff() / size, 1e-2);
}

INSTANTIATE_TEST_SUITE_P(Models, EffortLinearisation,
                         ::testing::Values(Probe{"tripod", "leg0", false},
                                           Probe{"examples/statics/4dof_payload.yaml", "base0", true},
                                           Probe{"examples/statics/4dof_payload.yaml", "base2", true}));

// Control toward a target that needs more than a limit: it stops with the
// limited item exactly at its limit, names it, and no step went beyond.
void ExpectStopsAtTheLimit(const Model& model, const PoseTarget& target, const std::string& item, bool push,
                           double limit) {
  ControlProblem control(model);
  control.SetControls(model.home_controls());
  double worst = 0;
  const ControlResult r = control.MoveTo(target, [&](const PoseTarget&, const ControlStepResult& step) {
    worst = std::max(worst, step.max_effort_violation);
  });
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.limited_by.find(item), std::string::npos) << r.limited_by;
  EXPECT_NE(r.warning.find(item), std::string::npos) << r.warning;
  EXPECT_LE(worst, 1e-6);
  // The first item named (a base: whichever reached its limit first).
  const std::string tag = push ? "push of '" : "effort of '";
  const size_t at = r.limited_by.find(tag);
  ASSERT_NE(at, std::string::npos) << r.limited_by;
  const size_t from = at + tag.size();
  const std::string named = r.limited_by.substr(from, r.limited_by.find('\'', from) - from);
  const StaticsReport at_end = ComputeStatics(model, control.forward().state(), control.controls());
  EXPECT_NEAR(std::abs(Value(at_end, named, push)), limit, 1e-6 * limit) << named;
}

TEST(EffortLimitControl, TripodStopsWithALegMotorAtItsLimit) {
  // leg0's effort at home and at the target without a limit on it; then a
  // limit halfway between stops control there.
  Model model = Tripod();
  model.joints[1].effort = {true, -100.0, 100.0};
  const PoseTarget target{Eigen::Vector3d(0.1, -0.1, 0.95), Eigen::Vector3d::Zero()};
  ControlProblem free(model);
  free.SetControls(model.home_controls());
  const double e0 = Value(ComputeStatics(model, free.forward().state(), free.controls()), "leg0", false);
  ASSERT_TRUE(free.MoveTo(target).converged);
  const double e1 = Value(ComputeStatics(model, free.forward().state(), free.controls()), "leg0", false);
  ASSERT_GT(std::abs(e1 - e0), 1.0) << "the target must change leg0's effort";
  const double limit = 0.5 * (e0 + e1);
  model.joints[1].effort = e1 > e0 ? EffortLimits{true, -100.0, limit} : EffortLimits{true, limit, 100.0};
  ExpectStopsAtTheLimit(model, target, "leg0", false, std::abs(limit));
}

TEST(EffortLimitControl, BasesStopWithAPushAtItsLimit) {
  const Model model = LoadFile("examples/statics/4dof_payload.yaml");
  // Lower: the links flatten and every base pushes harder.
  ExpectStopsAtTheLimit(model, {Eigen::Vector3d(0.04, 0.02, 0.45), Eigen::Vector3d::Zero()}, "base", true,
                        model.mobile_bases[0].push_limit);
}

}  // namespace
}  // namespace ccma
