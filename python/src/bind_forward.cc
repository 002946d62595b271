// The forward problem: ccma.ForwardProblem(model).solve(u) / .assemble(u).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "documents/json_values.h"
#include "ccma/end_effector.h"
#include "ccma/internal/format.h"
#include "ccma/joint_coordinates.h"
#include "problems/forward_problem.h"
#include "problems/loaded_equilibrium.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "python/src/json_to_python.h"
#include "python/src/pose_types.h"
#include "python/src/usage_guard.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

void BindPoses(py::module_& m) {
  py::class_<EndEffectorPose>(m, "EndEffectorPose", "The end-effector pose X_EE.")
      .def_readonly("position", &EndEffectorPose::position, "p_WE: the controlled point in world [m]")
      .def_readonly("rotation", &EndEffectorPose::rotation,
                    "R_EE = R_WB(now) R_WB(home)^T, world axes (3x3)")
      .def_readonly("rpy", &EndEffectorPose::rpy, "rotation as [roll, pitch, yaw] [rad]")
      .def("__repr__", [](const EndEffectorPose& p) {
        return "<ccma.EndEffectorPose position=[" + FormatG(p.position.x()) + ", " + FormatG(p.position.y()) +
               ", " + FormatG(p.position.z()) + "] rpy=[" + FormatG(p.rpy.x()) + ", " + FormatG(p.rpy.y()) + ", " +
               FormatG(p.rpy.z()) + "]>";
      });
  py::class_<BodyPose>(m, "BodyPose", "One body's absolute pose.")
      .def_readonly("name", &BodyPose::name)
      .def_readonly("position", &BodyPose::position, "p_WB [m]")
      .def_readonly("rotation", &BodyPose::rotation, "R_WB (3x3)")
      .def_readonly("quaternion", &BodyPose::quaternion, "R_WB as [w, x, y, z]")
      .def_readonly("rpy", &BodyPose::rpy, "R_WB as [roll, pitch, yaw] [rad]");
  py::class_<JointCoordinateReport>(m, "JointCoordinate", "q of a revolute [rad] or prismatic [m] joint.")
      .def_readonly("joint", &JointCoordinateReport::joint, "index into Model.joints")
      .def_readonly("q", &JointCoordinateReport::q, "rad or m, 0 at home")
      .def_readonly("within_limits", &JointCoordinateReport::within_limits);
}

void BindForwardOptions(py::module_& m) {
  py::class_<ForwardOptions>(m, "ForwardOptions",
                             "Options of the forward solve (problems/forward_problem.h); every "
                             "field is a keyword of the constructor.")
      .def(py::init([](py::kwargs kwargs) {
             ForwardOptions o;
             return WithKeywords(o, kwargs);
           }))
      .def_property(
          "solver",
          [](const ForwardOptions& o) { return o.solver == ForwardSolver::kNative ? "native" : "ceres"; },
          [](ForwardOptions& o, const std::string& v) {
            if (v != "native" && v != "ceres") throw py::value_error("solver: 'native' or 'ceres'");
            o.solver = v == "native" ? ForwardSolver::kNative : ForwardSolver::kCeres;
          },
          "'native' (ccma's sparse Levenberg-Marquardt, default) or 'ceres' (ceres::Solve, the reference)")
      .def_readwrite("secant_predictor", &ForwardOptions::secant_predictor,
                     "start each solve from the secant prediction along a path (default True)")
      .def_readwrite("rigid_motion_predictor", &ForwardOptions::rigid_motion_predictor,
                     "when every base moves by one planar rigid motion (and no joint ends at the ground), "
                     "move every body by it: the solve ends without an iteration (default True)")
      .def_readwrite("assembly_tolerance", &ForwardOptions::assembly_tolerance,
                     "E [m^2] below which the mechanism counts as assembled")
      .def_readwrite("max_iterations", &ForwardOptions::max_iterations, "per solve (per sub-step)")
      .def_readwrite("max_control_step", &ForwardOptions::max_control_step,
                     "assemble(): largest control change per sub-step [m, rad]")
      .def_readwrite("max_newton_polish_steps", &ForwardOptions::max_newton_polish_steps)
      .def_readwrite("branch_jump_relative", &ForwardOptions::branch_jump_relative)
      .def_readwrite("branch_jump_absolute", &ForwardOptions::branch_jump_absolute, "[m, rad]")
      .def("is_valid", [](const ForwardOptions& o) {
        std::string why;
        const bool ok = o.IsValid(&why);
        return py::make_tuple(ok, why);
      }, "(ok, why): whether every field is in range");
}

