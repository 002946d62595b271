// `ccma dynamics --model=FILE --trajectory=FILE.csv [--out=FILE.csv]
// [--wrench=fx,fy,fz,mx,my,mz]`: inverse dynamics along a trajectory CSV
// (analyses/dynamics.h): the effort every control spends while the
// mechanism moves, row by row, and its peaks, energy and power.
#include <iostream>
#include <optional>
#include <string>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "documents/control_path_csv.h"
#include "documents/dynamics_document.h"
#include "viewer/view_frames.h"

DECLARE_string(trajectory);  // apps/view_command.cc

namespace ccma::cli {

int RunDynamics(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "dynamics");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "dynamics"));
  const std::string trajectory = RequireFlag(FLAGS_trajectory, "trajectory", "dynamics");
  const ExternalWrench wrench = WrenchFlag();
  DynamicsReport report;
  try {
    const ControlPath path = documents::ReadControlPath(model, trajectory);
    report = ComputeDynamics(model, path, wrench);
  } catch (const viewer::ViewInputError& e) {
    throw UsageError(std::string("ccma dynamics: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("ccma dynamics: ") + e.what());
  }
  documents::Document document = documents::DynamicsDocument(report);
  if (!FLAGS_out.empty()) {
    OutputFile file(FLAGS_out, "out");
    documents::WriteCsv(documents::DynamicsTable(model, report), file.stream());
    file.Commit();
    document.json["out"] = FLAGS_out;
  }
  PrintDocument(document, "dynamics");
  return 0;
}

}  // namespace ccma::cli
