// Kinematic control: ccma.ControlProblem(model).move_to([x, y, z, r, p, y]),
// one step, path following (waypoints) and the sensitivities ds/du, dX/du.
#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl/filesystem.h>
#include <pybind11/stl.h>

#include "documents/json_values.h"
#include "documents/control_document.h"
#include "documents/trajectory_csv.h"
#include "ccma/end_effector.h"
#include "ccma/internal/format.h"
#include "ccma/model.h"
#include "formats/waypoints.h"
#include "problems/compensated_control.h"
#include "problems/control_problem.h"
#include "problems/trajectory.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "documents/trajectory_document.h"
#include "python/src/json_to_python.h"
#include "python/src/pose_types.h"
#include "python/src/usage_guard.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

Vector6d AsVector(const PoseTarget& t) {
  Vector6d v;
  v << t.position, t.rpy;
  return v;
}

// A target as `ccma control --target` takes it: six numbers x, y, z [m],
// roll, pitch, yaw [rad], or one per controlled component in that order (the
// others are filled in from the current pose; they are ignored either way).
// Another length is a ValueError naming both accepted forms; the range of
// each entry is checked by the solver (ValueError too).
PoseTarget TargetFrom(const ControlProblem& p, const Eigen::VectorXd& values) {
  const std::array<bool, 6>& controlled = p.forward().model().end_effector.controlled;
  std::vector<int> components;
  for (int c = 0; c < 6; ++c) {
    if (controlled[static_cast<size_t>(c)]) components.push_back(c);
  }
  Vector6d full = AsVector(p.CurrentPose());
  if (values.size() == 6) {
    full = values;
  } else if (values.size() == static_cast<Eigen::Index>(components.size())) {
    for (size_t i = 0; i < components.size(); ++i) full[components[i]] = values[static_cast<Eigen::Index>(i)];
  } else {
    std::string names;
    for (int c : components) {
      names += std::string(names.empty() ? "" : ",") + kEndEffectorComponentNames[static_cast<size_t>(c)];
    }
    throw py::value_error("target: expected 6 values x,y,z,roll,pitch,yaw or " + std::to_string(components.size()) +
                          " (the controlled " + names + "); got " + std::to_string(values.size()));
  }
  // As ControlProblem::MoveTo checks them, for every method (objective too,
  // which would answer NaN).
  for (int c = 0; c < 6; ++c) {
    if (!(std::abs(full[c]) <= kMaxMagnitude)) {
      throw py::value_error(std::string("target: ") + kEndEffectorComponentNames[static_cast<size_t>(c)] + " (" +
                            FormatG(full[c]) + ") must be a finite number in [-" + FormatG(kMaxMagnitude) + ", " +
                            FormatG(kMaxMagnitude) + "] (m or rad)");
    }
  }
  return {full.head<3>(), full.tail<3>()};
}

using OptionsClass = py::class_<ControlOptions>;

ControlOptions MakeControlOptions(py::kwargs kwargs) { return WithKeywords(ControlOptions(), kwargs); }

// One field of ControlOptions::Secondary as a property of ControlOptions.
void SecondaryField(OptionsClass& c, const char* name, double ControlOptions::Secondary::*field, const char* doc) {
  c.def_property(
      name, [field](const ControlOptions& o) { return o.secondary.*field; },
      [field](ControlOptions& o, double v) { o.secondary.*field = v; }, doc);
}

// ControlOptions::Secondary, flattened (redundancy resolution in the null
// space of the end-effector task).
void BindSecondaryOptions(OptionsClass& c) {
  using S = ControlOptions::Secondary;
  SecondaryField(c, "singularity_weight", &S::singularity_weight, "singularity barrier weight (0 = off) [1]");
  SecondaryField(c, "singularity_threshold", &S::singularity_threshold,
                 "sigma_0: smallest singular value of dX/du below which the barrier acts [m or rad per control unit]");
  SecondaryField(c, "pivot_weight", &S::pivot_weight, "pivot-ratio barrier weight on dG/ds (0 = off) [1]");
  SecondaryField(c, "pivot_threshold", &S::pivot_threshold,
                 "rho_0: pivot ratio of dG/ds below which that barrier acts [1]");
  SecondaryField(c, "spread_weight", &S::spread_weight, "base-spread weight (0 = off) [1/m^2]");
  SecondaryField(c, "clearance_m", &S::clearance_m, "base-to-base distance below which bases are pushed apart [m]");
  SecondaryField(c, "travel_weight", &S::travel_weight, "base-travel weight (0 = off) [1/m^2]");
}