// The attributes `ccma simulate`'s JSON has beyond the solve's own numbers
// (documents.h SimulateDocument), computed when asked for.
void BindResultConfiguration(py::class_<ForwardSolution>& c) {
  c.def_property_readonly("model", [](const ForwardSolution& r) { return r.model->name; }, "the model's name")
      .def_readonly("assembly_tolerance", &ForwardSolution::assembly_tolerance,
                    "E [m^2] below which the mechanism counts as assembled")
      .def_readonly("start", &ForwardSolution::start,
                    "'home' (the solve started from the home configuration) or 'current' (from the problem's "
                    "configuration before the call)")
      .def_property_readonly(
          "bodies",
          [](const ForwardSolution& r) {
            std::vector<BodyPose> poses;
            for (int b = 0; b < r.model->num_bodies(); ++b) poses.push_back(PoseOfBody(*r.model, r.state, b));
            return poses;
          },
          "every body's absolute pose after the solve (BodyPose: name, position [m], rpy [rad], quaternion)")
      .def_property_readonly(
          "joints", [](const ForwardSolution& r) { return ToView(documents::JointsToJson(*r.model, r.state)); },
          "list of Record {name, type, q [rad or m], actuated, limits?}: every revolute and prismatic joint")
      .def_property_readonly(
          "limits_violated", [](const ForwardSolution& r) { return LimitsViolated(*r.model, r.state); },
          "names of the joints outside their limits")
      .def_property_readonly(
          "clearance", [](const ForwardSolution& r) { return ToView(documents::ClearanceToJson(*r.model, r.state)); },
          "Record {min [m], pair, margin [m], below_margin}; None without collision geometry")
      .def_property_readonly(
          "deflection",
          [](const ForwardSolution& r) -> py::object {
            if (!r.loaded) return py::none();
            nlohmann::json out;
            documents::AddLoadedJson(*r.model, *r.loaded, &out);
            return ToView(out["deflection"]);
          },
          "assemble(loaded=True): Record {end_effector [dx, dy, dz [m], rx, ry, rz [rad]], max_body_m [m], held}: "
          "the loaded configuration against the rigid assembly; None otherwise")
      .def_property_readonly(
          "loaded",
          [](const ForwardSolution& r) -> py::object {
            if (!r.loaded) return py::none();
            nlohmann::json out;
            documents::AddLoadedJson(*r.model, *r.loaded, &out);
            return ToView(out["loaded"]);
          },
          "assemble(loaded=True): Record {converged, iterations, unbalanced_load [N or N*m], yields [m or rad per "
          "control]}; None otherwise")
      .def_property_readonly("warning", &documents::SimulateWarning,
                             "what went wrong: not assembled, not converged, a branch jump ('' when nothing)")
      .def(
          "to_dict", [](const ForwardSolution& r) { return ToPython(documents::SimulateDocument(r).json); },
          "The JSON document `ccma simulate` prints for the same solve (same keys and values).");
}

