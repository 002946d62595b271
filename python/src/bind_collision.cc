// Obstacles and collisions (docs/obstacles.md) in Python: the clearance at a
// problem's current configuration, and whole-trajectory planning
// (problems/plan.h) as ccma.plan.
#include <sstream>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "documents/json_values.h"
#include "documents/plan_document.h"
#include "documents/trajectory_csv.h"
#include "ccma/ccma.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "python/src/json_to_python.h"
#include "python/src/usage_guard.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

// `ccma plan` in Python: the JSON summary and the CSV (as a ccma.Table),
// written to `out` too when given.
py::object Plan(ControlProblem& p, const std::vector<Waypoint>& waypoints, const PlanOptions& options,
                const py::object& out) {
  const std::string out_path = OutPath(out);
  std::ostringstream csv_text;
  nlohmann::json document;
  {
    py::gil_scoped_release release;
    const UsageGuard guard(p);
    const PlanResult r = PlanTrajectory(p, waypoints, options);
    documents::TrajectoryCsv csv(p.forward().model(), csv_text);
    for (const TrajectoryStep& step : r.steps) csv.Write(step);
    document = documents::PlanDocument(p, r, waypoints.size(), csv.min_clearance()).json;
  }
  if (!out_path.empty()) document["out"] = out_path;
  py::dict tables;
  tables["plan"] = TableFromCsv(csv_text.str(), "plan");
  py::object result = MakeResult("PlanResult", document, tables);
  if (!out_path.empty()) result.attr("to_csv")(out_path);
  return result;
}

}  // namespace

void BindCollision(py::module_& m) {
  m.def(
      "clearance",
      [](const ForwardProblem& p) {
        const UsageGuard guard(p);
        return ToView(documents::ClearanceToJson(p.model(), p.state()));
      },
      py::arg("problem"),
      "The smallest clearance over the checked pairs of shapes at the problem's current configuration "
      "(docs/obstacles.md), as `ccma simulate`'s \"clearance\": a ccma.Record {min [m] (negative: overlap "
      "depth), pair [a, b], margin [m], below_margin}, or None when the model has no collision geometry or "
      "obstacles.");
  m.def(
      "clearance",
      [](const ControlProblem& p) {
        const UsageGuard guard(p);
        return ToView(documents::ClearanceToJson(p.forward().model(), p.forward().state()));
      },
      py::arg("problem"), "The same for a ControlProblem.");
  m.def(
      "plan",
      [](ControlProblem& p, const std::vector<Waypoint>& waypoints, double path_weight, double smoothness_weight,
         double travel_weight, int plan_iterations, double plan_time_s, const py::object& out) {
        PlanOptions options;
        const PlanCommandSettings settings{path_weight, smoothness_weight, travel_weight, plan_iterations, plan_time_s};
        if (std::string why; !PlanOptionsFromSettings(settings, &options, &why)) throw py::value_error("plan: " + why);
        CheckWaypoints(waypoints);
        return Plan(p, waypoints, options, out);
      },
      py::arg("problem"), py::arg("waypoints"), py::arg("path_weight") = 1e-2, py::arg("smoothness_weight") = 1.0,
      py::arg("travel_weight") = 1e-2, py::arg("plan_iterations") = 200, py::arg("plan_time_s") = 120.0,
      py::arg("out") = py::none(),
      "`ccma plan`: whole-trajectory planning from the problem's current controls (docs/obstacles.md). "
      "Returns a ccma.PlanResult: the command's JSON as attributes (to_dict()): converged, used ('plan' or "
      "'greedy'), iterations, stopped_by ('converged', 'plan_iterations' or 'plan_time_s'), finishing "
      "(repaired_rows, inserted_rows), shortfall (only when the finished plan stayed below the margin), "
      "greedy and plan (reached_waypoints, travel_m, min_clearance_m), controls, end_effector, clearance, "
      "warning; its CSV (the columns of `ccma trajectory`, one row per step) as `table`; out=PATH writes "
      "that CSV too. Keywords as the flags: path_weight, smoothness_weight, travel_weight, plan_iterations, "
      "plan_time_s [s] (bounds the detour seeds and the optimisation). Raises ValueError for differential "
      "bases, the bfgs method, options out of range or waypoints the waypoint CSV refuses (a value not "
      "finite or out of range, a time smaller than the one before; the message names the waypoint).");
}

}  // namespace ccma::python
