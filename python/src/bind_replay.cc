// The simulated closed loop (paper Section IV): ccma.replay(model, waypoints).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "execution/replay.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

using BoolVector = Eigen::Matrix<bool, Eigen::Dynamic, 1>;

// ReplayResult with its samples as arrays (one row per sample).
struct ReplaySolution {
  ReplayResult result;  // its samples moved into the arrays below
  Eigen::VectorXd time;
  RowMatrix commanded, tracked, set_controls, true_controls;
  Eigen::VectorXd residual_energy;
  BoolVector sample_torn, sample_assembled;
};

ReplaySolution Run(const Model& model, const std::vector<Waypoint>& waypoints, const ReplayOptions& options) {
  CheckWaypoints(waypoints);  // positions and angles too, with the messages of follow and plan
  std::string why;
  if (!IsValidReplay(waypoints, options, &why)) throw std::invalid_argument(why);
  ReplaySolution s;
  s.result = Replay(model, waypoints, options);
  const std::vector<ReplaySample>& samples = s.result.samples;
  const int n = static_cast<int>(samples.size());
  const int nc = model.num_controls();
  s.time.resize(n);
  s.commanded.resize(n, 6);
  s.tracked.resize(n, 6);
  s.set_controls.resize(n, nc);
  s.true_controls.resize(n, nc);
  s.residual_energy.resize(n);
  s.sample_torn.resize(n);
  s.sample_assembled.resize(n);
  for (int i = 0; i < n; ++i) {
    s.time[i] = samples[i].time;
    s.commanded.row(i) = samples[i].commanded.transpose();
    s.tracked.row(i) = samples[i].tracked.transpose();
    s.set_controls.row(i) = samples[i].set_controls.transpose();
    s.true_controls.row(i) = samples[i].true_controls.transpose();
    s.residual_energy[i] = samples[i].residual_energy;
    s.sample_torn[i] = samples[i].torn;
    s.sample_assembled[i] = samples[i].assembled;
  }
  s.result.samples.clear();
  return s;
}

void BindOptions(py::module_& m) {
  py::class_<ReplayOptions>(m, "ReplayOptions",
                            "Options of ccma.replay (execution/replay.h); every field is a keyword of the "
                            "constructor, e.g. ReplayOptions(noise='none', seed=3).")
      .def(py::init([](py::kwargs kwargs) { return WithKeywords(ReplayOptions(), kwargs); }))
      .def_property(
          "noise",
          [](const ReplayOptions& o) {
            const SimulationNoise none = SimulationNoise::None(), d;
            if (o.noise.position_sigma == none.position_sigma && o.noise.slip == none.slip &&
                o.noise.mocap_latency == none.mocap_latency && o.noise.command_latency == none.command_latency &&
                o.noise.heading_sigma == none.heading_sigma) {
              return "none";
            }
            if (o.noise.position_sigma == d.position_sigma && o.noise.slip == d.slip &&
                o.noise.mocap_latency == d.mocap_latency && o.noise.command_latency == d.command_latency &&
                o.noise.heading_sigma == d.heading_sigma) {
              return "default";
            }
            return "custom";
          },
          [](ReplayOptions& o, const std::string& v) {
            const unsigned seed = o.noise.seed;
            if (v == "none") {
              o.noise = SimulationNoise::None();
            } else if (v == "default") {
              o.noise = SimulationNoise();
            } else {
              throw py::value_error("noise: 'default' or 'none'");
            }
            o.noise.seed = seed;
          },
          "the simulated imperfections: 'default' (docs/cli.md, replay) or 'none'")
      .def_property(
          "seed", [](const ReplayOptions& o) { return o.noise.seed; },
          [](ReplayOptions& o, unsigned seed) { o.noise.seed = seed; }, "seed of every random draw")
      .def_readwrite("output_hz", &ReplayOptions::output_hz, "sample rate of the result [Hz]")
      .def_readwrite("settle_s", &ReplayOptions::settle_s, "kept running after the last waypoint [s]")
      .def_readwrite("torn_residual_energy", &ReplayOptions::torn_residual_energy,
                     "E above which a sample is torn [m^2]")
      .def_readwrite("control", &ReplayOptions::control, "ControlOptions of the plan")
      .def(
          "is_valid",
          [](const ReplayOptions& o) {
            std::string why;
            const bool ok = o.IsValid(&why);
            return py::make_tuple(ok, why);
          },
          "(ok, why): whether every field is in range");
}