void BindResult(py::module_& m) {
  py::class_<ForwardSolution> c(m, "ForwardResult",
                                "The outcome of ForwardProblem.solve/assemble: the attributes of `ccma simulate`'s "
                                "JSON (to_dict() is that JSON), and the solver's details.");
  c.def_readonly("converged", &ForwardSolution::converged, "dE/ds ~ 0")
      .def_readonly("assembled", &ForwardSolution::assembled, "E below the assembly tolerance")
      .def_readonly("residual_energy", &ForwardSolution::residual_energy, "E [m^2]")
      .def_readonly("iterations", &ForwardSolution::iterations)
      .def_readonly("substeps", &ForwardSolution::substeps)
      .def_readonly("newton_steps", &ForwardSolution::newton_steps)
      .def_readonly("gradient_norm", &ForwardSolution::gradient_norm, "max |dE/ds|")
      .def_readonly("gradient_norm_is_bound", &ForwardSolution::gradient_norm_is_bound,
                    "gradient_norm is the upper bound 2 |J|_F |C| (a rigid move checked on residuals only)")
      .def_readonly("solve_time_ms", &ForwardSolution::solve_time_ms, "[ms]")
      .def_readonly("branch_jump", &ForwardSolution::branch_jump, "assemble(): left the branch")
      .def_readonly("branch_jump_size", &ForwardSolution::branch_jump_size, "[m or rad]")
      .def_readonly("branch_jump_substep", &ForwardSolution::branch_jump_substep)
      .def_readonly("message", &ForwardSolution::message)
      .def_readonly("end_effector", &ForwardSolution::end_effector, "pose after the solve")
      .def_readonly("controls", &ForwardSolution::controls, "the controls solved at")
      .def("__repr__", [](const ForwardSolution& r) {
        return std::string("<ccma.ForwardResult assembled=") + (r.assembled ? "True" : "False") +
               " residual_energy=" + FormatG(r.residual_energy) + " iterations=" + std::to_string(r.iterations) +
               ">";
      });
  BindResultConfiguration(c);
}

// The solve `solve` (Solve or Assemble) at u, as a ForwardSolution.
template <typename Solve>
ForwardSolution Solved(ForwardProblem& p, Solve solve) {
  const UsageGuard guard(p);
  const bool at_home = AtHome(p);
  const ForwardResult r = solve(p);
  return MakeForwardSolution(p, r, at_home ? "home" : "current");
}

// assemble(u, loaded, wrench): `ccma simulate [--loaded]`.
ForwardSolution AssembleLoaded(ForwardProblem& p, const Eigen::VectorXd& u, bool loaded,
                               const std::optional<Eigen::VectorXd>& wrench) {
  if (wrench && !loaded) throw py::value_error("assemble: wrench only with loaded=True (the loads of the loaded equilibrium)");
  const ExternalWrench w = WrenchFrom(wrench, "assemble");
  ForwardSolution s = Solved(p, [&u](ForwardProblem& q) { return q.Assemble(u); });
  if (!loaded || !s.assembled) return s;
  try {
    s.loaded = SolveLoadedEquilibrium(p.model(), p.state(), p.controls(), w);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("assemble: ") + e.what());
  }
  s.state = s.loaded->state;
  s.end_effector = ComputeEndEffectorPose(p.model(), s.state);
  return s;
}

using ForwardClass = py::class_<ForwardProblem>;

// solve, assemble and going home.
void BindForwardSolves(ForwardClass& c) {
  c.def(py::init<const Model&, const ForwardOptions&>(), py::arg("model"), py::arg("options") = ForwardOptions(),
        py::keep_alive<1, 2>())
      .def(
          "solve",
          [](ForwardProblem& p, const Eigen::VectorXd& u) {
            return Solved(p, [&u](ForwardProblem& q) { return q.Solve(u); });
          },
          py::arg("u"), py::call_guard<py::gil_scoped_release>(), py::keep_alive<0, 1>(),
          "One warm-started solve at controls u (3 per base: x [m], y [m], theta [rad]; then the "
          "actuated joints [rad or m]). Raises ValueError on a wrong size or a non-finite entry.")
      .def("assemble", &AssembleLoaded, py::arg("u"), py::arg("loaded") = false, py::arg("wrench") = py::none(),
           py::call_guard<py::gil_scoped_release>(), py::keep_alive<0, 1>(),
           "Moves the controls to u in small sub-steps, following the assembly branch (what "
           "`ccma simulate` does); reports a branch jump. loaded=True (`ccma simulate --loaded`): the result is "
           "the nonlinear loaded equilibrium of a model with stiffness keys under gravity, the payload and "
           "wrench [fx, fy, fz [N], mx, my, mz [N*m]] (state, end_effector, bodies, deflection, loaded); the "
           "problem itself stays at the rigid assembly.")
      .def(
          "reset_to_home",
          [](ForwardProblem& p) {
            const UsageGuard guard(p);
            p.ResetToHome();
          },
          "home state and home controls (no solve)");
}

