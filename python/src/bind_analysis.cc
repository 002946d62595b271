// Mobility analysis (`ccma check`): ccma.check(model), the command's analysis
// at home, and ccma.analyze_mobility(model, state, controls) at any
// configuration.
#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "analyses/mobility.h"
#include "documents/check_document.h"
#include "python/src/bindings.h"
#include "python/src/json_to_python.h"
#include "python/src/pose_types.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

// A free motion with its bodies named, as `ccma check` names them.
struct NamedFreeMotion {
  Eigen::VectorXd direction;
  std::vector<std::string> bodies;
  std::vector<std::string> joints;
};

struct MobilitySolution : MobilityReport {
  std::vector<NamedFreeMotion> named_free_motions;
};

MobilitySolution Named(const Model& model, const MobilityReport& r) {
  MobilitySolution s;
  static_cast<MobilityReport&>(s) = r;
  for (const FreeMotion& motion : r.free_motions) {
    NamedFreeMotion named{motion.direction, {}, {}};
    for (const int b : motion.bodies) named.bodies.push_back(model.bodies[b].name);
    for (const int j : motion.joints) named.joints.push_back(model.joints[j].name);
    s.named_free_motions.push_back(named);
  }
  return s;
}

void BindReport(py::module_& m) {
  py::class_<NamedFreeMotion>(m, "FreeMotion", "One free motion with the controls fixed (analyses/mobility.h).")
      .def_readonly("direction", &NamedFreeMotion::direction,
                    "ds (state_size): 6 per body, rotation increment [rad] then translation [m], unit norm")
      .def_readonly("bodies", &NamedFreeMotion::bodies,
                    "names of the bodies it moves, in model order (as `ccma check`'s free_motions)")
      .def_readonly("joints", &NamedFreeMotion::joints,
                    "names of the revolute and prismatic joints whose coordinate it changes, in model order "
                    "(as `ccma check`'s free_motions)");
  py::class_<MobilitySolution>(m, "MobilityReport",
                               "Numerical mobility at a configuration (analyses/mobility.h); the names are "
                               "`ccma check`'s.")
      .def_readonly("constraints", &MobilitySolution::constraint_rows, "rows of C")
      .def_readonly("constraint_rank", &MobilitySolution::constraint_rank, "rank of dC/ds")
      .def_readonly("dof_with_controls_fixed", &MobilitySolution::dof_with_controls_fixed)
      .def_readonly("rigid_with_controls_fixed", &MobilitySolution::rigid_with_controls_fixed)
      .def_readonly("dof_with_controls_free", &MobilitySolution::dof_with_controls_free)
      .def_readonly("end_effector_dof", &MobilitySolution::end_effector_dof)
      .def_readonly("end_effector_dof_nonholonomic", &MobilitySolution::end_effector_dof_nonholonomic)
      .def_readonly("smallest_singular_value", &MobilitySolution::smallest_singular_value, "of dC/ds")
      .def_readonly("residual_energy", &MobilitySolution::energy, "E at the configuration [m^2]")
      .def_readonly("free_motions", &MobilitySolution::named_free_motions,
                    "a basis of the free motions with the controls fixed, each naming few bodies (empty when rigid)")
      .def_readonly("free_motions_listed", &MobilitySolution::free_motions_listed,
                    "False when free motions exist but were too many to list (then free_motions is empty)");
}

}  // namespace

void BindAnalysis(py::module_& m) {
  BindReport(m);
  m.def(
      "analyze_mobility",
      [](const Model& model, std::optional<StateArray> state, std::optional<Eigen::VectorXd> controls,
         double rank_tolerance) {
        const State s = state ? StateFromArray(model, *state) : State::Home(model);
        const Eigen::VectorXd u = controls ? *controls : model.home_controls();
        CheckControls(model, u);
        MobilityReport r;
        {
          py::gil_scoped_release release;
          r = AnalyzeMobility(model, s, u, rank_tolerance);
        }
        return Named(model, r);
      },
      py::arg("model"), py::arg("state") = py::none(), py::arg("controls") = py::none(),
      py::arg("rank_tolerance") = 1e-8,
      "Ranks of dC/ds and of the end-effector motions at a state ((num_bodies x 7), rows [qw, qx, qy, "
      "qz, px, py, pz] as ForwardProblem.state; default home) and controls (default home); dense SVDs, "
      "for analysis. At home, ccma.check(model) gives the whole of `ccma check`.");
  m.def(
      "check",
      [](const Model& model) {
        nlohmann::json document;
        {
          py::gil_scoped_release release;
          document = documents::CheckDocument(model).json;
        }
        return MakeResult("CheckResult", document);
      },
      py::arg("model"),
      "`ccma check`: the model's counts and its mobility at home, as a ccma.CheckResult (the command's JSON as "
      "attributes; to_dict() is that JSON): bodies, joints, controls, constraints, constraint_rank, "
      "rigid_with_controls_fixed, end_effector_dof, free_motions, warnings, clearance, ...");
}

}  // namespace ccma::python
