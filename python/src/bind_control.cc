// Kinematic control: ccma.ControlProblem(model).move_to([x, y, z, r, p, y]),
// one step, path following (waypoints) and the sensitivities ds/du, dX/du.
#include <filesystem>

#include <pybind11/eigen.h>
#include <pybind11/stl/filesystem.h>
#include <pybind11/stl.h>

#include "ccma/end_effector.h"
#include "ccma/internal/format.h"
#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "problems/trajectory.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "python/src/pose_types.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

PoseTarget TargetFrom(const Vector6d& t) {
  PoseTarget target;
  target.position = t.head<3>();
  target.rpy = t.tail<3>();
  return target;
}

Vector6d AsVector(const PoseTarget& t) {
  Vector6d v;
  v << t.position, t.rpy;
  return v;
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

ControlOptions MakeControlOptions(py::kwargs kwargs) { return WithKeywords(ControlOptions(), kwargs); }

void BindOptions(py::module_& m) {
  py::class_<ControlOptions>(m, "ControlOptions",
                             "Options of the control solve (problems/control_problem.h); every field "
                             "is a keyword of the constructor, e.g. ControlOptions(method='bfgs').")
      .def(py::init(&MakeControlOptions))
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
      .def_readwrite("forward", &ControlOptions::forward, "ForwardOptions of the inner solves")
      // ControlOptions::Secondary, flattened (redundancy resolution in the
      // null space of the end-effector task).
      .def_property(
          "singularity_weight", [](const ControlOptions& o) { return o.secondary.singularity_weight; },
          [](ControlOptions& o, double v) { o.secondary.singularity_weight = v; }, "singularity barrier weight (0 = off) [1]")
      .def_property(
          "singularity_threshold", [](const ControlOptions& o) { return o.secondary.singularity_threshold; },
          [](ControlOptions& o, double v) { o.secondary.singularity_threshold = v; }, "sigma_0: smallest singular value of dX/du below which the barrier acts [m or rad per control unit]")
      .def_property(
          "pivot_weight", [](const ControlOptions& o) { return o.secondary.pivot_weight; },
          [](ControlOptions& o, double v) { o.secondary.pivot_weight = v; }, "pivot-ratio barrier weight on dG/ds (0 = off) [1]")
      .def_property(
          "pivot_threshold", [](const ControlOptions& o) { return o.secondary.pivot_threshold; },
          [](ControlOptions& o, double v) { o.secondary.pivot_threshold = v; }, "rho_0: pivot ratio of dG/ds below which that barrier acts [1]")
      .def_property(
          "spread_weight", [](const ControlOptions& o) { return o.secondary.spread_weight; },
          [](ControlOptions& o, double v) { o.secondary.spread_weight = v; }, "base-spread weight (0 = off) [1/m^2]")
      .def_property(
          "clearance_m", [](const ControlOptions& o) { return o.secondary.clearance_m; },
          [](ControlOptions& o, double v) { o.secondary.clearance_m = v; }, "base-to-base distance below which bases are pushed apart [m]")
      .def_property(
          "travel_weight", [](const ControlOptions& o) { return o.secondary.travel_weight; },
          [](ControlOptions& o, double v) { o.secondary.travel_weight = v; }, "base-travel weight (0 = off) [1/m^2]")
      .def("is_valid", [](const ControlOptions& o) {
        std::string why;
        const bool ok = o.IsValid(&why);
        return py::make_tuple(ok, why);
      }, "(ok, why): whether every field is in range");
}

void BindResults(py::module_& m) {
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
      .def_readonly("max_lateral_displacement", &ControlStepResult::max_lateral_displacement, "[m]")
      .def_readonly("limited_by", &ControlStepResult::limited_by)
      .def_readonly("time_ms", &ControlStepResult::time_ms, "[ms]");
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

ControlSolution MoveTo(ControlProblem& p, const Vector6d& target) {
  ControlSolution s;
  static_cast<ControlResult&>(s) = p.MoveTo(TargetFrom(target));
  s.target = target;
  s.controls = p.controls();
  s.end_effector = p.forward().end_effector();
  return s;
}

TrajectorySolution Follow(ControlProblem& p, const std::vector<Waypoint>& waypoints) {
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

void BindProblem(py::module_& m) {
  py::class_<ControlProblem>(
      m, "ControlProblem",
      "Kinematic control: controls u whose assembly puts the end-effector at a target "
      "(min 1/2 |e|^2 + lambda E, gradients from implicit sensitivities). Keeps the model alive. "
      "Not for use by two threads at once.")
      .def(py::init<const Model&, const ControlOptions&>(), py::arg("model"),
           py::arg("options") = ControlOptions(), py::keep_alive<1, 2>())
      .def(
          "set_controls",
          [](ControlProblem& p, const Eigen::VectorXd& u) {
            ForwardSolution s;
            static_cast<ForwardResult&>(s) = p.SetControls(u);
            s.end_effector = p.forward().end_effector();
            s.controls = p.controls();
            return s;
          },
          py::arg("u"), py::call_guard<py::gil_scoped_release>(),
          "Assembles the mechanism at u (following the branch) and starts from there.")
      .def(
          "step", [](ControlProblem& p, const Vector6d& t) { return p.SolveStep(TargetFrom(t)); }, py::arg("target"),
          py::call_guard<py::gil_scoped_release>(),
          "One solve toward target [x, y, z, roll, pitch, yaw] ([m], [rad]) without path "
          "splitting (for small moves).")
      .def("move_to", &MoveTo, py::arg("target"), py::call_guard<py::gil_scoped_release>(),
           "Walks the end-effector to target [x, y, z, roll, pitch, yaw] ([m], [rad]) in steps of "
           "at most max_step_m and max_step_rad (components not controlled are ignored).")
      .def("follow", &Follow, py::arg("waypoints"), py::call_guard<py::gil_scoped_release>(),
           "Follows a list of ccma.Waypoint (e.g. ccma.load_waypoints(path)); stops at the first "
           "waypoint it cannot reach.")
      .def(
          "follow",
          [](ControlProblem& p, const Eigen::Ref<const RowMatrix>& a) {
            const std::vector<Waypoint> w = WaypointsFromArray(a);
            py::gil_scoped_release release;
            return Follow(p, w);
          },
          py::arg("waypoints"), "The same for an (N x 7) array of rows [time, x, y, z, roll, pitch, yaw].")
      .def(
          "objective",
          [](ControlProblem& p, const Vector6d& t) {
            Eigen::VectorXd g;
            double o = 0;
            {
              py::gil_scoped_release release;
              o = p.Objective(TargetFrom(t), &g);
            }
            return py::make_tuple(o, g);
          },
          py::arg("target"), "(O, dO/du_eff) at the current controls (effective controls only).")
      .def("state_sensitivity", &ControlProblem::StateSensitivity, py::call_guard<py::gil_scoped_release>(),
           "ds/du: (state_size x effective controls) at the current solution (m or rad per control unit)")
      .def(
          "end_effector_jacobian",
          [](ControlProblem& p) -> Eigen::MatrixXd {
            const Eigen::MatrixXd ds_du = p.StateSensitivity();
            return EndEffectorJacobian(p.forward().model(), p.forward().state()) * ds_du;
          },
          py::call_guard<py::gil_scoped_release>(),
          "dX_EE/du: (6 x effective controls), rows x y z [m] then rotation increment [rad]")
      .def_property_readonly(
          "controls", [](const ControlProblem& p) -> Eigen::VectorXd { return p.controls(); },
          "current controls (a copy)")
      .def_property_readonly("effective_controls", &ControlProblem::effective_controls,
                             "indices into controls that the solver changes")
      .def_property_readonly(
          "forward", [](ControlProblem& p) -> ForwardProblem& { return p.forward(); },
          py::return_value_policy::reference_internal, "the inner ForwardProblem (state, body poses)")
      .def_property_readonly(
          "current_pose", [](const ControlProblem& p) { return AsVector(p.CurrentPose()); },
          "[x, y, z, roll, pitch, yaw] of the end-effector now");
}

void BindWaypoints(py::module_& m) {
  py::register_exception<WaypointError>(m, "WaypointError", PyExc_ValueError);
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