void BindControlOptions(py::module_& m) {
  OptionsClass c(m, "ControlOptions",
                 "Options of the control solve (problems/control_problem.h); every field "
                 "is a keyword of the constructor, e.g. ControlOptions(method='bfgs').");
  c.def(py::init(&MakeControlOptions))
      .def_property(
          "method",
          [](const ControlOptions& o) { return o.method == ControlMethod::kBfgs ? "bfgs" : "lm"; },
          [](ControlOptions& o, const std::string& v) {
            if (v != "lm" && v != "bfgs") throw py::value_error("method: 'lm' or 'bfgs'");
            o.method = v == "lm" ? ControlMethod::kLevenbergMarquardt : ControlMethod::kBfgs;
          },
          "'lm' (Levenberg-Marquardt, default) or 'bfgs' (the paper's)")
      .def_property(
          "gradient",
          [](const ControlOptions& o) {
            return o.gradient == GradientMethod::kImplicit ? "implicit" : "finite_difference";
          },
          [](ControlOptions& o, const std::string& v) {
            if (v != "implicit" && v != "finite_difference") {
              throw py::value_error("gradient: 'implicit' or 'finite_difference'");
            }
            o.gradient = v == "implicit" ? GradientMethod::kImplicit : GradientMethod::kFiniteDifference;
          },
          "'implicit' (sensitivities, default) or 'finite_difference'")
      .def_readwrite("lambda_", &ControlOptions::lambda,
                     "weight of E in the objective, 0 < lambda < 1 [1]: the flag --lambda (lambda is a Python "
                     "keyword, hence the trailing underscore)")
      .def_readwrite("max_step_m", &ControlOptions::max_step_m, "path step: translation [m]")
      .def_readwrite("max_step_rad", &ControlOptions::max_step_rad, "path step: rotation [rad]")
      .def_readwrite("max_iterations", &ControlOptions::max_iterations, "outer iterations per step")
      .def_readwrite("target_tolerance", &ControlOptions::target_tolerance, "[m or rad]")
      .def_readwrite("finite_difference_step", &ControlOptions::finite_difference_step, "[m or rad]")
      .def_readwrite("forward", &ControlOptions::forward, "ForwardOptions of the inner solves");
  BindSecondaryOptions(c);
  c.def("is_valid", [](const ControlOptions& o) {
    std::string why;
    const bool ok = o.IsValid(&why);
    return py::make_tuple(ok, why);
  }, "(ok, why): whether every field is in range");
}

void BindStepResult(py::module_& m) {
  py::class_<ControlStepResult>(m, "ControlStepResult", "One solve toward one target (ControlProblem.step).")
      .def_readonly("reached", &ControlStepResult::reached)
      .def_readonly("assembled", &ControlStepResult::assembled)
      .def_readonly("singular", &ControlStepResult::singular)
      .def_readonly("iterations", &ControlStepResult::iterations)
      .def_readonly("forward_solves", &ControlStepResult::forward_solves)
      .def_readonly("objective", &ControlStepResult::objective)
      .def_readonly("error", &ControlStepResult::error, "max |e| over the controlled components [m, rad]")
      .def_readonly("residual_energy", &ControlStepResult::residual_energy, "[m^2]")
      .def_readonly("dG_ds_pivot_ratio", &ControlStepResult::rcond, "pivot ratio of dG/ds [1]")
      .def_readonly("min_singular_value_dX_du", &ControlStepResult::min_singular_value_dX_du)
      .def_readonly("max_limit_violation", &ControlStepResult::max_limit_violation, "[rad or m]")
      .def_readonly("max_effort_violation", &ControlStepResult::max_effort_violation, "[N or N*m]")
      .def_readonly("max_clearance_violation", &ControlStepResult::max_clearance_violation,
                    "how far a pair of shapes is below collision.margin [m] (0)")
      .def_readonly("max_lateral_displacement", &ControlStepResult::max_lateral_displacement, "[m]")
      .def_readonly("limited_by", &ControlStepResult::limited_by)
      .def_readonly("solve_time_ms", &ControlStepResult::time_ms, "[ms]");
}

