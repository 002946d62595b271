// Kinematic control: ccma.ControlProblem(model).move_to([x, y, z, r, p, y]),
// one step, path following (waypoints) and the sensitivities ds/du, dX/du.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl/filesystem.h>
#include <pybind11/stl.h>

#include "ccma/end_effector.h"
#include "ccma/internal/format.h"
#include "ccma/model.h"
#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "problems/trajectory.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "python/src/pose_types.h"
#include "python/src/usage_guard.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

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

// ControlResult plus where it left the mechanism.
struct ControlSolution : ControlResult {
  Vector6d target;
  Eigen::VectorXd controls;
  EndEffectorPose end_effector;
};

// A followed path, one row per step (NumPy arrays).
struct TrajectorySolution : TrajectoryResult {
  Eigen::VectorXd time;          // s
  RowMatrix targets;             // steps x 6
  RowMatrix reached;             // steps x 6: x y z [m], roll pitch yaw [rad]
  RowMatrix controls;            // steps x num_controls
  Eigen::VectorXd residual_energy;
  Eigen::VectorXd error;         // m or rad
  Eigen::Matrix<bool, Eigen::Dynamic, 1> step_reached;
};

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

void BindOptions(py::module_& m) {
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
      .def_readwrite("lambda_", &ControlOptions::lambda, "weight of E in the objective, 0 < lambda < 1")
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
      .def_readonly("rcond", &ControlStepResult::rcond, "pivot ratio of dG/ds")
      .def_readonly("min_singular_value_dX_du", &ControlStepResult::min_singular_value_dX_du)
      .def_readonly("max_limit_violation", &ControlStepResult::max_limit_violation, "[rad or m]")
      .def_readonly("max_effort_violation", &ControlStepResult::max_effort_violation, "[N or N*m]")
      .def_readonly("max_clearance_violation", &ControlStepResult::max_clearance_violation,
                    "how far a pair of shapes is below collision.margin [m] (0)")
      .def_readonly("max_lateral_displacement", &ControlStepResult::max_lateral_displacement, "[m]")
      .def_readonly("limited_by", &ControlStepResult::limited_by)
      .def_readonly("time_ms", &ControlStepResult::time_ms, "[ms]");
}

void BindResults(py::module_& m) {
  BindStepResult(m);
  py::class_<ControlSolution>(m, "ControlResult", "The outcome of ControlProblem.move_to.")
      .def_readonly("converged", &ControlSolution::converged, "the target was reached")
      .def_readonly("assembled", &ControlSolution::assembled)
      .def_readonly("steps", &ControlSolution::steps)
      .def_readonly("iterations", &ControlSolution::iterations)
      .def_readonly("forward_solves", &ControlSolution::forward_solves)
      .def_readonly("objective", &ControlSolution::objective)
      .def_readonly("error", &ControlSolution::error, "[m, rad]")
      .def_readonly("residual_energy", &ControlSolution::residual_energy, "[m^2]")
      .def_readonly("max_step_residual_energy", &ControlSolution::max_step_residual_energy, "[m^2]")
      .def_readonly("rcond", &ControlSolution::rcond)
      .def_readonly("min_rcond", &ControlSolution::min_rcond)
      .def_readonly("min_singular_value_dX_du", &ControlSolution::min_singular_value_dX_du)
      .def_readonly("max_limit_violation", &ControlSolution::max_limit_violation, "[rad or m]")
      .def_readonly("max_effort_violation", &ControlSolution::max_effort_violation, "[N or N*m]")
      .def_readonly("max_clearance_violation", &ControlSolution::max_clearance_violation,
                    "worst over the path's steps [m] (0)")
      .def_readonly("max_lateral_displacement", &ControlSolution::max_lateral_displacement, "[m]")
      .def_readonly("limited_by", &ControlSolution::limited_by)
      .def_readonly("solve_time_ms", &ControlSolution::solve_time_ms, "[ms]")
      .def_readonly("warning", &ControlSolution::warning, "why the target was not reached ('' if it was)")
      .def_readonly("target", &ControlSolution::target, "[x, y, z, roll, pitch, yaw]")
      .def_readonly("controls", &ControlSolution::controls, "all controls at the end")
      .def_readonly("end_effector", &ControlSolution::end_effector, "pose assembled at `controls`")
      .def("__repr__", [](const ControlSolution& r) {
        return std::string("<ccma.ControlResult converged=") + (r.converged ? "True" : "False") +
               " steps=" + std::to_string(r.steps) + " error=" + FormatG(r.error) +
               " residual_energy=" + FormatG(r.residual_energy) + ">";
      });
  py::class_<TrajectorySolution>(m, "TrajectoryResult",
                                 "A followed path (ControlProblem.follow): arrays with one row per step.")
      .def_readonly("converged", &TrajectorySolution::converged, "every waypoint reached")
      .def_readonly("steps", &TrajectorySolution::steps)
      .def_readonly("iterations", &TrajectorySolution::iterations)
      .def_readonly("max_residual_energy", &TrajectorySolution::max_residual_energy, "[m^2]")
      .def_readonly("max_error", &TrajectorySolution::max_error, "[m, rad]")
      .def_readonly("solve_time_ms", &TrajectorySolution::solve_time_ms, "[ms]")
      .def_readonly("warning", &TrajectorySolution::warning)
      .def_readonly("time", &TrajectorySolution::time, "(steps,) [s]")
      .def_readonly("targets", &TrajectorySolution::targets, "(steps x 6) x y z [m] roll pitch yaw [rad]")
      .def_readonly("reached", &TrajectorySolution::reached, "(steps x 6) end-effector after each step")
      .def_readonly("controls", &TrajectorySolution::controls, "(steps x num_controls)")
      .def_readonly("residual_energy", &TrajectorySolution::residual_energy, "(steps,) [m^2]")
      .def_readonly("error", &TrajectorySolution::error, "(steps,) [m, rad]")
      .def_readonly("step_reached", &TrajectorySolution::step_reached, "(steps,) bool");
}

