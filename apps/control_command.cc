// `ccma control --model=FILE --target=x,y,z,roll,pitch,yaw [--controls=...]
//  [--method=lm|bfgs] [--max_step_m=0.01] [--max_step_rad=0.005] [--lambda=0.5]`:
// kinematic control, walking the end-effector to the target in small steps.
#include <cmath>
#include <iostream>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/json_output.h"

DECLARE_string(model);
DECLARE_string(controls);
DEFINE_string(target, "", "end-effector target x,y,z [m], roll,pitch,yaw [rad]");
DEFINE_string(method, "lm", "outer loop: lm (Levenberg-Marquardt, default) or bfgs (the paper's)");
DEFINE_double(max_step_m, 0.010, "path step: end-effector translation per step [m]");
DEFINE_double(max_step_rad, 0.005, "path step: end-effector rotation per step [rad]");
DEFINE_double(lambda, 0.5, "weight of the residual energy in the objective, 0 < lambda < 1");

namespace ccma::cli {

ControlOptions ControlOptionsFromFlags() {
  ControlOptions options;
  if (FLAGS_method == "lm") {
    options.method = ControlMethod::kLevenbergMarquardt;
  } else if (FLAGS_method == "bfgs") {
    options.method = ControlMethod::kBfgs;
  } else {
    throw UsageError("--method: '" + FLAGS_method + "' is not lm or bfgs");
  }
  if (!(FLAGS_max_step_m > 0) || !std::isfinite(FLAGS_max_step_m)) {
    throw UsageError("--max_step_m must be a positive number");
  }
  if (!(FLAGS_max_step_rad > 0) || !std::isfinite(FLAGS_max_step_rad)) {
    throw UsageError("--max_step_rad must be a positive number");
  }
  if (!(FLAGS_lambda > 0 && FLAGS_lambda < 1)) throw UsageError("--lambda must lie in (0, 1)");
  options.max_step_m = FLAGS_max_step_m;
  options.max_step_rad = FLAGS_max_step_rad;
  options.lambda = FLAGS_lambda;
  return options;
}

const std::set<std::string> kControlFlags = {"model", "controls", "method", "max_step_m",
                                             "max_step_rad", "lambda"};

int RunControl(const std::vector<std::string>& args) {
  std::set<std::string> allowed = kControlFlags;
  allowed.insert("target");
  ParseFlags(args, allowed, "control");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "control"));
  const Eigen::VectorXd target_values = ParseNumberList(RequireFlag(FLAGS_target, "target", "control"), "target");
  if (target_values.size() != 6) {
    throw UsageError("--target: expected 6 values x,y,z,roll,pitch,yaw; got " +
                     std::to_string(target_values.size()));
  }
  const ControlOptions options = ControlOptionsFromFlags();
  const Eigen::VectorXd start = ControlsFlagOrHome(model);

  ControlProblem control(model, options);
  const ForwardResult start_assembly = control.SetControls(start);
  const PoseTarget target{target_values.head<3>(), target_values.tail<3>()};
  ControlResult result = control.MoveTo(target);
  if (!start_assembly.assembled) {
    result.warning = "the starting controls do not assemble (E = " +
                     std::to_string(start_assembly.residual_energy) + "); " + result.warning;
  }

  nlohmann::json out;
  out["model"] = model.name;
  out["method"] = FLAGS_method;
  out["converged"] = result.converged;
  out["assembled"] = result.assembled;
  out["steps"] = result.steps;
  out["iterations"] = result.iterations;
  out["forward_solves"] = result.forward_solves;
  out["objective"] = result.objective;
  out["error"] = result.error;
  out["residual_energy"] = result.residual_energy;
  out["max_step_residual_energy"] = result.max_step_residual_energy;
  out["conditioning"] = {{"dG_ds_pivot_ratio", result.rcond},
                         {"min_dG_ds_pivot_ratio_on_path", result.min_rcond},
                         {"min_singular_value_dX_du", result.min_singular_value_dX_du}};
  out["solve_time_ms"] = result.solve_time_ms;
  out["target"] = ToJson(target_values);
  out["controls"] = ToJson(control.controls());
  out["end_effector"] = ToJson(control.forward().end_effector());
  if (!result.warning.empty()) {
    out["warning"] = result.warning;
    std::cerr << "ccma control: warning: " << result.warning << "\n";
  }
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
