// `ccma simulate --model=FILE [--controls=u0,u1,...]`: the forward problem,
// from the home configuration to the given controls.
#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/json_output.h"

DECLARE_string(model);
DECLARE_string(controls);

namespace ccma::cli {

int RunSimulate(const std::vector<std::string>& args) {
  ParseFlags(args, {"model", "controls"}, "simulate");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "simulate"));
  const Eigen::VectorXd u = ControlsFlagOrHome(model);

  ForwardProblem forward(model);
  const ForwardResult result = forward.Assemble(u);

  nlohmann::json out;
  out["model"] = model.name;
  out["converged"] = result.converged;
  out["assembled"] = result.assembled;
  out["residual_energy"] = result.residual_energy;
  out["assembly_tolerance"] = forward.options().assembly_tolerance;
  out["iterations"] = result.iterations;
  out["substeps"] = result.substeps;
  out["solve_time_ms"] = result.solve_time_ms;
  out["controls"] = ToJson(u);
  out["end_effector"] = ToJson(forward.end_effector());
  out["bodies"] = BodiesToJson(model, forward.state());
  out["message"] = result.message;
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
