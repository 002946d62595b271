// The control step's constraints (problems/internal/step_constraint.h):
// every row of the linearisation against central differences of the
// constraint itself through re-solved forward problems (joint limits: q(u)
// along the assembly; differential arcs: the lateral displacement l(u)),
// the rows' order, the active set's growth and the report.
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ccma/joint_coordinates.h"
#include "formats/model_loader.h"
#include "problems/forward_problem.h"
#include "problems/internal/sensitivity.h"
#include "problems/internal/step_constraints.h"
#include "tests/hinge_model.h"

namespace ccma {
namespace step_constraints_test {

// kHinge: tests/hinge_model.h.

Model Load(const std::string& file) { return LoadModel(std::string(CCMA_MODELS_DIR) + "/" + file); }

// ds/du over the effective controls at the assembled state.
Eigen::MatrixXd StateSensitivity(const ForwardProblem& forward, const std::vector<int>& effective) {
  return Sensitivity(forward.constraints(), forward.state(), forward.controls(), effective).StateSensitivity();
}

// The joint-limit rows A d = b: A = dq/du (central differences of q along
// re-assembled mechanisms), b = bound - q.
void ExpectLimitRowsMatchDifferences(const Model& model, const Eigen::VectorXd& u) {
  const std::vector<int> effective = model.effective_control_indices();
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Assemble(u).assembled);
  const StepConstraints constraints(model, effective);
  ActiveSet active = constraints.NoneActive();
  std::vector<int> limited;
  for (int j = 0; j < static_cast<int>(model.joints.size()); ++j) {
    if (model.joints[j].limited) limited.push_back(j);
  }
  ASSERT_FALSE(limited.empty());
  active.back() = limited;  // joint limits come last
  const State base = forward.state();
  const Eigen::MatrixXd ds_du = StateSensitivity(forward, effective);
  const LinearConstraints rows = constraints.Linearize(u, base, ds_du, active);
  const int first = rows.rows() - static_cast<int>(limited.size());
  ASSERT_GE(first, 0);
  const double h = 1e-6;
  for (size_t c = 0; c < effective.size(); ++c) {
    Eigen::VectorXd up = u, down = u;
    up[effective[c]] += h;
    down[effective[c]] -= h;
    forward.SetState(base);
    ASSERT_TRUE(forward.Solve(up).assembled);
    const State s_up = forward.state();
    forward.SetState(base);
    ASSERT_TRUE(forward.Solve(down).assembled);
    const State s_down = forward.state();
    for (size_t i = 0; i < limited.size(); ++i) {
      const Joint& joint = model.joints[limited[i]];
      const double numeric = (JointCoordinate(joint, s_up) - JointCoordinate(joint, s_down)) / (2 * h);
      EXPECT_NEAR(rows.A(first + static_cast<int>(i), static_cast<int>(c)), numeric, 1e-7)
          << joint.name << " control " << effective[c];
    }
  }
  // b = bound - q for the nearer bound.
  for (size_t i = 0; i < limited.size(); ++i) {
    const Joint& joint = model.joints[limited[i]];
    const double q = JointCoordinate(joint, base);
    const double bound = std::abs(q - joint.lower) < std::abs(q - joint.upper) ? joint.lower : joint.upper;
    EXPECT_DOUBLE_EQ(rows.b[first + static_cast<int>(i)], bound - q);
  }
}

TEST(StepConstraints, JointLimitRowsAreDqDuOnTheHinge) {
  const Model model = LoadModelFromString(kHinge, "hinge.yaml");
  Eigen::VectorXd u = model.home_controls();
  u[0] += 0.01;
  ExpectLimitRowsMatchDifferences(model, u);
}

TEST(StepConstraints, JointLimitRowsAreDqDuOnTheStewartGough) {
  const Model model = Load("stewart_gough_6ups.yaml");
  Eigen::VectorXd u = model.home_controls();
  for (int i = 0; i < u.size(); ++i) u[i] += 0.003 * std::sin(1.7 * i + 0.3);  // seeded, deterministic
  ExpectLimitRowsMatchDifferences(model, u);
}

TEST(StepConstraints, ArcRowsAreTheLateralDisplacementsGradient) {
  const Model model = Load("4dof_differential.yaml");
  const std::vector<int> effective = model.effective_control_indices();
  StepConstraints constraints(model, effective);
  ASSERT_FALSE(constraints.empty());
  const Eigen::VectorXd u0 = model.home_controls();
  ForwardProblem forward(model);
  const State s = forward.state();
  constraints.Begin(u0, s);
  Eigen::VectorXd u = u0;
  for (int i = 0; i < u.size(); ++i) u[i] += 0.01 * std::cos(0.9 * i + 0.1);
  const Eigen::MatrixXd ds_du = Eigen::MatrixXd::Zero(model.state_size(), static_cast<Eigen::Index>(effective.size()));
  const ActiveSet none = constraints.NoneActive();
  const LinearConstraints rows = constraints.Linearize(u, s, ds_du, none);
  ASSERT_EQ(rows.rows(), model.num_bases());  // one arc row per differential base, no limit rows
  // b = -l(u); A = dl/du, both from the step's start u0.
  const double h = 1e-6;
  for (size_t c = 0; c < effective.size(); ++c) {
    Eigen::VectorXd up = u, down = u;
    up[effective[c]] += h;
    down[effective[c]] -= h;
    const Eigen::VectorXd numeric =
        (constraints.Linearize(down, s, ds_du, none).b - constraints.Linearize(up, s, ds_du, none).b) / (2 * h);
    for (int r = 0; r < rows.rows(); ++r) {
      EXPECT_NEAR(rows.A(r, static_cast<int>(c)), numeric[r], 1e-8) << "row " << r << " control " << c;
    }
  }
  // The largest |l| is what Hold() compares with its tolerance.
  const double largest = rows.b.cwiseAbs().maxCoeff();
  ASSERT_GT(largest, 1e-4);
  EXPECT_TRUE(constraints.Hold(u, s, 1.000001 * largest));
  EXPECT_FALSE(constraints.Hold(u, s, 0.999999 * largest));
  EXPECT_TRUE(constraints.Hold(u0, s, 1e-15));  // no displacement at the start
}

TEST(StepConstraints, ActiveSetGrowsWithTheJointAStepWouldPushPastItsBound) {
  const Model model = LoadModelFromString(kHinge, "hinge.yaml");
  const std::vector<int> effective = model.effective_control_indices();
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Assemble(model.home_controls()).assembled);
  const StepConstraints constraints(model, effective);
  const Eigen::MatrixXd ds_du = StateSensitivity(forward, effective);
  // The hinge's q moves with its motor control: find that column.
  const Joint& hinge = model.joints[1];
  ASSERT_EQ(hinge.name, "hinge");
  Eigen::VectorXd d = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(effective.size()));
  ActiveSet active = constraints.NoneActive();
  EXPECT_FALSE(constraints.Grow(forward.controls(), forward.state(), ds_du, d, &active));  // no change: nothing crosses
  const Eigen::RowVectorXd dq_du = [&] {
    ActiveSet all = constraints.NoneActive();
    all.back() = {1};
    return Eigen::RowVectorXd(constraints.Linearize(forward.controls(), forward.state(), ds_du, all).A.row(0));
  }();
  ASSERT_GT(dq_du.norm(), 0.5);
  d = 0.5 * dq_du.transpose() / dq_du.squaredNorm();  // q + 0.5 rad: past the upper bound 0.3
  EXPECT_TRUE(constraints.Grow(forward.controls(), forward.state(), ds_du, d, &active));
  EXPECT_EQ(active.back(), std::vector<int>({1}));
  EXPECT_FALSE(constraints.Grow(forward.controls(), forward.state(), ds_du, d, &active));  // already held: no growth
  // The report names it once the joint sits at its bound.
  ControlStepResult result;
  constraints.Report(forward.controls(), forward.state(), active, &result);
  EXPECT_EQ(result.limited_by, "");  // q = 0 at home: not at a bound
  EXPECT_EQ(result.max_limit_violation, 0.0);
}

}  // namespace
}  // namespace ccma
