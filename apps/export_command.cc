// `ccma export --model=FILE --format=urdf|sdf|mjcf --out=FILE`: the model as URDF
// plus a closure file beside it (formats/urdf_writer.h), or as SDFormat with
// its loops (formats/sdformat_writer.h). `ccma import` of the output gives
// back the same mechanism.
#include <memory>
#include <string>
#include <vector>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "documents/export_document.h"

DEFINE_string(format, "", "export: the file format to write [urdf|sdf|mjcf]");

namespace ccma::cli {

int RunExport(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "export");
  const std::string model_path = RequireFlag(FLAGS_model, "model", "export");
  const std::string format = RequireFlag(FLAGS_format, "format", "export");
  if (!documents::IsExportFormat(format)) {
    throw UsageError(std::string("ccma export: --format must be ") + documents::kExportFormats);
  }
  const std::string out_path = RequireFlag(FLAGS_out, "out", "export");
  const Model model = LoadModelOrThrow(model_path);
  documents::Export exported = documents::ExportModel(model, format, out_path);
  // All checked before any is written.
  std::vector<std::unique_ptr<OutputFile>> files;
  for (const documents::ExportedFile& f : exported.files) {
    files.push_back(std::make_unique<OutputFile>(f.path, "out", f.derived ? ExistingName::kReplace : ExistingName::kFollow));
    files.back()->stream() << f.text;
  }
  for (auto file = files.rbegin(); file != files.rend(); ++file) (*file)->Commit();
  exported.document.json["out"] = out_path;
  PrintJson(exported.document.json);
  return 0;
}

}  // namespace ccma::cli
