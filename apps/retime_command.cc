// `ccma retime --model=FILE --trajectory=FILE.csv --out=FILE.csv`: the
// fastest timing of a trajectory's path within every effort and rate limit,
// rest to rest (analyses/retime.h); the output is the input with new times.
#include <iostream>
#include <string>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "documents/control_path_csv.h"
#include "documents/retime_document.h"
#include "formats/model_loader.h"
#include "viewer/view_frames.h"

DECLARE_string(trajectory);  // apps/view_command.cc

namespace ccma::cli {

Command RetimeCommand() {
  return {"retime", "the fastest timing of a trajectory's path within every effort and rate limit",
          "ccma retime --model=FILE --trajectory=FILE.csv --out=FILE.csv",
          "The same path (the trajectory's rows, in order) at the fastest timing that keeps every control's\n"
          "effort within its effort_limits / push_limit and its rate within its velocity_limit, from rest to\n"
          "rest: the efforts along the path are affine in s'' and s'^2, and TOPP-RA (reachability analysis,\n"
          "Pham and Pham 2018) finds the fastest profile over the rows; the timing is then checked by the same\n"
          "inverse dynamics as ccma dynamics (a natural spline through the new times) and stretched where a row\n"
          "is beyond a limit. The best uniform time scaling of the input is computed too; the faster is kept.\n"
          "--out: the input CSV, every byte as it was but the time_s cells. Prints feasible, rows, duration_s,\n"
          "original_duration_s, uniform_duration_s, method (topp-ra or uniform), verified_scale, limiting\n"
          "[{name, kind, share}]. A path beyond a limit even at rest: feasible false, infeasible {row, line,\n"
          "time_s, control, kind, effort, limit}, a warning, no file. A model without limits: exit 2.",
          {"model", "trajectory", "out"}, RunRetime,
          {{"trajectory", "the trajectory CSV whose path to retime (ccma trajectory's or ccma plan's --out) [file]"},
           {"out", "the retimed CSV to write: the input with new time_s [path]"}}};
}

int RunRetime(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "retime");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "retime"));
  const std::string trajectory = RequireFlag(FLAGS_trajectory, "trajectory", "retime");
  const std::string out = RequireFlag(FLAGS_out, "out", "retime");
  std::string text, error;
  if (!internal::ReadRegularFile(trajectory, viewer::kMaxViewFileBytes, "trajectory CSV", &text, &error)) {
    throw UsageError("ccma retime: " + error);
  }
  ControlPath path;
  RetimeReport report;
  try {
    path = documents::ReadControlPathText(model, text, trajectory);
    report = Retime(model, path);
  } catch (const viewer::ViewInputError& e) {
    throw UsageError(std::string("ccma retime: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("ccma retime: ") + e.what());
  }
  documents::Document document = documents::RetimeDocument(report, path.times.size());
  if (report.feasible) {
    OutputFile file(out, "out");
    file.stream() << documents::RetimedCsv(text, path.lines, report.times);
    file.Commit();
    document.json["out"] = out;
  }
  PrintDocument(document, "retime");
  return 0;
}

}  // namespace ccma::cli
