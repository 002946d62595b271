// The simulated closed loop (paper Section IV): ccma.replay(model, waypoints) (python/ccma/replay.py).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "execution/replay.h"
#include "documents/replay_document.h"
#include "documents/replay_report.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "python/src/json_to_python.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

// `ccma replay` without its files: (the command's JSON without "files" and
// "plots", its two CSV files' tables {"end_effector", "bases"}) for
// ccma.replay (python/ccma/replay.py).
py::tuple Run(const Model& model, const std::vector<Waypoint>& waypoints, const ReplayOptions& options) {
  CheckWaypoints(waypoints);  // positions and angles too, with the messages of follow and plan
  std::string why;
  if (!IsValidReplay(model, waypoints, options, &why)) throw std::invalid_argument(why);
  ReplayResult r;
  nlohmann::json document;
  documents::Table end_effector, bases;
  {
    py::gil_scoped_release release;
    r = Replay(model, waypoints, options);
    document = documents::ReplayDocument(model, options, r).json;
    end_effector = documents::ReplayEndEffectorTable(r);
    bases = documents::ReplayBasesTable(model, r);
  }
  py::dict tables;
  tables["end_effector"] = ToTable(end_effector);
  tables["bases"] = ToTable(bases);
  return py::make_tuple(ToPython(document), tables);
}

void BindReplayOptions(py::module_& m) {
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
      .def_property(
          "gait_hz", [](const ReplayOptions& o) { return o.gait.hz; },
          [](ReplayOptions& o, double v) { o.gait.hz = v; }, "legged bases: trotting gait frequency [Hz]")
      .def_property(
          "gait_bob_m", [](const ReplayOptions& o) { return o.gait.bob_m; },
          [](ReplayOptions& o, double v) { o.gait.bob_m = v; }, "legged bases: amplitude of the body's bob [m]")
      .def_property(
          "gait_sway_rad", [](const ReplayOptions& o) { return o.gait.sway_rad; },
          [](ReplayOptions& o, double v) { o.gait.sway_rad = v; },
          "legged bases: amplitude of the body's sway (roll) [rad]")
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

}  // namespace

void BindReplay(py::module_& m) {
  BindReplayOptions(m);
  m.def("_replay", &Run, py::arg("model"), py::arg("waypoints"), py::arg("options"),
        "Internal: ccma.replay (python/ccma/replay.py) for a list of ccma.Waypoint: (the JSON of `ccma replay` "
        "without files and plots, its tables {end_effector, bases}).");
  m.def(
      "_replay",
      [](const Model& model, const Eigen::Ref<const RowMatrix>& a, const ReplayOptions& options) {
        return Run(model, WaypointsFromArray(a), options);
      },
      py::arg("model"), py::arg("waypoints"), py::arg("options"),
      "The same for an (N x 7) array of rows [time, x, y, z, roll, pitch, yaw].");
}

}  // namespace ccma::python
