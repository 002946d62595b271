// `ccma export --model=FILE --format=urdf|sdf --out=FILE`: the model as URDF
// plus a closure file beside it (formats/urdf_writer.h), or as SDFormat with
// its loops (formats/sdformat_writer.h). `ccma import` of the output gives
// back the same mechanism.
#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "formats/sdformat_writer.h"
#include "formats/urdf_writer.h"

DEFINE_string(format, "", "export: the file format to write [urdf|sdf]");

namespace ccma::cli {

int RunExport(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "export");
  const std::string model_path = RequireFlag(FLAGS_model, "model", "export");
  const std::string format = RequireFlag(FLAGS_format, "format", "export");
  if (format != "urdf" && format != "sdf") throw UsageError("ccma export: --format must be urdf or sdf");
  const std::string out_path = RequireFlag(FLAGS_out, "out", "export");
  const Model model = LoadModelOrThrow(model_path);
  nlohmann::json summary = {{"out", out_path}, {"format", format}, {"closures", nullptr}};
  if (format == "urdf") {
    const UrdfExport urdf = WriteUrdf(model);
    const std::string closure_path = ClosureFilePath(out_path);
    OutputFile out(out_path, "out");
    // A name derived from --out, not given: an entry planted there (a link
    // to someone's file) is replaced, never written through.
    OutputFile closures(closure_path, "out", ExistingName::kReplace);
    out.stream() << urdf.urdf;
    closures.stream() << urdf.closures;
    closures.Commit();
    out.Commit();
    summary["closures"] = closure_path;
    summary["links"] = urdf.links;
    summary["joints"] = urdf.joints;
    summary["loops"] = urdf.loops;
  } else {
    const SdformatExport sdf = WriteSdformat(model);
    OutputFile out(out_path, "out");
    out.stream() << sdf.sdf;
    out.Commit();
    summary["links"] = sdf.links;
    summary["joints"] = sdf.joints;
    summary["loops"] = sdf.loops;
  }
  PrintJson(summary);
  return 0;
}

}  // namespace ccma::cli
