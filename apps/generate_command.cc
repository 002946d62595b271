// `ccma generate --agents=N --out=FILE`: write a Stewart-like model with N
// mobile bases (the family of 6dof_six_agents; see formats/model_generator.h).
#include <fstream>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/flags.h"
#include "apps/commands.h"
#include "apps/json_output.h"
#include "apps/output_file.h"

DEFINE_int32(agents, 0, "number of mobile bases (or legs with --kind=stewart_gough), 3..1000 [agents]");
DEFINE_string(kind, "ccma",
              "ccma: mobile bases with R-R-S legs (family of 6dof_six_agents); stewart_gough: a UPS "
              "platform on the ground with actuated legs, no base (>= 6 legs); legged: quadrupeds, each "
              "carrying an arm that holds the platform (family of 6dof_three_legged) [ccma|stewart_gough|legged]");

namespace ccma::cli {

int RunGenerate(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "generate");
  if (FLAGS_agents < 3) throw UsageError("ccma generate: --agents must be an integer >= 3");
  if (FLAGS_agents > 1000) throw UsageError("ccma generate: --agents must be at most 1000");
  const std::string out_path = RequireFlag(FLAGS_out, "out", "generate");
  StewartOptions options;
  options.agents = FLAGS_agents;
  if (FLAGS_kind != "ccma" && FLAGS_kind != "stewart_gough" && FLAGS_kind != "legged") {
    throw UsageError("ccma generate: --kind must be ccma, stewart_gough or legged");
  }
  if (FLAGS_kind == "stewart_gough" && FLAGS_agents < 6) {
    throw UsageError("ccma generate: --kind=stewart_gough needs --agents >= 6");
  }
  LeggedOptions legged;
  legged.agents = FLAGS_agents;
  const std::string text = FLAGS_kind == "ccma"            ? GenerateStewartModel(options)
                           : FLAGS_kind == "legged"        ? GenerateLeggedModel(legged)
                                                           : GenerateStewartGoughModel(options);
  const Model model = LoadModelFromString(text, out_path);  // validate before writing
  OutputFile out(out_path, "out");
  out.stream() << text;
  out.Commit();
  nlohmann::json summary = {{"model", model.name},       {"agents", model.num_bases()},
                            {"actuated_joints", model.num_actuated_joints()},
                            {"bodies", model.num_bodies()}, {"state_size", model.state_size()},
                            {"controls", model.num_controls()}, {"out", out_path}};
  PrintJson(summary);
  return 0;
}

}  // namespace ccma::cli