void BindResult(py::module_& m) {
  py::class_<ReplaySolution>(m, "ReplayResult", "A replay: arrays with one row per output sample.")
      .def_property_readonly("converged", [](const ReplaySolution& s) { return s.result.converged; },
                             "every waypoint reached by the plan")
      .def_property_readonly("warning", [](const ReplaySolution& s) { return s.result.warning; })
      .def_property_readonly("failed_step_time", [](const ReplaySolution& s) { return s.result.failed_step_time; },
                             "[s]; NaN if every waypoint was reached")
      .def_property_readonly("torn", [](const ReplaySolution& s) { return s.result.torn; },
                             "some sample's chain could not follow the bases")
      .def_property_readonly("torn_samples", [](const ReplaySolution& s) { return s.result.torn_samples; },
                             "how many samples were torn")
      .def_property_readonly("first_torn_time", [](const ReplaySolution& s) { return s.result.first_torn_time; },
                             "[s]; NaN if never torn")
      .def_property_readonly("max_residual_energy",
                             [](const ReplaySolution& s) { return s.result.max_residual_energy; }, "[m^2]")
      .def_property_readonly(
          "rmse", [](const ReplaySolution& s) { return Eigen::Matrix<double, 6, 1>(s.result.rmse.data()); },
          "tracked vs commanded per component: x y z [m], roll pitch yaw [rad]")
      .def_property_readonly("duration_s", [](const ReplaySolution& s) { return s.result.duration_s; }, "[s]")
      .def_property_readonly(
          "trustworthy", [](const ReplaySolution& s) { return s.result.converged && !s.result.torn && s.time.size() > 0; },
          "converged and never torn: only then does the RMSE measure tracking")
      .def_readonly("time", &ReplaySolution::time, "(samples,) [s]")
      .def_readonly("commanded", &ReplaySolution::commanded, "(samples x 6) the plan's end-effector")
      .def_readonly("tracked", &ReplaySolution::tracked, "(samples x 6) the driven chain's end-effector")
      .def_readonly("set_controls", &ReplaySolution::set_controls, "(samples x num_controls)")
      .def_readonly("true_controls", &ReplaySolution::true_controls,
                    "(samples x num_controls) where the bases really are")
      .def_readonly("residual_energy", &ReplaySolution::residual_energy, "(samples,) of the chain [m^2]")
      .def_readonly("sample_torn", &ReplaySolution::sample_torn, "(samples,) bool")
      .def_readonly("sample_assembled", &ReplaySolution::sample_assembled, "(samples,) bool: E <= 1e-16 m^2")
      .def("__repr__", [](const ReplaySolution& s) {
        return std::string("<ccma.ReplayResult converged=") + (s.result.converged ? "True" : "False") +
               " torn=" + (s.result.torn ? "True" : "False") + " samples=" + std::to_string(s.time.size()) + ">";
      });
}

}  // namespace

void BindReplay(py::module_& m) {
  BindOptions(m);
  BindResult(m);
  m.def("replay", &Run, py::arg("model"), py::arg("waypoints"), py::arg("options") = ReplayOptions(),
        py::call_guard<py::gil_scoped_release>(),
        "The paper's closed loop, simulated: bases track the control solution with noise and latency, "
        "the chain follows (execution/replay.h). waypoints: a list of ccma.Waypoint. Raises ValueError "
        "on waypoints or options out of range.");
  m.def(
      "replay",
      [](const Model& model, const Eigen::Ref<const RowMatrix>& a, const ReplayOptions& options) {
        const std::vector<Waypoint> w = WaypointsFromArray(a);
        py::gil_scoped_release release;
        return Run(model, w, options);
      },
      py::arg("model"), py::arg("waypoints"), py::arg("options") = ReplayOptions(),
      "The same for an (N x 7) array of rows [time, x, y, z, roll, pitch, yaw].");
}

}  // namespace ccma::python