// The configuration a result reports: the loaded one after compensate=True
// (as `ccma control --compensate`), else where the control left the mechanism.
const State& Reported(const ControlSolution& r) { return r.compensation ? r.compensation->loaded.state : r.state; }

// The attributes of `ccma control`'s JSON beyond the solve's own numbers
// (documents/control_document.h ControlDocument), computed when asked for.
// What compensate=True adds: compensation and deflection (None otherwise).
void BindCompensation(py::class_<ControlSolution>& c) {
  c.def_property_readonly(
          "compensation",
          [](const ControlSolution& r) -> py::object {
            if (!r.compensation) return py::none();
            nlohmann::json out;
            documents::AddCompensationJson(*r.model, r.rigid_end_effector, *r.compensation, &out);
            return ToView(out["compensation"]);
          },
          "move_to(compensate=True): Record {converged, rounds, miss [m or rad], aim [x, y, z, roll, pitch, yaw], "
          "rigid_end_effector}; None otherwise")
      .def_property_readonly(
          "deflection",
          [](const ControlSolution& r) -> py::object {
            if (!r.compensation) return py::none();
            nlohmann::json out;
            documents::AddLoadedJson(*r.model, r.compensation->loaded, &out);
            return ToView(out["deflection"]);
          },
          "move_to(compensate=True): the loaded configuration's deflection, as ForwardResult.deflection; None "
          "otherwise");
}

void BindControlConfiguration(py::class_<ControlSolution>& c) {
  c.def_property_readonly("model", [](const ControlSolution& r) { return r.model->name; }, "the model's name")
      .def_readonly("method", &ControlSolution::method, "'lm' or 'bfgs'")
      .def_property_readonly(
          "conditioning", [](const ControlSolution& r) { return ToView(documents::ConditioningJson(r)); },
          "Record {dG_ds_pivot_ratio, min_dG_ds_pivot_ratio_on_path [1], min_singular_value_dX_du, "
          "min_singular_value_dX_du_on_path [m or rad per control unit]}: at the end and over the path")
      .def_property_readonly(
          "secondary",
          [](const ControlSolution& r) -> py::object {
            if (!r.secondary.enabled()) return py::none();
            return ToView(documents::SecondaryJson(r.secondary, r.null_space_steps, r.secondary_objective));
          },
          "Record of the null-space objective (weights, null_space_steps, objective); None when off")
      .def_property_readonly(
          "bodies",
          [](const ControlSolution& r) {
            std::vector<BodyPose> poses;
            for (int b = 0; b < r.model->num_bodies(); ++b) poses.push_back(PoseOfBody(*r.model, Reported(r), b));
            return poses;
          },
          "every body's absolute pose at the end (BodyPose: name, position [m], rpy [rad], quaternion)")
      .def_property_readonly(
          "joints", [](const ControlSolution& r) { return ToView(documents::JointsToJson(*r.model, Reported(r))); },
          "list of Record {name, type, q [rad or m], actuated, limits?}")
      .def_property_readonly(
          "limits_violated", [](const ControlSolution& r) { return LimitsViolated(*r.model, Reported(r)); },
          "names of the joints outside their limits")
      .def_property_readonly(
          "clearance", [](const ControlSolution& r) { return ToView(documents::ClearanceToJson(*r.model, Reported(r))); },
          "Record {min [m], pair, margin [m], below_margin}; None without collision geometry")
      .def_property_readonly(
          "from_home", [](const ControlSolution& r) { return ToView(documents::FromHome(r)); },
          "Record {reproducible, end_effector_distance_m [m], end_effector_rotation_rad [rad], "
          "max_state_difference [m, rad], idle_bodies}: whether the controls, assembled from home, give this "
          "configuration up to idle motions (the bodies idle_bodies names; checked when first asked for)")
      .def_property_readonly("warning", &documents::ControlWarning,
                             "why the target was not reached, or that the controls assemble elsewhere from home "
                             "('' when neither)")
      .def(
          "to_dict", [](const ControlSolution& r) { return ToPython(documents::ControlDocument(r).json); },
          "The JSON document `ccma control` prints for the same move (same keys and values).");
}

