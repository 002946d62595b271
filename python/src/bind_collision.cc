// Obstacles and collisions (docs/obstacles.md) in Python: the clearance at a
// problem's current configuration, and whole-trajectory planning
// (problems/plan.h) as ccma.plan.
#include <limits>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "ccma/ccma.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "python/src/usage_guard.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

// {"min", "pair", "margin", "below_margin"}, or None without collision geometry.
py::object ClearanceAt(const Model& model, const State& s) {
  const CollisionModel collision(model);
  const ClearanceSummary c = MinimumClearance(collision, s);
  if (!c.any) return py::none();
  py::dict d;
  d["min"] = c.min;
  d["pair"] = py::make_tuple(c.a, c.b);
  d["margin"] = collision.margin();
  d["below_margin"] = c.min < collision.margin() - 1e-9;
  return std::move(d);
}

py::dict MeasuresDict(const PathMeasures& m) {
  py::dict d;
  d["reached_waypoints"] = m.reached_waypoints;
  d["travel_m"] = m.travel_m;
  d["min_clearance_m"] = m.min_clearance_m;  // inf without collision geometry
  return d;
}

py::dict Plan(ControlProblem& p, const std::vector<Waypoint>& waypoints, const PlanOptions& options) {
  PlanResult r;
  {
    const UsageGuard guard(p);
    py::gil_scoped_release release;
    r = PlanTrajectory(p, waypoints, options);
  }
  const Model& model = p.forward().model();
  const CollisionModel collision(model);
  const int n = static_cast<int>(r.steps.size());
  Eigen::VectorXd time(n), clearance(n);
  RowMatrix controls(n, model.num_controls()), reached(n, 6);
  for (int i = 0; i < n; ++i) {
    const TrajectoryStep& s = r.steps[static_cast<size_t>(i)];
    time[i] = s.time;
    controls.row(i) = s.controls.transpose();
    reached.row(i) << s.reached.position.transpose(), s.reached.rpy.transpose();
    const ClearanceSummary c = MinimumClearance(collision, s.state);
    clearance[i] = c.any ? c.min : std::numeric_limits<double>::infinity();
  }
  py::dict d;
  d["converged"] = r.converged;
  d["used"] = r.used_plan ? "plan" : "greedy";
  d["note"] = r.note;
  d["iterations"] = r.iterations;
  d["stopped_by"] = r.stopped_by;
  d["finishing"] = py::dict(py::arg("repaired_rows") = r.repaired_rows,
                            py::arg("inserted_rows") = r.inserted_rows);
  d["shortfall"] = py::none();
  if (r.shortfall.any) {
    const PlanShortfall& f = r.shortfall;
    py::dict s;
    s["step"] = f.step;
    s["midpoint"] = f.midpoint;
    s["time_s"] = f.time_s;
    s["torn"] = f.torn;
    if (f.torn) {
      s["residual_energy"] = f.residual_energy;
    } else {
      s["pair"] = py::make_tuple(f.a, f.b);
      s["clearance_m"] = f.clearance_m;
      s["floor_m"] = f.floor_m;
      s["shortfall_m"] = f.shortfall_m;
    }
    d["shortfall"] = s;
  }
  d["greedy"] = MeasuresDict(r.greedy);
  d["plan"] = MeasuresDict(r.plan);
  d["time"] = time;
  d["controls"] = controls;
  d["reached"] = reached;
  d["clearance"] = clearance;
  d["solve_time_ms"] = r.solve_time_ms;
  return d;
}

}  // namespace

void BindCollision(py::module_& m) {
  m.def(
      "clearance", [](const ForwardProblem& p) { return ClearanceAt(p.model(), p.state()); }, py::arg("problem"),
      "The smallest clearance over the checked pairs of shapes at the problem's current configuration "
      "(docs/obstacles.md): {'min': m (negative: overlap depth), 'pair': (a, b), 'margin': m, "
      "'below_margin': bool}, or None when the model has no collision geometry or obstacles.");
  m.def(
      "clearance", [](const ControlProblem& p) { return ClearanceAt(p.forward().model(), p.forward().state()); },
      py::arg("problem"), "The same for a ControlProblem.");
  m.def(
      "plan",
      [](ControlProblem& p, const std::vector<Waypoint>& waypoints, double path_weight,
         double smoothness_weight, double travel_weight, int max_iterations, double max_seconds) {
        PlanOptions options;
        options.max_seconds = max_seconds;
        options.path_weight = path_weight;
        options.smoothness_weight = smoothness_weight;
        options.travel_weight = travel_weight;
        options.max_iterations = max_iterations;
        std::string why;
        if (!options.IsValid(&why)) throw py::value_error("plan: " + why);
        CheckWaypoints(waypoints);
        return Plan(p, waypoints, options);
      },
      py::arg("problem"), py::arg("waypoints"), py::arg("path_weight") = 1e-2,
      py::arg("smoothness_weight") = 1.0, py::arg("travel_weight") = 1e-2,
      py::arg("max_iterations") = 200, py::arg("max_seconds") = 120.0,
      "Whole-trajectory planning from the problem's current controls (`ccma plan`, "
      "docs/obstacles.md): "
      "returns a dict: converged, used ('plan' or 'greedy'), note, iterations, stopped_by "
      "('converged', "
      "'plan_iterations' or 'plan_time_s': max_seconds [s] bounds the seeds and the optimisation), "
      "finishing "
      "(repaired_rows, inserted_rows), shortfall (None, or where the finished plan is below the "
      "margin, as the "
      "CLI's JSON), greedy and plan "
      "(reached_waypoints, travel_m, min_clearance_m), and per step time [s], controls, reached "
      "(x y z [m] roll pitch yaw [rad]) and clearance [m] (inf without collision geometry). "
      "Raises ValueError for differential bases, the bfgs method, options out of range or "
      "waypoints the "
      "waypoint CSV refuses (a value not finite or out of range, a time smaller than the one "
      "before; the "
      "message names the waypoint).");
}

}  // namespace ccma::python
