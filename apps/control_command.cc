// `ccma control --model=FILE --target=... [--controls=...] [control flags]`:
// kinematic control, walking the end-effector to the target in small steps.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <utility>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/work_bound.h"
#include "ccma/internal/format.h"
#include "documents/control_document.h"
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

// The move to the target: plain, or (--compensate) putting the loaded
// end-effector there.
documents::ControlSolution Move(ControlProblem* control, const PoseTarget& target) {
  if (!FLAGS_wrench.empty() && !FLAGS_compensate) throw UsageError("--wrench: only with --compensate (the loads it compensates)");
  if (!FLAGS_compensate) return documents::MakeControlSolution(*control, control->MoveTo(target), target, std::nullopt);
  try {
    CompensatedResult compensated = MoveToCompensated(control, target, WrenchFlag());
    return documents::MakeControlSolution(*control, {}, target, std::move(compensated));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("ccma control --compensate: ") + e.what());
  }
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
  documents::ControlSolution solution = Move(&control, target);
  if (!start_assembly.assembled) {
    solution.warning = "the starting controls do not assemble (E = " + FormatG(start_assembly.residual_energy) +
                       "); " + solution.warning;
  }
  PrintDocument(documents::ControlDocument(solution), "control");
  return 0;
}

}  // namespace ccma::cli
