// Mobility analysis (`ccma check`): ccma.analyze_mobility(model).
#include <optional>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "analyses/mobility.h"
#include "python/src/bindings.h"
#include "python/src/pose_types.h"

namespace py = pybind11;

namespace ccma::python {

void BindAnalysis(py::module_& m) {
  py::class_<FreeMotion>(m, "FreeMotion", "One free motion with the controls fixed (analyses/mobility.h).")
      .def_readonly("direction", &FreeMotion::direction,
                    "ds (state_size): 6 per body, rotation increment [rad] then translation [m], unit norm")
      .def_readonly("bodies", &FreeMotion::bodies, "indices into model.bodies of the bodies it moves, ascending")
      .def_readonly("joints", &FreeMotion::joints,
                    "indices into model.joints of the revolute and prismatic joints whose coordinate it changes, "
                    "ascending");
  py::class_<MobilityReport>(m, "MobilityReport", "Numerical mobility at a configuration (analyses/mobility.h).")
      .def_readonly("constraint_rows", &MobilityReport::constraint_rows)
      .def_readonly("constraint_rank", &MobilityReport::constraint_rank)
      .def_readonly("dof_with_controls_fixed", &MobilityReport::dof_with_controls_fixed)
      .def_readonly("rigid_with_controls_fixed", &MobilityReport::rigid_with_controls_fixed)
      .def_readonly("dof_with_controls_free", &MobilityReport::dof_with_controls_free)
      .def_readonly("end_effector_dof", &MobilityReport::end_effector_dof)
      .def_readonly("end_effector_dof_nonholonomic", &MobilityReport::end_effector_dof_nonholonomic)
      .def_readonly("smallest_singular_value", &MobilityReport::smallest_singular_value, "of dC/ds")
      .def_readonly("energy", &MobilityReport::energy, "E [m^2]")
      .def_readonly("free_motions", &MobilityReport::free_motions,
                    "a basis of the free motions with the controls fixed, each naming few bodies (empty when rigid)")
      .def_readonly("free_motions_listed", &MobilityReport::free_motions_listed,
                    "False when free motions exist but were too many to list (then free_motions is empty)");
  m.def(
      "analyze_mobility",
      [](const Model& model, std::optional<StateArray> state, std::optional<Eigen::VectorXd> controls,
         double rank_tolerance) {
        const State s = state ? StateFromArray(model, *state) : State::Home(model);
        const Eigen::VectorXd u = controls ? *controls : model.home_controls();
        CheckControls(model, u);
        py::gil_scoped_release release;
        return AnalyzeMobility(model, s, u, rank_tolerance);
      },
      py::arg("model"), py::arg("state") = py::none(), py::arg("controls") = py::none(),
      py::arg("rank_tolerance") = 1e-8,
      "Ranks of dC/ds and of the end-effector motions at a state ((num_bodies x 7), rows [qw, qx, qy, "
      "qz, px, py, pz] as ForwardProblem.state; default home) and controls (default home); dense SVDs, "
      "for analysis.");
}

}  // namespace ccma::python