// The state and controls as arrays, the end-effector and E.
void BindState(ForwardClass& c) {
  c.def_property_readonly("state", [](const ForwardProblem& p) {
                            const UsageGuard guard(p);
                            return StateToArray(p.state());
                          },
                          "(num_bodies x 7) array, rows [qw, qx, qy, qz, px, py, pz]: the unit quaternion "
                          "of R_WB, scalar first, then p_WB [m] (a copy)")
      .def(
          "set_state",
          [](ForwardProblem& p, const Eigen::Ref<const StateArray>& a) {
            const UsageGuard guard(p);
            p.SetState(StateFromArray(p.model(), a));
          },
          py::arg("state"), "Replaces the state ((num_bodies x 7), as .state) without solving.")
      .def_property_readonly(
          "controls",
          [](const ForwardProblem& p) -> Eigen::VectorXd {
            const UsageGuard guard(p);
            return p.controls();
          },
          "current controls (a copy)")
      .def_property_readonly("end_effector",
                             [](const ForwardProblem& p) {
                               const UsageGuard guard(p);
                               return p.end_effector();
                             })
      .def(
          "energy",
          [](const ForwardProblem& p) {
            const UsageGuard guard(p);
            return p.Energy();
          },
          "E at the current state and controls [m^2]");
}

// Per-body poses, joint coordinates and dX/ds at the current state.
void BindQueries(ForwardClass& c) {
  c.def(
       "body_pose",
       [](const ForwardProblem& p, int body) {
         const UsageGuard guard(p);
         if (body < 0 || body >= p.model().num_bodies()) throw py::index_error("body index out of range");
         return PoseOfBody(p.model(), p.state(), body);
       },
       py::arg("body"))
      .def(
          "body_pose",
          [](const ForwardProblem& p, const std::string& name) {
            const UsageGuard guard(p);
            const int body = p.model().FindBody(name);
            if (body < 0) throw py::key_error("no body named '" + name + "'");
            return PoseOfBody(p.model(), p.state(), body);
          },
          py::arg("name"))
      .def(
          "body_poses",
          [](const ForwardProblem& p) {
            const UsageGuard guard(p);
            std::vector<BodyPose> poses;
            for (int b = 0; b < p.model().num_bodies(); ++b) poses.push_back(PoseOfBody(p.model(), p.state(), b));
            return poses;
          },
          "every body's absolute pose, in model order")
      .def(
          "joint_coordinates",
          [](const ForwardProblem& p) {
            const UsageGuard guard(p);
            return JointCoordinates(p.model(), p.state());
          },
          "q of every revolute and prismatic joint, in file order")
      .def(
          "limits_violated",
          [](const ForwardProblem& p) {
            const UsageGuard guard(p);
            return LimitsViolated(p.model(), p.state());
          },
          "names of the joints outside their limits")
      .def(
          "end_effector_state_jacobian",
          [](const ForwardProblem& p) {
            const UsageGuard guard(p);
            return EndEffectorJacobian(p.model(), p.state());
          },
          "dX_EE/ds (6 x state_size): rows position [m] then rotation increment [rad]");
}

void BindForwardProblem(py::module_& m) {
  ForwardClass c(m, "ForwardProblem",
                 "Simulation: s_hat(u) = argmin_s E(s, u), warm-started from the last state. Keeps the "
                 "model alive. One thread at a time: a call while another thread is inside one raises RuntimeError.");
  BindForwardSolves(c);
  BindState(c);
  BindQueries(c);
}

}  // namespace

void BindForward(py::module_& m) {
  BindPoses(m);
  BindForwardOptions(m);
  BindResult(m);
  BindForwardProblem(m);
}

}  // namespace ccma::python