void BindResults(py::module_& m) {
  BindStepResult(m);
  py::class_<ControlSolution> c(m, "ControlResult",
                                "The outcome of ControlProblem.move_to: the attributes of `ccma control`'s JSON "
                                "(to_dict() is that JSON), and the step constraints' measures.");
  c.def_readonly("converged", &ControlSolution::converged, "the target was reached")
      .def_readonly("assembled", &ControlSolution::assembled)
      .def_readonly("steps", &ControlSolution::steps)
      .def_readonly("iterations", &ControlSolution::iterations)
      .def_readonly("forward_solves", &ControlSolution::forward_solves)
      .def_readonly("branch_jumps_rejected", &ControlSolution::branch_jumps_rejected)
      .def_readonly("objective", &ControlSolution::objective, "O = 1/2 |e|^2 + lambda E [m^2]")
      .def_readonly("error", &ControlSolution::error, "[m, rad]")
      .def_readonly("residual_energy", &ControlSolution::residual_energy, "[m^2]")
      .def_readonly("max_step_residual_energy", &ControlSolution::max_step_residual_energy, "[m^2]")
      .def_readonly("max_limit_violation", &ControlSolution::max_limit_violation, "[rad or m]")
      .def_readonly("max_effort_violation", &ControlSolution::max_effort_violation, "[N or N*m]")
      .def_readonly("max_clearance_violation", &ControlSolution::max_clearance_violation,
                    "worst over the path's steps [m] (0)")
      .def_readonly("max_lateral_displacement", &ControlSolution::max_lateral_displacement, "[m]")
      .def_readonly("limited_by", &ControlSolution::limited_by)
      .def_readonly("solve_time_ms", &ControlSolution::solve_time_ms, "[ms]")
      .def_readonly("target", &ControlSolution::target, "[x, y, z, roll, pitch, yaw]")
      .def_readonly("controls", &ControlSolution::controls, "all controls at the end")
      .def_readonly("end_effector", &ControlSolution::end_effector, "pose assembled at `controls`")
      .def("__repr__", [](const ControlSolution& r) {
        return std::string("<ccma.ControlResult converged=") + (r.converged ? "True" : "False") +
               " steps=" + std::to_string(r.steps) + " error=" + FormatG(r.error) +
               " residual_energy=" + FormatG(r.residual_energy) + ">";
      });
  BindControlConfiguration(c);
  BindCompensation(c);
}

// move_to(target, compensate, wrench): `ccma control [--compensate]`.
ControlSolution MoveTo(ControlProblem& p, const Eigen::VectorXd& values, bool compensate,
                       const std::optional<Eigen::VectorXd>& wrench) {
  const UsageGuard guard(p);
  const PoseTarget target = TargetFrom(p, values);
  if (wrench && !compensate) throw py::value_error("move_to: wrench only with compensate=True (the loads it compensates)");
  const ExternalWrench w = WrenchFrom(wrench, "move_to");
  if (!compensate) return documents::MakeControlSolution(p, p.MoveTo(target), target, std::nullopt);
  try {
    CompensatedResult compensated = MoveToCompensated(&p, target, w);
    return documents::MakeControlSolution(p, {}, target, std::move(compensated));
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("move_to: ") + e.what());
  }
}

// `ccma trajectory [--compensate]` in Python: the JSON summary and the CSV
// (as a ccma.Table), written to `out` too when given.
py::object Follow(ControlProblem& p, const std::vector<Waypoint>& waypoints, const py::object& out, bool compensate,
                  const std::optional<Eigen::VectorXd>& wrench) {
  CheckWaypoints(waypoints);
  if (wrench && !compensate) throw py::value_error("follow: wrench only with compensate=True (the loads it compensates)");
  const ExternalWrench w = WrenchFrom(wrench, "follow");
  const std::string out_path = OutPath(out);
  std::ostringstream csv_text;
  nlohmann::json document;
  {
    py::gil_scoped_release release;
    const UsageGuard guard(p);
    documents::TrajectoryCsv csv(p.forward().model(), csv_text);
    documents::TrajectorySolution solution;
    solution.control = &p;
    solution.waypoints = waypoints.size();
    const auto on_step = [&](const TrajectoryStep& step) {
      csv.Write(step);
      solution.tally.Add(step);
    };
    if (compensate) solution.compensation.emplace();  // (ValueError from std::invalid_argument, as the plain path's)
    solution.result = compensate ? FollowWaypointsCompensated(p, waypoints, w, on_step, &*solution.compensation)
                                 : FollowWaypoints(p, waypoints, on_step);
    solution.path_clearance = csv.min_clearance();
    document = documents::TrajectoryDocument(solution).json;
  }
  if (!out_path.empty()) document["out"] = out_path;
  py::dict tables;
  tables["trajectory"] = TableFromCsv(csv_text.str(), "trajectory");
  py::object result = MakeResult("TrajectoryResult", document, tables);
  if (!out_path.empty()) result.attr("to_csv")(out_path);
  return result;
}

