// Statics (analyses/statics.h, `ccma statics`) in Python: joint reactions and
// control efforts at a problem's current configuration.
#include <optional>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "ccma/ccma.h"
#include "documents/statics_document.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "python/src/json_to_python.h"
#include "python/src/usage_guard.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

// `ccma statics` at the problem's configuration: a ccma.StaticsResult.
py::object Statics(const ForwardProblem& p, const std::optional<Eigen::VectorXd>& wrench, const BasePoseNoise& noise) {
  const ExternalWrench w = WrenchFrom(wrench, "statics");
  nlohmann::json document;
  {
    const UsageGuard guard(p);
    py::gil_scoped_release release;
    try {
      const double energy = p.Energy();
      document = documents::StaticsDocument(p.model(), p.state(), p.controls(),
                                            energy < p.options().assembly_tolerance, energy, w, noise)
                     .json;
    } catch (const std::invalid_argument& e) {
      throw py::value_error(std::string("statics: ") + e.what());
    }
  }
  return MakeResult("StaticsResult", document);
}

BasePoseNoise Noise(double position_sigma, double heading_sigma) {
  if (!(position_sigma >= 0 && position_sigma <= 1) || !(heading_sigma >= 0 && heading_sigma <= 1)) {
    throw py::value_error("statics: mocap_noise_m and mocap_noise_rad must lie in [0, 1] (m, rad)");
  }
  return {position_sigma, heading_sigma};
}

}  // namespace

void BindStatics(py::module_& m) {
  m.def(
      "statics",
      [](const ForwardProblem& p, const std::optional<Eigen::VectorXd>& wrench, double m, double rad) {
        return Statics(p, wrench, Noise(m, rad));
      },
      py::arg("problem"), py::arg("wrench") = py::none(), py::arg("mocap_noise_m") = 0.001,
      py::arg("mocap_noise_rad") = 0.003,
      "`ccma statics`: static equilibrium at the problem's current configuration (docs/statics.md). Returns a "
      "ccma.StaticsResult, the command's JSON as attributes (to_dict()): joints (name, point [m], force [N], "
      "moment [N*m] that between[0] exerts on between[1], world frame, moment about point), actuators (name, "
      "kind, effort [N or N*m] per control), determinate, balanced, unbalanced_load, ee_covariance (6 x 6 "
      "[m^2, m rad, rad^2], from the bases' pose noise mocap_noise_m [m], mocap_noise_rad [rad]), within_limits, "
      "limiting and payload_capacity when the model gives limits, compliant_reactions, deflection, "
      "ee_compliance, ee_stiffness (ee_stiffness_note), controlled_stiffness (controlled_stiffness_note), most_compliant when it has stiffness keys (compliance), "
      "assembled, residual_energy, bodies, clearance, warning. wrench: fx, fy, fz [N] at the end-effector point, mx, my, mz [N*m], world frame.");
  m.def(
      "statics",
      [](const ControlProblem& p, const std::optional<Eigen::VectorXd>& wrench, double m, double rad) {
        return Statics(p.forward(), wrench, Noise(m, rad));
      },
      py::arg("problem"), py::arg("wrench") = py::none(), py::arg("mocap_noise_m") = 0.001,
      py::arg("mocap_noise_rad") = 0.003, "The same for a ControlProblem.");
}

}  // namespace ccma::python
