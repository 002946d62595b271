// Inverse dynamics and retiming (analyses/dynamics.h, analyses/retime.h;
// `ccma dynamics`, `ccma retime`) in Python: ccma.dynamics(problem,
// trajectory) and ccma.retime(problem, trajectory), with the commands'
// documents and tables, built by the same functions (documents/).
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "analyses/dynamics.h"
#include "analyses/retime.h"
#include "ccma/ccma.h"
#include "documents/control_path_csv.h"
#include "documents/dynamics_document.h"
#include "documents/retime_document.h"
#include "documents/table.h"
#include "formats/model_loader.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "python/src/json_to_python.h"
#include "python/src/usage_guard.h"
#include "viewer/view_frames.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

// The trajectory argument as CSV text and a name for messages: a path (str
// or os.PathLike, read as --trajectory is: a regular file of bounded size),
// a ccma.Table, or a result that carries one (ControlProblem.follow's,
// ccma.plan's: its `table`).
std::pair<std::string, std::string> TrajectoryText(const py::object& trajectory, const std::string& command) {
  const py::object path_like = py::module_::import("os").attr("PathLike");
  if (py::isinstance<py::str>(trajectory) || py::isinstance(trajectory, path_like)) {
    const std::string path = py::module_::import("os").attr("fspath")(trajectory).cast<std::string>();
    std::string text, error;
    if (!internal::ReadRegularFile(path, viewer::kMaxViewFileBytes, "trajectory CSV", &text, &error)) {
      throw py::value_error(command + ": " + error);
    }
    return {text, path};
  }
  py::object table = trajectory;
  if (!py::hasattr(table, "to_csv_text") && py::hasattr(trajectory, "table")) table = trajectory.attr("table");
  if (py::hasattr(table, "to_csv_text")) return {table.attr("to_csv_text")().cast<std::string>(), "<table>"};
  throw py::type_error(command + ": trajectory must be a CSV path, a ccma.Table or a result with a table "
                       "(ControlProblem.follow's, ccma.plan's)");
}

// The commands' exceptions for bad input, as ValueError.
template <typename F>
auto Checked(const std::string& command, F&& f) {
  try {
    return f();
  } catch (const viewer::ViewInputError& e) {
    throw py::value_error(command + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw py::value_error(command + ": " + e.what());
  }
}

py::object Dynamics(const ForwardProblem& p, const py::object& trajectory, const std::optional<Eigen::VectorXd>& wrench,
                    const py::object& out) {
  const ExternalWrench w = WrenchFrom(wrench, "dynamics");
  const std::string out_path = OutPath(out);
  const std::pair<std::string, std::string> input = TrajectoryText(trajectory, "dynamics");
  const std::string& text = input.first;  // (a lambda cannot capture a structured binding in C++17)
  const std::string& source = input.second;
  nlohmann::json document;
  documents::Table table;
  {
    const UsageGuard guard(p);
    py::gil_scoped_release release;
    const DynamicsReport report = Checked("dynamics", [&] {
      return ComputeDynamics(p.model(), documents::ReadControlPathText(p.model(), text, source), w);
    });
    document = documents::DynamicsDocument(report).json;
    table = documents::DynamicsTable(p.model(), report);
  }
  if (!out_path.empty()) document["out"] = out_path;
  py::dict tables;
  tables["dynamics"] = ToTable(table);
  py::object result = MakeResult("DynamicsResult", document, tables);
  if (!out_path.empty()) result.attr("to_csv")(out_path);
  return result;
}

py::object Retime(const ForwardProblem& p, const py::object& trajectory, const py::object& out) {
  const std::string out_path = OutPath(out);
  const std::pair<std::string, std::string> input = TrajectoryText(trajectory, "retime");
  const std::string& text = input.first;  // (a lambda cannot capture a structured binding in C++17)
  const std::string& source = input.second;
  nlohmann::json document;
  std::string retimed;
  {
    const UsageGuard guard(p);
    py::gil_scoped_release release;
    const ControlPath path = Checked("retime", [&] { return documents::ReadControlPathText(p.model(), text, source); });
    const RetimeReport report = Checked("retime", [&] { return ccma::Retime(p.model(), path); });
    document = documents::RetimeDocument(report, path.times.size()).json;
    if (report.feasible) retimed = documents::RetimedCsv(text, path.lines, report.times);
  }
  py::dict tables;
  if (!retimed.empty()) {
    tables["trajectory"] = TableFromCsv(retimed, "retimed trajectory");
    if (!out_path.empty()) {
      const py::object file = py::module_::import("builtins").attr("open")(out_path, "w", py::arg("newline") = "");
      file.attr("write")(retimed);
      file.attr("close")();
      document["out"] = out_path;
    }
  }
  py::dict extras;
  extras["csv_text"] = retimed.empty() ? py::object(py::none()) : py::object(py::str(retimed));
  return MakeResult("RetimeResult", document, tables, extras);
}

}  // namespace