using ProblemClass = py::class_<ControlProblem>;

// The target forms every method below accepts (TargetFrom).
constexpr const char* kTargetForms =
    "target: [x, y, z, roll, pitch, yaw] ([m], [rad]), or only the model's controlled components in that "
    "order (as `ccma control --target`; the others are ignored); ValueError on another length";

// Setting the controls, one step, a whole move and a path.
void BindControlSolves(ProblemClass& c) {
  c.def(py::init<const Model&, const ControlOptions&>(), py::arg("model"), py::arg("options") = ControlOptions(),
        py::keep_alive<1, 2>())
      .def(
          "set_controls",
          [](ControlProblem& p, const Eigen::VectorXd& u) {
            const UsageGuard guard(p);
            const bool at_home = AtHome(p.forward());
            const ForwardResult r = p.SetControls(u);
            return MakeForwardSolution(p.forward(), r, at_home ? "home" : "current");
          },
          py::arg("u"), py::call_guard<py::gil_scoped_release>(), py::keep_alive<0, 1>(),
          "Assembles the mechanism at u (following the branch) and starts from there.")
      .def(
          "step",
          [](ControlProblem& p, const Eigen::VectorXd& t) {
            const UsageGuard guard(p);
            return p.SolveStep(TargetFrom(p, t));
          },
          py::arg("target"), py::call_guard<py::gil_scoped_release>(),
          (std::string("One solve toward the target without path splitting (for small moves). ") + kTargetForms)
              .c_str())
      .def("move_to", &MoveTo, py::arg("target"), py::arg("compensate") = false, py::arg("wrench") = py::none(),
           py::call_guard<py::gil_scoped_release>(), py::keep_alive<0, 1>(),
           (std::string("Walks the end-effector to the target in steps of at most max_step_m and max_step_rad. "
                        "compensate=True (`ccma control --compensate`, a model with stiffness keys): the controls "
                        "put the loaded end-effector (under gravity, the payload and wrench [fx, fy, fz [N], mx, my, "
                        "mz [N*m]]) on the target; end_effector, error and converged are then the loaded ones and "
                        "`compensation` tells how. ") +
            kTargetForms)
               .c_str())
      .def("follow", &Follow, py::arg("waypoints"), py::arg("out") = py::none(), py::arg("compensate") = false,
           py::arg("wrench") = py::none(),
           "`ccma trajectory`: follows a list of ccma.Waypoint (e.g. ccma.load_waypoints(path)); stops at the "
           "first waypoint it cannot reach. Returns a ccma.TrajectoryResult: the command's JSON as attributes "
           "(to_dict()), its CSV, one row per path step, as `table`; out=PATH writes that CSV too. ValueError "
           "(naming the waypoint) on a value the waypoint CSV refuses: a time not finite, beyond 1e6 s or "
           "smaller than the one before, a position or angle not finite or beyond 1e4, more than 1e6 waypoints. "
           "compensate=True (`ccma trajectory --compensate`, a model with stiffness keys): every step puts the "
           "loaded end-effector (under gravity, the payload and wrench [fx, fy, fz [N], mx, my, mz [N*m]]) on "
           "its target; the rows, end_effector and clearance are then the loaded ones, and `compensation` "
           "{rounds, max_miss [m or rad]} tells how.")
      .def(
          "follow",
          [](ControlProblem& p, const Eigen::Ref<const RowMatrix>& a, const py::object& out, bool compensate,
             const std::optional<Eigen::VectorXd>& wrench) {
            return Follow(p, WaypointsFromArray(a), out, compensate, wrench);
          },
          py::arg("waypoints"), py::arg("out") = py::none(), py::arg("compensate") = false,
          py::arg("wrench") = py::none(), "The same for an (N x 7) array of rows [time, x, y, z, roll, pitch, yaw].");
}