ControlSolution MoveTo(ControlProblem& p, const Eigen::VectorXd& values) {
  const UsageGuard guard(p);
  const PoseTarget target = TargetFrom(p, values);
  ControlSolution s;
  static_cast<ControlResult&>(s) = p.MoveTo(target);
  s.target = AsVector(target);
  s.controls = p.controls();
  s.end_effector = p.forward().end_effector();
  return s;
}

TrajectorySolution Follow(ControlProblem& p, const std::vector<Waypoint>& waypoints) {
  CheckWaypoints(waypoints);
  const UsageGuard guard(p);
  std::vector<TrajectoryStep> steps;
  TrajectorySolution s;
  static_cast<TrajectoryResult&>(s) =
      FollowWaypoints(p, waypoints, [&](const TrajectoryStep& step) { steps.push_back(step); });
  const int n = static_cast<int>(steps.size());
  s.time.resize(n);
  s.targets.resize(n, 6);
  s.reached.resize(n, 6);
  s.controls.resize(n, p.forward().model().num_controls());
  s.residual_energy.resize(n);
  s.error.resize(n);
  s.step_reached.resize(n);
  for (int i = 0; i < n; ++i) {
    s.time[i] = steps[i].time;
    s.targets.row(i) = AsVector(steps[i].target).transpose();
    s.reached.row(i) << steps[i].reached.position.transpose(), steps[i].reached.rpy.transpose();
    s.controls.row(i) = steps[i].controls.transpose();
    s.residual_energy[i] = steps[i].result.residual_energy;
    s.error[i] = steps[i].result.error;
    s.step_reached[i] = steps[i].result.reached;
  }
  return s;
}

using ProblemClass = py::class_<ControlProblem>;

// The target forms every method below accepts (TargetFrom).
constexpr const char* kTargetForms =
    "target: [x, y, z, roll, pitch, yaw] ([m], [rad]), or only the model's controlled components in that "
    "order (as `ccma control --target`; the others are ignored); ValueError on another length";

// Setting the controls, one step, a whole move and a path.
void BindSolves(ProblemClass& c) {
  c.def(py::init<const Model&, const ControlOptions&>(), py::arg("model"), py::arg("options") = ControlOptions(),
        py::keep_alive<1, 2>())
      .def(
          "set_controls",
          [](ControlProblem& p, const Eigen::VectorXd& u) {
            const UsageGuard guard(p);
            ForwardSolution s;
            static_cast<ForwardResult&>(s) = p.SetControls(u);
            s.end_effector = p.forward().end_effector();
            s.controls = p.controls();
            return s;
          },
          py::arg("u"), py::call_guard<py::gil_scoped_release>(),
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
      .def("move_to", &MoveTo, py::arg("target"), py::call_guard<py::gil_scoped_release>(),
           (std::string("Walks the end-effector to the target in steps of at most max_step_m and max_step_rad. ") +
            kTargetForms)
               .c_str())
      .def("follow", &Follow, py::arg("waypoints"), py::call_guard<py::gil_scoped_release>(),
           "Follows a list of ccma.Waypoint (e.g. ccma.load_waypoints(path)); stops at the first "
           "waypoint it cannot reach. ValueError (naming the waypoint) on a value the waypoint CSV refuses: "
           "a time not finite, beyond 1e6 s or smaller than the one before, a position or angle not finite "
           "or beyond 1e4, more than 1e6 waypoints.")
      .def(
          "follow",
          [](ControlProblem& p, const Eigen::Ref<const RowMatrix>& a) {
            const std::vector<Waypoint> w = WaypointsFromArray(a);
            py::gil_scoped_release release;
            return Follow(p, w);
          },
          py::arg("waypoints"), "The same for an (N x 7) array of rows [time, x, y, z, roll, pitch, yaw].");
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

void BindProblem(py::module_& m) {
  ProblemClass c(m, "ControlProblem",
                 "Kinematic control: controls u whose assembly puts the end-effector at a target "
                 "(min 1/2 |e|^2 + lambda E, gradients from implicit sensitivities). Keeps the model alive. "
                 "One thread at a time: a call while another thread is inside one raises RuntimeError.");
  BindSolves(c);
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
  BindOptions(m);
  BindResults(m);
  BindWaypoints(m);
  BindProblem(m);
}

}  // namespace ccma::python
