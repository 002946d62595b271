// `ccma control --model=FILE --target=... [--controls=...] [control flags]`:
// kinematic control, walking the end-effector to the target in small steps.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>

#include "analyses/configuration_difference.h"
#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/work_bound.h"
#include "ccma/internal/format.h"
#include "problems/path.h"

DEFINE_string(target, "",
              "end-effector target: x,y,z [m], roll,pitch,yaw [rad]; or only the model's controlled "
              "components, in that order [m, rad]");


namespace ccma::cli {
namespace {

// --target: six values, or one per controlled component (the others keep
// their home value; they are ignored).
PoseTarget TargetFlag(const Model& model, const PoseTarget& home) {
  const Eigen::VectorXd values = ParseNumberList(RequireFlag(FLAGS_target, "target", "control"), "target");
  std::vector<int> components;
  for (int c = 0; c < 6; ++c) {
    if (model.end_effector.controlled[c]) components.push_back(c);
  }
  Eigen::Matrix<double, 6, 1> full;
  full << home.position, home.rpy;
  if (values.size() == 6) {
    full = values;
  } else if (values.size() == static_cast<int>(components.size())) {
    for (size_t i = 0; i < components.size(); ++i) full[components[i]] = values[static_cast<int>(i)];
  } else {
    std::string names;
    for (int c : components) names += std::string(names.empty() ? "" : ",") + kEndEffectorComponentNames[c];
    throw UsageError("--target: expected 6 values x,y,z,roll,pitch,yaw or " + std::to_string(components.size()) +
                     " (the controlled " + names + "); got " + std::to_string(values.size()));
  }
  for (int c = 0; c < 6; ++c) {
    if (std::abs(full[c]) > kMaxMagnitude) {
      throw UsageError(std::string("--target: ") + kEndEffectorComponentNames[c] + " (" + FormatG(full[c]) +
                       ") must lie in [-1e4, 1e4] (m or rad)");
    }
  }
  return {full.head<3>(), full.tail<3>()};
}

// Do the returned controls, assembled from home the way `ccma simulate
// --controls=...` does, give the same configuration? Not always: a path can
// lead to another assembly branch of the same controls. Idle motions (a rod
// spinning about its axis) are not branches: analyses/configuration_difference.h.
nlohmann::json CheckReproducibleFromHome(const Model& model, const ControlProblem& control, std::string* warning) {
  ForwardProblem from_home(model);
  const ForwardResult r = from_home.Assemble(control.controls());
  const ConfigurationDifference difference =
      CompareConfigurations(model, control.forward().state(), from_home.state(), control.controls());
  const bool same = r.assembled && difference.same;
  if (!same) {
    *warning += std::string(warning->empty() ? "" : "; ") +
                "these controls, simulated from home (ccma simulate --controls=...), assemble to another "
                "configuration (end-effector " + FormatG(difference.end_effector_distance) + " m away" +
                (r.assembled ? "" : ", not assembled") +
                "): the mechanism has several assembly branches here; reproduce this result exactly with "
                "ccma simulate --from=<this JSON>";
  }
  nlohmann::json idle = nlohmann::json::array();
  for (const int b : difference.idle_bodies) idle.push_back(model.bodies[b].name);
  return {{"reproducible", same},
          {"end_effector_distance_m", difference.end_effector_distance},
          {"end_effector_rotation_rad", difference.end_effector_rotation},
          {"max_state_difference", difference.max_state_difference},
          {"idle_bodies", idle}};
}

// The move to the target: plain, or (--compensate) putting the loaded
// end-effector there, its rounds in `compensated`.
ControlResult Move(ControlProblem* control, const PoseTarget& target, CompensatedResult* compensated) {
  if (!FLAGS_wrench.empty() && !FLAGS_compensate) throw UsageError("--wrench: only with --compensate (the loads it compensates)");
  if (!FLAGS_compensate) return control->MoveTo(target);
  try {
    *compensated = MoveToCompensated(control, target, WrenchFlag());
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("ccma control --compensate: ") + e.what());
  }
  ControlResult result = compensated->control;
  if (!compensated->warning.empty()) {
    result.warning += std::string(result.warning.empty() ? "" : "; ") + "--compensate: " + compensated->warning;
  }
  return result;
}

// Work bounded by its cost (--max_minutes): the path's steps timed as they
// are made; every further path (a compensated control's later rounds) a
// stage of its own.
void BoundTheMove(ControlProblem* control, const PoseTarget& target, std::shared_ptr<WorkEstimate>* estimate) {
  long steps = 1;
  try {
    const ControlOptions& o = control->options();
    steps = PosePath(control->forward().model(), control->CurrentPose(), target, o.max_step_m, o.max_step_rad).steps();
  } catch (const std::invalid_argument&) {
    // MoveTo says why the path cannot be taken.
  }
  *estimate = std::make_shared<WorkEstimate>(
      CommandWorkEstimate("control", FLAGS_compensate ? "path steps (first round)" : "path steps", false), steps);
  control->SetPathStepObserver([bound = *estimate, first = true](int step, int path_steps) mutable {
    if (step == 1 && !first) bound->BeginStage("path steps (a later round)", path_steps, 0, true);
    first = false;
    bound->Update(step);
  });
}

}  // namespace

