// `ccma statics --model=FILE [--controls=...] [--wrench=fx,fy,fz,mx,my,mz]`:
// static equilibrium of the mechanism assembled at the controls
// (analyses/statics.h): joint reactions and the effort of every control.
#include <iostream>
#include <string>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "documents/statics_document.h"

DECLARE_double(mocap_noise_m);    // apps/replay_command.cc (the replay's noise model)
DECLARE_double(mocap_noise_rad);

namespace ccma::cli {

BasePoseNoise PoseNoiseFromFlags() {
  BasePoseNoise noise;
  const SimulationNoise replay;
  noise.position_sigma = FLAGS_mocap_noise_m >= 0 ? FLAGS_mocap_noise_m : replay.position_sigma;
  noise.heading_sigma = FLAGS_mocap_noise_rad >= 0 ? FLAGS_mocap_noise_rad : replay.heading_sigma;
  if (!(noise.position_sigma <= 1.0) || !(noise.heading_sigma <= 1.0)) {
    throw UsageError("--mocap_noise_m and --mocap_noise_rad must lie in [0, 1] (m, rad)");
  }
  return noise;
}

int RunStatics(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "statics");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "statics"));
  const ExternalWrench wrench = WrenchFlag();
  const BasePoseNoise noise = PoseNoiseFromFlags();
  const Eigen::VectorXd u = ControlsFlagOrHome(model);
  ForwardProblem forward(model);
  const ForwardResult assembly = forward.Assemble(u);
  try {
    PrintDocument(documents::StaticsDocument(model, forward.state(), forward.controls(), assembly.assembled,
                                             assembly.residual_energy, wrench, noise),
                  "statics");
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("ccma statics: ") + e.what());
  }
  return 0;
}

}  // namespace ccma::cli
