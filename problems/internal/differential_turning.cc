#include "problems/internal/differential_turning.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "ccma/rotation.h"
#include "problems/internal/constrained_lm_step.h"
#include "problems/internal/control_linearization.h"
#include "problems/internal/control_workspace.h"

namespace ccma {

bool DifferentialTurning::FaceTheMotion(const PoseTarget& target, Eigen::VectorXd* u) {
  const Model& model = p_.forward_.model();
  std::vector<int> differential;
  for (int k = 0; k < model.num_bases(); ++k) {
    if (model.mobile_bases[k].type == BaseType::kDifferential) differential.push_back(k);
  }
  if (differential.empty()) return false;
  // Where would the bases go if they could slide? (a Gauss-Newton step)
  ControlLinearization lin;
  p_.Linearize(target, &lin);
  const Eigen::VectorXd d =
      ConstrainedLmStep(lin.DenseJtJ(), lin.Jtr, 1e-12 * std::max(lin.DenseJtJ().trace(), 1e-30), LinearConstraints{}, lin.eigen());
  *u = p_.forward_.controls();
  const std::vector<int>& column = p_.workspace_->effective_column;
  bool turned = false;
  for (int k : differential) {
    const int i = model.base_control(k);
    if (column[i] < 0 || column[i + 1] < 0) continue;
    const double dx = d[column[i]], dy = d[column[i + 1]];
    if (std::hypot(dx, dy) < 1e-9) continue;
    // Face the motion, forwards or backwards, whichever is the smaller turn.
    double change = WrapAngle(std::atan2(dy, dx) - (*u)[i + 2]);
    if (change > M_PI / 2) change -= M_PI;
    if (change < -M_PI / 2) change += M_PI;
    if (std::abs(change) <= kMaxArcTurn) continue;
    (*u)[i + 2] += change;
    turned = true;
  }
  return turned;
}

bool DifferentialTurning::Turn(const PoseTarget& target, ControlStepResult* turn) {
  const auto start = std::chrono::steady_clock::now();
  Eigen::VectorXd u;
  if (!FaceTheMotion(target, &u)) return false;
  ForwardProblem& forward = p_.forward_;
  const PoseTarget before = p_.CurrentPose();
  const State state_before = forward.state();
  const Eigen::VectorXd u_before = forward.controls();
  p_.workspace_->step_constraints.Begin(forward.controls(), forward.state());  // a turn on the spot: no lateral motion
  const ForwardResult assembled = forward.Assemble(u);
  ++p_.forward_solves_;
  *turn = ControlStepResult();
  p_.Finish(before, turn);  // the end-effector must not have moved
  turn->assembled = assembled.assembled;
  turn->reached = turn->reached && assembled.assembled && !assembled.branch_jump;
  if (!turn->reached) {
    // The headings are not free in this chain (turning moves the
    // end-effector): no turn; the step must manage under its constraints.
    forward.Restore(state_before, u_before);
    return false;
  }
  turn->iterations = 1;
  turn->forward_solves = assembled.substeps;
  turn->time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return true;
}

}  // namespace ccma
