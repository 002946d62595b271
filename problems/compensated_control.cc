#include "problems/compensated_control.h"

#include <algorithm>
#include <cmath>

#include "ccma/internal/dense_factorizations.h"

#include "ccma/internal/format.h"

namespace ccma {
namespace {

// target - reached on the controlled components [m, rad] (angles wrapped to
// (-pi, pi]); 0 on the others.
Eigen::Matrix<double, 6, 1> Miss(const Model& model, const PoseTarget& target, const EndEffectorPose& reached) {
  Eigen::Matrix<double, 6, 1> miss;
  miss << target.position - reached.position, target.rpy - reached.rpy;
  for (int c = 0; c < 6; ++c) {
    if (c >= 3) miss[c] = std::remainder(miss[c], 2 * M_PI);
    if (!model.end_effector.controlled[c]) miss[c] = 0;
  }
  return miss;
}

}  // namespace

// The aim's update from the misses: Broyden's method on F(aim) = target -
// loaded end-effector (6 components, uncontrolled ones 0), starting from
// the fixed-point iteration (B = -I: aim += miss), so that the rounds
// converge superlinearly where the deflection changes with the controls.
class AimUpdate {
 public:
  Eigen::Matrix<double, 6, 1> Next(const Eigen::Matrix<double, 6, 1>& miss) {
    if (have_last_) {
      const Eigen::Matrix<double, 6, 1> dF = miss - last_miss_;
      const double ss = last_step_.squaredNorm();
      if (ss > 0) B_ += (dF - B_ * last_step_) * last_step_.transpose() / ss;
    }
    Eigen::Matrix<double, 6, 1> step = -MinimumNormSolver(Eigen::MatrixXd(B_)).solve(Eigen::VectorXd(miss));
    if (!step.allFinite()) step = miss;
    last_miss_ = miss;
    last_step_ = step;
    have_last_ = true;
    return step;
  }

 private:
  Eigen::Matrix<double, 6, 6> B_ = -Eigen::Matrix<double, 6, 6>::Identity();  // dF/d(aim)
  Eigen::Matrix<double, 6, 1> last_miss_, last_step_;
  bool have_last_ = false;
};

namespace {

// The rigid control problem toward `aim` from the current controls [adds
// its time to *solve_time_ms]. A later round (`start` given) moves them by
// the aim's small correction; where so small a move is ill-conditioned (a
// differential base heads where it drives, and the direction of a 1e-8 m
// move is anyone's), it is solved again from `start`, the first round's
// controls: a move of the whole step.
ControlResult RigidRound(ControlProblem* control, const PoseTarget& aim, const Eigen::VectorXd* start,
                         double* solve_time_ms) {
  ControlResult result = control->MoveTo(aim);
  *solve_time_ms += result.solve_time_ms;
  if (result.converged || !start) return result;
  control->SetControls(*start);
  result = control->MoveTo(aim);
  *solve_time_ms += result.solve_time_ms;
  return result;
}

}  // namespace

CompensatedResult MoveToCompensated(ControlProblem* control, const PoseTarget& target, const ExternalWrench& wrench,
                                    const CompensationOptions& options) {
  const Model& model = control->forward().model();
  CompensatedResult out;
  out.aim = target;
  out.aim.position += options.aim_offset.head<3>();
  out.aim.rpy += options.aim_offset.tail<3>();
  double solve_time_ms = 0;
  AimUpdate update;
  const std::shared_ptr<LoadedWorkspace> workspace = options.workspace ? options.workspace : NewLoadedWorkspace();
  const Eigen::VectorXd start_controls = control->controls();
  while (out.rounds < options.max_rounds) {
    ++out.rounds;
    out.control = RigidRound(control, out.aim, out.rounds == 1 ? nullptr : &start_controls, &solve_time_ms);
    // Each round's equilibrium starts from the last one: the controls moved little.
    LoadedOptions loaded_options;
    loaded_options.check_held = false;
    loaded_options.workspace = workspace;
    const LoadedEquilibrium* start = out.rounds > 1 ? &out.loaded : (options.start ? &*options.start : nullptr);
    if (start && start->converged) {
      loaded_options.start_state = start->state;
      loaded_options.start_yields = start->yields;
    }
    out.loaded = SolveLoadedEquilibrium(model, control->forward().constraints(), control->forward().state(),
                                        control->controls(), wrench, loaded_options);
    if (!out.control.converged || !out.loaded.converged) break;
    const Eigen::Matrix<double, 6, 1> miss = Miss(model, target, ComputeEndEffectorPose(model, out.loaded.state));
    out.miss = miss.cwiseAbs().maxCoeff();
    if (out.miss <= options.tolerance) {
      out.converged = true;
      break;
    }
    const Eigen::Matrix<double, 6, 1> step = update.Next(miss);
    out.aim.position += step.head<3>();
    out.aim.rpy += step.tail<3>();
  }
  out.control.solve_time_ms = solve_time_ms;
  if (options.check_held && out.loaded.converged) {
    DecideHeld(model, control->forward().constraints(), control->controls(), &out.loaded);
  }
  if (out.converged) return out;
  if (!out.control.converged) {
    out.warning = "round " + std::to_string(out.rounds) + ": the rigid end-effector did not reach the compensated aim" +
                  (out.control.warning.empty() ? "" : " (" + out.control.warning + ")");
  } else if (!out.loaded.converged) {
    out.warning = "the loaded equilibrium was not found: " + out.loaded.message;
  } else {
    out.warning = "the loaded end-effector is still " + FormatG(out.miss) + " m or rad from the target after " +
                  std::to_string(out.rounds) + " rounds";
  }
  return out;
}

}  // namespace ccma
