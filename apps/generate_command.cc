// `ccma generate --agents=N [--kind=K] --out=FILE`: flags in, the generated
// model file out (documents/generate_document.h decides and builds it).
#include <fstream>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/flags.h"
#include "apps/commands.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "documents/generate_document.h"

DEFINE_int32(agents, 0, "number of mobile bases (or legs with --kind=stewart_gough), 3..1000 [agents]");
DEFINE_string(kind, "ccma",
              "ccma: mobile bases with R-R-S legs (family of 6dof_six_agents); stewart_gough: a UPS "
              "platform on the ground with actuated legs, no base (>= 6 legs); legged: quadrupeds, each "
              "carrying an arm that holds the platform (family of 6dof_three_legged) [ccma|stewart_gough|legged]");

namespace ccma::cli {

int RunGenerate(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "generate");
  documents::GenerateSettings settings;
  settings.kind = FLAGS_kind;
  settings.agents = FLAGS_agents;
  if (std::string why; !settings.IsValid(&why)) throw UsageError("ccma generate: " + why);
  const std::string out_path = RequireFlag(FLAGS_out, "out", "generate");
  documents::Generated generated = documents::GenerateModel(settings, out_path);
  OutputFile out(out_path, "out");
  out.stream() << generated.text;
  out.Commit();
  generated.document.json["out"] = out_path;
  PrintJson(generated.document.json);
  return 0;
}

}  // namespace ccma::cli