// The objective, the sensitivities and where the problem is now.
void BindDerivatives(ProblemClass& c) {
  c.def(
       "objective",
       [](ControlProblem& p, const Eigen::VectorXd& t) {
         Eigen::VectorXd g;
         double o = 0;
         {
           py::gil_scoped_release release;
           const UsageGuard guard(p);
           o = p.Objective(TargetFrom(p, t), &g);
         }
         return py::make_tuple(o, g);
       },
       py::arg("target"),
       (std::string("(O, dO/du_eff) at the current controls (effective controls only). ") + kTargetForms).c_str())
      .def(
          "state_sensitivity",
          [](ControlProblem& p) -> Eigen::MatrixXd {
            const UsageGuard guard(p);
            return p.StateSensitivity();
          },
          py::call_guard<py::gil_scoped_release>(),
           "ds/du: (state_size x effective controls) at the current solution (m or rad per control unit)")
      .def(
          "end_effector_jacobian",
          [](ControlProblem& p) -> Eigen::MatrixXd {
            const UsageGuard guard(p);
            const Eigen::MatrixXd ds_du = p.StateSensitivity();
            return EndEffectorJacobian(p.forward().model(), p.forward().state()) * ds_du;
          },
          py::call_guard<py::gil_scoped_release>(),
          "dX_EE/du: (6 x effective controls), rows x y z [m] then rotation increment [rad]")
      .def_property_readonly(
          "controls",
          [](const ControlProblem& p) -> Eigen::VectorXd {
            const UsageGuard guard(p);
            return p.controls();
          },
          "current controls (a copy)")
      .def_property_readonly("effective_controls", &ControlProblem::effective_controls,
                             "indices into controls that the solver changes")
      .def_property_readonly(
          "forward", [](ControlProblem& p) -> ForwardProblem& { return p.forward(); },
          py::return_value_policy::reference_internal, "the inner ForwardProblem (state, body poses)")
      .def_property_readonly(
          "current_pose",
          [](const ControlProblem& p) {
            const UsageGuard guard(p);
            return AsVector(p.CurrentPose());
          },
          "[x, y, z, roll, pitch, yaw] of the end-effector now");
}

void BindControlProblem(py::module_& m) {
  ProblemClass c(m, "ControlProblem",
                 "Kinematic control: controls u whose assembly puts the end-effector at a target "
                 "(min 1/2 |e|^2 + lambda E, gradients from implicit sensitivities). Keeps the model alive. "
                 "One thread at a time: a call while another thread is inside one raises RuntimeError.");
  BindControlSolves(c);
  BindDerivatives(c);
}

void BindWaypoints(py::module_& m) {
  py::register_exception<WaypointError>(m, "WaypointError", PyExc_ValueError).attr("__doc__") =
      "Raised by load_waypoints when a waypoint CSV cannot be read or is malformed (a missing "
      "column, a value that is not a number, time going backwards; docs/waypoints.md). Carries "
      "one argument, the message 'file:line: what' (str(e), e.args[0]). A subclass of ValueError.";
  py::class_<Waypoint>(m, "Waypoint", "An end-effector waypoint: time [s], position [m], rpy [rad].")
      .def(py::init([](double time, const Eigen::Vector3d& position, const Eigen::Vector3d& rpy) {
             return Waypoint{time, position, rpy};
           }),
           py::arg("time"), py::arg("position"), py::arg("rpy") = Eigen::Vector3d::Zero())
      .def_readwrite("time", &Waypoint::time)
      .def_readwrite("position", &Waypoint::position)
      .def_readwrite("rpy", &Waypoint::rpy);
  m.def("load_waypoints", [](const std::filesystem::path& path) { return LoadWaypoints(path.string()); },
        py::arg("path"),
        "Reads a waypoint CSV (time,x,y,z,roll,pitch,yaw; docs/waypoints.md); raises ccma.WaypointError.");
}

}  // namespace

void BindControl(py::module_& m) {
  BindControlOptions(m);
  BindResults(m);
  BindWaypoints(m);
  BindControlProblem(m);
}

}  // namespace ccma::python