void BindDynamics(py::module_& m) {
  m.def(
      "dynamics",
      [](const ForwardProblem& p, const py::object& trajectory, const std::optional<Eigen::VectorXd>& wrench,
         const py::object& out) { return Dynamics(p, trajectory, wrench, out); },
      py::arg("problem"), py::arg("trajectory"), py::arg("wrench") = py::none(), py::arg("out") = py::none(),
      "`ccma dynamics`: inverse dynamics along a trajectory of the problem's model (docs/dynamics.md). trajectory: "
      "a trajectory CSV's path, a ccma.Table, or ControlProblem.follow's / ccma.plan's result. Returns a "
      "ccma.DynamicsResult: the command's JSON as attributes (rows, duration_s, assembled, actuators {name, kind, "
      "peak_effort, peak_time_s, rms_effort, limit, within_limits}, within_limits, limiting, energy_J, max_power_W, "
      "max_rate_inconsistency, warning) and its --out CSV as `table` (time_s, an effort column per control [N or "
      "N*m], kinetic_J, potential_J, power_W); out=PATH writes it. wrench: fx, fy, fz [N], mx, my, mz [N*m] at the "
      "end-effector point, world frame. ValueError naming the line and column on a CSV of another model, times "
      "that do not increase or a bad cell.");
  m.def(
      "dynamics",
      [](const ControlProblem& p, const py::object& trajectory, const std::optional<Eigen::VectorXd>& wrench,
         const py::object& out) { return Dynamics(p.forward(), trajectory, wrench, out); },
      py::arg("problem"), py::arg("trajectory"), py::arg("wrench") = py::none(), py::arg("out") = py::none(),
      "The same for a ControlProblem.");
  m.def(
      "retime",
      [](const ForwardProblem& p, const py::object& trajectory, const py::object& out) {
        return Retime(p, trajectory, out);
      },
      py::arg("problem"), py::arg("trajectory"), py::arg("out") = py::none(),
      "`ccma retime`: the fastest rest-to-rest timing of a trajectory's path within every effort_limits, "
      "push_limit and velocity_limit of the problem's model (docs/dynamics.md, TOPP-RA). trajectory as for "
      "ccma.dynamics. Returns a ccma.RetimeResult: the command's JSON as attributes (feasible, rows, duration_s, "
      "original_duration_s, uniform_duration_s, method, verified_scale, limiting {name, kind, share}, infeasible, "
      "warning), the retimed CSV (the input with new time_s cells) as `table` and `csv_text` (None when "
      "infeasible); out=PATH writes it when feasible. ValueError on a model without limits or a bad CSV.");
  m.def(
      "retime",
      [](const ControlProblem& p, const py::object& trajectory, const py::object& out) {
        return Retime(p.forward(), trajectory, out);
      },
      py::arg("problem"), py::arg("trajectory"), py::arg("out") = py::none(), "The same for a ControlProblem.");
}

}  // namespace ccma::python
