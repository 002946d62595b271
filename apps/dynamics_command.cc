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

Command DynamicsCommand() {
  return {"dynamics", "inverse dynamics along a trajectory CSV: every control's effort while it moves",
          "ccma dynamics --model=FILE --trajectory=FILE.csv [--out=FILE.csv] [--wrench=fx,fy,fz,mx,my,mz]",
          "The efforts a motion takes: the trajectory's controls (time_s and its control columns, as ccma\n"
          "trajectory and ccma plan write them) as a natural cubic spline in time; at every row the mechanism\n"
          "is assembled, its bodies' velocities and accelerations follow from the controls' through the exact\n"
          "first- and second-order sensitivities, and the effort of every control is statics' plus the inertia\n"
          "of every mass (mass, com, inertia; the payload): Newton-Euler with the constraint multipliers, the\n"
          "same code as ccma statics, so at rest the two agree exactly. Prints rows, duration_s, assembled,\n"
          "actuators [{name, kind, peak_effort, peak_time_s, rms_effort, limit, peak_rate, rate_limit,\n"
          "within_limits}] (efforts against effort_limits / push_limit, rates against velocity_limit),\n"
          "within_limits, limiting, energy_J (the trapezoid of power_W over the rows), max_power_W. --out:\n"
          "one row per input row: time_s, an effort column per control (u0_x_N, u0_theta_Nm, u_<joint>_Nm),\n"
          "kinetic_J, potential_J, power_W. A CSV of another model (its x_m, y_m, z_m not where this model's\n"
          "end-effector assembles), times that do not increase or a bad cell: exit 2 naming file, line, column.",
          {"model", "trajectory", "out", "wrench"}, RunDynamics,
          {{"trajectory", "the trajectory CSV to run (ccma trajectory's or ccma plan's --out) [file]"},
           {"out", "the CSV to write, one row per trajectory row: efforts, energies, power [path]"}}};
}

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
