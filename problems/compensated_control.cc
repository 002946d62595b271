#include "problems/compensated_control.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <utility>

#include "ccma/internal/dense_factorizations.h"
#include "ccma/internal/format.h"
#include "problems/internal/end_effector_error.h"
#include "problems/internal/compensated_newton.h"
#include "problems/internal/compliant_equilibrium.h"

namespace ccma {
namespace {


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

// The aim a corrected round stands for: the rigid end-effector's pose at
// the controls, on the controlled components.
void AimAtRigidPose(const ControlProblem& control, PoseTarget* aim) {
  const PoseTarget rigid = control.CurrentPose();
  for (int c = 0; c < 6; ++c) {
    if (!control.forward().model().end_effector.controlled[c]) continue;
    (c < 3 ? aim->position[c] : aim->rpy[c - 3]) = c < 3 ? rigid.position[c] : rigid.rpy[c - 3];
  }
}

// Where a loaded equilibrium is expected after the controls moved the rigid
// assembly from `rigid_from` to `rigid_to`: the latter deflected as the
// last equilibrium `loaded` was from the former (each body by the same
// tangent, the yields kept). Its error is the deflection's change, not the
// controls' move, so the Newton iteration starts about that much closer.
LoadedOptions StartFrom(const LoadedEquilibrium& loaded, const State& rigid_from, const State& rigid_to) {
  LoadedOptions options;
  State start = rigid_to;
  start.Plus(loaded.state.Minus(rigid_from));
  options.start_state = std::move(start);
  options.start_yields = loaded.yields;
  return options;
}

// The Newton finish after the first rigid round
// (problems/internal/compensated_newton.h): the loaded equilibrium and the
// controls that put its end-effector on the target, from the round's
// controls and the loaded configuration expected there (`start`, or the
// rigid assembly). True when the control problem accepts the controls
// (ControlProblem::CorrectTo) and the loaded end-effector is on the target
// (the Newton iteration's last point passed the loaded equilibrium's own
// tests): out->loaded, miss, aim and rounds are then set.
bool NewtonFinish(ControlProblem* control, const PoseTarget& target, const ExternalWrench& wrench,
                  const CompensationOptions& options, const LoadedOptions& start,
                  const std::shared_ptr<LoadedWorkspace>& workspace, CompensatedResult* out) {
  const Model& model = control->forward().model();
  if (!model.compliant() || !control->correctable()) return false;  // (a rigid model's loaded end-effector is its own)
  const ConstraintSet& set = control->forward().constraints();
  const std::vector<int> compliant = CompliantEquilibrium::CompliantControls(model);
  LoadedPoint x{start.start_state ? *start.start_state : control->forward().state(),
                Eigen::VectorXd::Zero(static_cast<Eigen::Index>(compliant.size()))};
  for (size_t i = 0; start.start_state && i < compliant.size(); ++i) {
    x.delta[static_cast<Eigen::Index>(i)] = start.start_yields[compliant[i]];
  }
  Eigen::VectorXd u = control->controls();
  CompensatedNewtonOptions newton;
  newton.tolerances = LoadedTolerancesFor(model, control->forward().state(), wrench, LoadedOptions().force_tolerance);
  newton.error_tolerance = 0.1 * options.tolerance;
  const CompensatedNewtonResult newton_result =
      SolveCompensatedNewton(model, set, target, control->effective_controls(), wrench, newton, workspace.get(), &x, &u);
  if (!newton_result.converged || !control->CorrectTo(u)) return false;
  LoadedEquilibrium loaded;
  loaded.converged = true;
  loaded.iterations = newton_result.iterations;
  loaded.unbalanced = newton_result.unbalanced;
  DescribeLoadedPoint(model, control->forward().state(), x, compliant, &loaded);
  const double miss = ControlledMiss(model, target, ComputeEndEffectorPose(model, loaded.state)).cwiseAbs().maxCoeff();
  if (!(miss <= options.tolerance)) return false;
  out->loaded = std::move(loaded);
  out->miss = miss;
  out->converged = true;
  ++out->rounds;
  AimAtRigidPose(*control, &out->aim);
  out->control.residual_energy = control->forward().Energy();
  return true;
}

// Rounds of rigid control and loaded equilibria (the header's method), the
// first round's rigid control already made: from its loaded equilibrium
// (started from `first`), the aim moves by Broyden's update until the
// loaded end-effector is on the target. `start_controls`: those the call
// began with (RigidRound's retry).
void Rounds(ControlProblem* control, const PoseTarget& target, const ExternalWrench& wrench,
            const CompensationOptions& options, LoadedOptions first, const std::shared_ptr<LoadedWorkspace>& workspace,
            const Eigen::VectorXd& start_controls, double* solve_time_ms, CompensatedResult* out) {
  const Model& model = control->forward().model();
  AimUpdate update;
  LoadedOptions loaded_options = std::move(first);
  while (true) {
    loaded_options.check_held = false;
    loaded_options.workspace = workspace;
    out->loaded = SolveLoadedEquilibrium(model, control->forward().constraints(), control->forward().state(),
                                         control->controls(), wrench, loaded_options);
    // The miss of the configuration reported, also when a round failed
    // (the loaded one at the fraction of the loads it held).
    const Eigen::Matrix<double, 6, 1> miss = ControlledMiss(model, target, ComputeEndEffectorPose(model, out->loaded.state));
    out->miss = miss.cwiseAbs().maxCoeff();
    if (!out->control.converged || !out->loaded.converged) return;
    if (out->miss <= options.tolerance) {
      out->converged = true;
      return;
    }
    if (out->rounds >= options.max_rounds) return;
    const Eigen::Matrix<double, 6, 1> step = update.Next(miss);
    out->aim.position += step.head<3>();
    out->aim.rpy += step.tail<3>();
    ++out->rounds;
    // Each round's equilibrium starts from the last one's deflection, on
    // the new rigid assembly.
    const State rigid_before = control->forward().state();
    out->control = RigidRound(control, out->aim, &start_controls, solve_time_ms);
    loaded_options = StartFrom(out->loaded, rigid_before, control->forward().state());
  }
}

// Why the compensation did not converge.
std::string Warning(const CompensatedResult& out) {
  if (!out.control.converged) {
    return "round " + std::to_string(out.rounds) + ": the rigid end-effector did not reach the compensated aim" +
           (out.control.warning.empty() ? "" : " (" + out.control.warning + ")");
  }
  if (!out.loaded.converged) return "the loaded equilibrium was not found: " + out.loaded.message;
  return "the loaded end-effector is still " + FormatG(out.miss) + " m or rad from the target after " +
         std::to_string(out.rounds) + " rounds";
}

}  // namespace

Eigen::Matrix<double, 6, 1> ControlledMiss(const Model& model, const PoseTarget& target, const EndEffectorPose& reached) {
  Eigen::Matrix<double, 6, 1> miss;
  miss << target.position - reached.position, target.rpy - reached.rpy;
  for (int c = 0; c < 6; ++c) {
    if (c >= 3) miss[c] = std::remainder(miss[c], 2 * M_PI);
    if (!model.end_effector.controlled[c]) miss[c] = 0;
  }
  return miss;
}

CompensatedResult MoveToCompensated(ControlProblem* control, const PoseTarget& target, const ExternalWrench& wrench,
                                    const CompensationOptions& options) {
  const Model& model = control->forward().model();
  CompensatedResult out;
  out.aim = target;
  out.aim.position += options.aim_offset.head<3>();
  out.aim.rpy += options.aim_offset.tail<3>();
  double solve_time_ms = 0;
  const std::shared_ptr<LoadedWorkspace> workspace = options.workspace ? options.workspace : NewLoadedWorkspace();
  const State rigid_before = control->forward().state();
  const Eigen::VectorXd start_controls = control->controls();
  out.rounds = 1;
  out.control = RigidRound(control, out.aim, nullptr, &solve_time_ms);
  // The first loaded equilibrium is expected where options.start's
  // deflection puts the new rigid assembly.
  LoadedOptions first;
  if (options.start && options.start->converged && options.start->state.num_bodies() == rigid_before.num_bodies()) {
    first = StartFrom(*options.start, rigid_before, control->forward().state());
  }
  if (!out.control.converged || !NewtonFinish(control, target, wrench, options, first, workspace, &out)) {
    Rounds(control, target, wrench, options, first, workspace, start_controls, &solve_time_ms, &out);
  }
  out.control.solve_time_ms = solve_time_ms;
  if (options.check_held && out.loaded.converged) {
    DecideHeld(model, control->forward().constraints(), control->controls(), &out.loaded);
  }
  if (!out.converged) out.warning = Warning(out);
  return out;
}

}  // namespace ccma