int RunControl(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "control");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "control"));
  ControlOptions options = ControlOptionsFromFlags();
  ApplySecondaryFlags(&options);
  const Eigen::VectorXd start = ControlsFlagOrHome(model);
  ControlProblem control(model, options);
  const PoseTarget target = TargetFlag(model, control.CurrentPose());

  const ForwardResult start_assembly = control.SetControls(start);
  std::shared_ptr<WorkEstimate> estimate;
  BoundTheMove(&control, target, &estimate);
  CompensatedResult compensated;
  ControlResult result = Move(&control, target, &compensated);
  if (!start_assembly.assembled) {
    result.warning = "the starting controls do not assemble (E = " + FormatG(start_assembly.residual_energy) +
                     "); " + result.warning;
  }
  const nlohmann::json from_home = CheckReproducibleFromHome(model, control, &result.warning);

  nlohmann::json out;
  out["model"] = model.name;
  out["method"] = FLAGS_method;
  out["converged"] = result.converged;
  out["assembled"] = result.assembled;
  out["steps"] = result.steps;
  out["iterations"] = result.iterations;
  out["forward_solves"] = result.forward_solves;
  out["branch_jumps_rejected"] = result.branch_jumps_rejected;
  out["objective"] = result.objective;
  out["error"] = result.error;
  out["residual_energy"] = result.residual_energy;
  out["max_step_residual_energy"] = result.max_step_residual_energy;
  out["conditioning"] = {{"dG_ds_pivot_ratio", result.rcond},
                         {"min_dG_ds_pivot_ratio_on_path", result.min_rcond},
                         {"min_singular_value_dX_du", result.min_singular_value_dX_du},
                         {"min_singular_value_dX_du_on_path", result.min_singular_value_dX_du_on_path}};
  if (options.secondary.enabled()) {
    out["secondary"] = SecondaryJson(options.secondary, result.null_space_steps, result.secondary_objective);
  }
  out["solve_time_ms"] = result.solve_time_ms;
  out["target"] = {target.position[0], target.position[1], target.position[2],
                   target.rpy[0],      target.rpy[1],      target.rpy[2]};
  out["controls"] = ToJson(control.controls());
  out["end_effector"] = ToJson(control.forward().end_effector());
  out["bodies"] = BodiesToJson(model, control.forward().state());
  out["joints"] = JointsToJson(model, control.forward().state());
  out["limits_violated"] = LimitsViolatedToJson(model, control.forward().state());
  AddClearance(model, FLAGS_compensate ? compensated.loaded.state : control.forward().state(), "control", &out);
  out["from_home"] = from_home;
  if (FLAGS_compensate) AddCompensationJson(model, control.forward().end_effector(), compensated, &out);
  if (!result.warning.empty()) {
    out["warning"] = result.warning;
    std::cerr << "ccma control: warning: " << result.warning << "\n";
  }
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
