// `ccma generate --agents=N --out=FILE`: write a Stewart-like model with N
// mobile bases (the family of 6dof_six_agents; see ccma/model_generator.h).
#include <fstream>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/json_output.h"

DECLARE_string(out);
DEFINE_int32(agents, 0, "number of mobile bases, >= 3");

namespace ccma::cli {

int RunGenerate(const std::vector<std::string>& args) {
  ParseFlags(args, {"agents", "out"}, "generate");
  if (FLAGS_agents < 3) throw UsageError("ccma generate: --agents must be an integer >= 3");
  if (FLAGS_agents > 1000) throw UsageError("ccma generate: --agents must be at most 1000");
  const std::string out_path = RequireFlag(FLAGS_out, "out", "generate");
  StewartOptions options;
  options.agents = FLAGS_agents;
  const std::string text = GenerateStewartModel(options);
  const Model model = LoadModelFromString(text, out_path);  // validate before writing
  std::ofstream out(out_path);
  if (!(out << text)) throw UsageError("ccma generate: --out: cannot write '" + out_path + "'");
  out.close();
  nlohmann::json summary = {{"model", model.name},       {"agents", model.num_bases()},
                            {"bodies", model.num_bodies()}, {"state_size", model.state_size()},
                            {"controls", model.num_controls()}, {"out", out_path}};
  PrintJson(summary);
  return 0;
}

}  // namespace ccma::cli
