// Statics (analyses/statics.h, `ccma statics`) in Python: joint reactions and
// control efforts at a problem's current configuration.
#include <optional>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "ccma/ccma.h"
#include "python/src/bindings.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

py::dict Statics(const Model& model, const State& s, const Eigen::VectorXd& u,
                 const std::optional<Eigen::VectorXd>& wrench, const BasePoseNoise& noise) {
  ExternalWrench w;
  if (wrench) {
    if (wrench->size() != 6 || !wrench->allFinite() || wrench->cwiseAbs().maxCoeff() > 1e6) {
      throw py::value_error("statics: wrench must be 6 finite numbers fx,fy,fz [N], mx,my,mz [N*m], each in [-1e6, 1e6]");
    }
    w.force = wrench->head<3>();
    w.moment = wrench->tail<3>();
  }
  StaticsReport r;
  try {
    r = ComputeStatics(model, s, u, w);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  py::list joints, actuators;
  for (const JointReaction& j : r.joints) {
    py::dict d;
    d["name"] = j.name;
    d["point"] = Eigen::Vector3d(j.point);
    d["force"] = Eigen::Vector3d(j.force);
    d["moment"] = Eigen::Vector3d(j.moment);
    joints.append(d);
  }
  for (const ActuatorEffort& a : r.actuators) {
    py::dict d;
    d["name"] = a.name;
    d["kind"] = ActuatorKindName(a.kind);
    d["effort"] = a.effort;
    actuators.append(d);
  }
  py::dict out;
  out["joints"] = joints;
  out["actuators"] = actuators;
  out["determinate"] = r.determinate;
  out["balanced"] = r.balanced;
  out["unbalanced_load"] = r.residual;
  if (r.limits_given) {
    out["within_limits"] = r.within_limits;
    out["limiting"] = r.limiting;
    const PayloadCapacity capacity = ComputePayloadCapacity(model, s, u);
    if (Reportable(capacity)) {
      py::dict c;
      c["mass"] = ReportedMass(capacity);
      c["limiting"] = capacity.broken_unloaded.empty() ? capacity.limiting : capacity.broken_unloaded;
      if (!capacity.note.empty()) c["note"] = capacity.note;
      out["payload_capacity"] = c;
    }
  }
  const Eigen::Matrix<double, 6, 6> covariance = EndEffectorCovariance(model, s, u, noise);
  if (covariance.allFinite()) out["ee_covariance"] = Eigen::MatrixXd(covariance);
  return out;
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
        return Statics(p.model(), p.state(), p.controls(), wrench, Noise(m, rad));
      },
      py::arg("problem"), py::arg("wrench") = py::none(), py::arg("mocap_noise_m") = 0.001,
      py::arg("mocap_noise_rad") = 0.003,
      "Static equilibrium at the problem's current configuration (`ccma statics`, docs/statics.md): a dict "
      "with joints (name, point [m], force [N], moment [N*m] that between[0] exerts on between[1], world "
      "frame, moment about point), actuators (name, kind, effort [N or N*m] per control), determinate, "
      "balanced, unbalanced_load, ee_covariance (6 x 6 [m^2, m rad, rad^2], from the bases' pose noise "
      "mocap_noise_m [m], mocap_noise_rad [rad]), and within_limits, limiting when the model gives limits. "
      "wrench: fx, fy, fz [N] at the end-effector point, mx, my, mz [N*m], world frame.");
  m.def(
      "statics",
      [](const ControlProblem& p, const std::optional<Eigen::VectorXd>& wrench, double m, double rad) {
        return Statics(p.forward().model(), p.forward().state(), p.controls(), wrench, Noise(m, rad));
      },
      py::arg("problem"), py::arg("wrench") = py::none(), py::arg("mocap_noise_m") = 0.001,
      py::arg("mocap_noise_rad") = 0.003, "The same for a ControlProblem.");
}

}  // namespace ccma::python
