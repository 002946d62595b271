// Workspace maps (analyses/workspace.h) for ccma.workspace (python/ccma/workspace.py):
//   _workspace_compute(model, ranges, ..., progress=None) -> dict of arrays (local threads)
//   _workspace_tiles(model, ranges, ...) -> list of tiles (rows, order, depends_on)
//   _workspace_tile(model, ranges, ..., tile, inputs) -> dict of arrays with states
// Private: the public call is ccma.workspace, which adds the Dask path: one
// task per tile (or group of tiles), submitted when the tiles it depends on
// are finished, their results (with states) passed as `inputs`. States cross
// as arrays copied bit for bit, so a distributed run gives the same numbers
// as a local one.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "ccma/model.h"
#include "analyses/workspace.h"
#include "analyses/work_estimate.h"
#include "documents/workspace_table.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
#include "python/src/json_to_python.h"
#include "python/src/pose_types.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

// [(name, lo, hi), ...] with names x y z roll pitch yaw.
using RangeList = std::vector<std::tuple<std::string, double, double>>;

std::vector<WorkspaceRange> Ranges(const RangeList& ranges) {
  std::vector<WorkspaceRange> out;
  for (const auto& [name, lo, hi] : ranges) {
    int component = -1;
    for (int c = 0; c < 6; ++c) {
      if (name == kEndEffectorComponentNames[static_cast<size_t>(c)]) component = c;
    }
    if (component < 0) throw std::invalid_argument("ranges: " + Quote(name) + " is not one of x y z roll pitch yaw");
    out.push_back({component, lo, hi});
  }
  return out;
}

WorkspaceOptions Options(const Model& model, const RangeList& ranges, int resolution, int samples,
                         std::uint64_t seed, int threads, int wave_size, const ControlOptions& control,
                         int tile_size = 0) {
  WorkspaceOptions o;
  o.tile_size = tile_size;
  o.ranges = Ranges(ranges);
  o.resolution = resolution;
  o.random_samples = samples;
  o.seed = seed;
  o.threads = threads;
  o.wave_size = wave_size;
  o.control = control;
  std::string why;
  if (!o.IsValid(model, &why)) throw std::invalid_argument("workspace: " + why);
  return o;
}

// A state crosses to the workers as StateToArray's rows [qw, qx, qy, qz, px,
// py, pz] (the Python convention) and comes back through FromArray,
StateArray ToArray(const State& s) { return StateToArray(s); }

// the inverse of ToArray, bit-exact (no re-normalisation: the continuation
// must see the same state).
State FromArray(const Model& model, const StateArray& a) {
  if (a.rows() != model.num_bodies() || !a.allFinite()) {
    throw std::invalid_argument("workspace: a start state must be " + std::to_string(model.num_bodies()) +
                                " x 7 finite numbers");
  }
  State s(model.num_bodies());
  for (int b = 0; b < model.num_bodies(); ++b) {
    double* pose = s.pose(b);  // storage: qx qy qz qw px py pz
    pose[0] = a(b, 1);
    pose[1] = a(b, 2);
    pose[2] = a(b, 3);
    pose[3] = a(b, 0);
    for (int i = 4; i < kPoseAmbientSize; ++i) pose[i] = a(b, i);
  }
  return s;
}

RowMatrix PosesArray(const std::vector<PoseTarget>& poses) {
  RowMatrix a(static_cast<Eigen::Index>(poses.size()), 6);
  for (size_t i = 0; i < poses.size(); ++i) a.row(static_cast<Eigen::Index>(i) ) << poses[i].position.transpose(), poses[i].rpy.transpose();
  return a;
}

py::dict SamplesDict(const Model& model, const std::vector<WorkspaceSample>& samples, bool with_states) {
  const auto n = static_cast<Eigen::Index>(samples.size());
  std::vector<PoseTarget> poses;
  Eigen::Matrix<bool, Eigen::Dynamic, 1> reachable(n), converged(n), assembled(n);
  RowMatrix controls(n, model.num_controls());
  Eigen::VectorXd energy(n), error(n), sigma(n), rcond(n), violation(n);
  Eigen::VectorXi wave(n), steps(n), tile(n);
  Eigen::Matrix<long long, Eigen::Dynamic, 1> start(n);
  std::vector<std::string> limited_by, warning;
  StateArray states(with_states ? n * model.num_bodies() : 0, 7);
  for (Eigen::Index i = 0; i < n; ++i) {
    const WorkspaceSample& s = samples[static_cast<size_t>(i)];
    poses.push_back(s.pose);
    reachable[i] = s.reachable;
    converged[i] = s.converged;
    assembled[i] = s.assembled;
    controls.row(i) = s.controls.transpose();
    energy[i] = s.residual_energy;
    error[i] = s.error;
    sigma[i] = s.sigma_min;
    rcond[i] = s.rcond;
    violation[i] = s.max_limit_violation;
    wave[i] = s.wave;
    tile[i] = s.tile;
    steps[i] = s.steps;
    start[i] = s.start;
    limited_by.push_back(s.limited_by);
    warning.push_back(s.warning);
    if (with_states) states.middleRows(i * model.num_bodies(), model.num_bodies()) = ToArray(s.state);
  }
  py::dict d;
  d["poses"] = PosesArray(poses);
  d["reachable"] = reachable;
  d["converged"] = converged;
  d["assembled"] = assembled;
  d["controls"] = controls;
  d["residual_energy"] = energy;
  d["error"] = error;
  d["sigma_min"] = sigma;
  d["rcond"] = rcond;
  d["max_limit_violation"] = violation;
  d["wave"] = wave;
  d["start"] = start;
  d["steps"] = steps;
  d["tile"] = tile;
  d["limited_by"] = limited_by;
  d["warning"] = warning;
  if (with_states) d["states"] = states;
  return d;
}

// The per-sample arrays of a SamplesDict (with states when `with_states`)
// have n rows; throws otherwise.
void CheckShapes(const Model& model, const py::dict& d, Eigen::Index n, bool with_states) {
  bool ok = d["controls"].cast<RowMatrix>().rows() == n && d["controls"].cast<RowMatrix>().cols() == model.num_controls() &&
            (!with_states || d["states"].cast<StateArray>().rows() == n * model.num_bodies()) &&
            d["limited_by"].cast<std::vector<std::string>>().size() == static_cast<size_t>(n) &&
            d["warning"].cast<std::vector<std::string>>().size() == static_cast<size_t>(n);
  for (const char* key : {"reachable", "converged", "assembled"}) {
    ok = ok && d[key].cast<Eigen::Matrix<bool, Eigen::Dynamic, 1>>().size() == n;
  }
  for (const char* key : {"residual_energy", "error", "sigma_min", "rcond", "max_limit_violation"}) {
    ok = ok && d[key].cast<Eigen::VectorXd>().size() == n;
  }
  for (const char* key : {"steps", "wave", "tile"}) ok = ok && d[key].cast<Eigen::VectorXi>().size() == n;
  ok = ok && d["start"].cast<Eigen::Matrix<long long, Eigen::Dynamic, 1>>().size() == n;
  if (!ok) throw std::invalid_argument("workspace: a tile's input has arrays of the wrong shape");
}

// The inverse of SamplesDict: with states for a tile's inputs, without (the
// samples' states left empty) for a map's table.
std::vector<WorkspaceSample> SamplesFromDict(const Model& model, const py::dict& d, bool with_states = true) {
  const auto reachable = d["reachable"].cast<Eigen::Matrix<bool, Eigen::Dynamic, 1>>();
  const Eigen::Index n = reachable.size();
  CheckShapes(model, d, n, with_states);
  const auto converged = d["converged"].cast<Eigen::Matrix<bool, Eigen::Dynamic, 1>>();
  const auto assembled = d["assembled"].cast<Eigen::Matrix<bool, Eigen::Dynamic, 1>>();
  const auto controls = d["controls"].cast<RowMatrix>();
  const auto energy = d["residual_energy"].cast<Eigen::VectorXd>();
  const auto error = d["error"].cast<Eigen::VectorXd>();
  const auto sigma = d["sigma_min"].cast<Eigen::VectorXd>();
  const auto rcond = d["rcond"].cast<Eigen::VectorXd>();
  const auto violation = d["max_limit_violation"].cast<Eigen::VectorXd>();
  const auto steps = d["steps"].cast<Eigen::VectorXi>();
  const auto wave = d["wave"].cast<Eigen::VectorXi>();
  const auto tile = d["tile"].cast<Eigen::VectorXi>();
  const auto start = d["start"].cast<Eigen::Matrix<long long, Eigen::Dynamic, 1>>();
  const auto limited_by = d["limited_by"].cast<std::vector<std::string>>();
  const auto warning = d["warning"].cast<std::vector<std::string>>();
  const auto states = with_states ? d["states"].cast<StateArray>() : StateArray();
  const auto poses = d["poses"].cast<RowMatrix>();
  std::vector<WorkspaceSample> out(static_cast<size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    WorkspaceSample& s = out[static_cast<size_t>(i)];
    s.pose.position = poses.row(i).head<3>().transpose();
    s.pose.rpy = poses.row(i).tail<3>().transpose();
    s.reachable = reachable[i];
    s.converged = converged[i];
    s.assembled = assembled[i];
    s.controls = controls.row(i).transpose();
    s.residual_energy = energy[i];
    s.error = error[i];
    s.sigma_min = sigma[i];
    s.rcond = rcond[i];
    s.max_limit_violation = violation[i];
    s.steps = steps[i];
    s.wave = wave[i];
    s.start = start[i];
    s.tile = tile[i];
    s.limited_by = limited_by[static_cast<size_t>(i)];
    s.warning = warning[static_cast<size_t>(i)];
    if (with_states) s.state = FromArray(model, states.middleRows(i * model.num_bodies(), model.num_bodies()));
  }
  return out;
}

// A per-sample column of a tile's samples (SamplesDict with states): f at
// each reached sample, 0 at the others.
Eigen::VectorXd TileColumn(const Model& model, const StateArray& states, const RowMatrix& controls,
                           const Eigen::Matrix<bool, Eigen::Dynamic, 1>& reachable,
                           double (*f)(const Model&, const State&, const Eigen::VectorXd&)) {
  const Eigen::Index n = reachable.size();
  if (controls.rows() != n || controls.cols() != model.num_controls() || states.rows() != n * model.num_bodies()) {
    throw std::invalid_argument("workspace: a tile's arrays have the wrong shape");
  }
  Eigen::VectorXd out(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    out[i] = reachable[i] ? f(model, FromArray(model, states.middleRows(i * model.num_bodies(), model.num_bodies())),
                              controls.row(i).transpose())
                          : 0.0;
  }
  return out;
}

// Python's progress(done, total), called with the GIL at most about 1000
// times per map (and always at the end); none when `progress` is None. Holds
// a reference: `progress` outlives the computation.
WorkspaceProgress PythonProgress(const py::object& progress) {
  if (progress.is_none()) return nullptr;
  return [&progress, last = 0LL](long long done, long long total) mutable {
    if (done != total && done - last < std::max<long long>(1, total / 1000)) return;
    last = done;
    py::gil_scoped_acquire gil;
    progress(done, total);
  };
}

// With `estimate` (not null): the rows' computed columns timed at home (in
// the estimate from the start), the samples counted as they finish, then
// those columns as a stage of their own, never refused.
py::dict WorkspaceCompute(const Model& model, const RangeList& ranges, int resolution, int samples,
                          std::uint64_t seed, int threads, int wave_size, const ControlOptions& control,
                          int tile_size, const py::object& progress, WorkEstimate* estimate) {
  const WorkspaceOptions o = Options(model, ranges, resolution, samples, seed, threads, wave_size, control, tile_size);
  if (estimate != nullptr) {
    estimate->AddLaterSeconds(documents::WorkspaceRowSeconds(model) * static_cast<double>(o.SampleCount()),
                              "the computed columns");
  }
  const WorkspaceProgress python = PythonProgress(progress);
  const WorkspaceProgress report = [&python, estimate](long long done, long long total) {
    if (estimate != nullptr) estimate->Update(done);
    if (python) python(done, total);
  };
  WorkspaceResult r;
  {
    py::gil_scoped_release release;
    r = ComputeWorkspace(model, o, report);
  }
  const long long n = static_cast<long long>(r.samples.size());
  if (estimate != nullptr) estimate->BeginStage("rows' computed columns", n, 0, false);
  py::dict d = SamplesDict(model, r.samples, false);
  const documents::WorkspaceComputedColumns computed =
      documents::ComputeWorkspaceColumns(model, r.samples, [estimate](long long row) {
        if (estimate != nullptr) estimate->Update(row);
      });
  d["ee_std_m"] = computed.ee_std_m;
  if (model.compliant()) d["stiffness_min_N_per_m"] = computed.stiffness_min;
  d["tile_size"] = o.TileSide();
  std::vector<std::string> components;
  for (int c : r.components) components.emplace_back(kEndEffectorComponentNames[static_cast<size_t>(c)]);
  d["components"] = components;
  d["seconds"] = r.seconds;
  d["tiles"] = r.tiles;
  return d;
}

py::list WorkspaceTilesList(const Model& model, const RangeList& ranges, int resolution, int samples,
                            std::uint64_t seed, int wave_size, int tile_size) {
  const WorkspaceOptions o = Options(model, ranges, resolution, samples, seed, 1, wave_size, ControlOptions(), tile_size);
  py::list out;
  for (const WorkspaceTile& t : WorkspaceTiles(model, o)) {
    py::dict d;
    d["rows"] = Eigen::Matrix<long long, Eigen::Dynamic, 1>(
        Eigen::Map<const Eigen::Matrix<long long, Eigen::Dynamic, 1>>(t.rows.data(), static_cast<Eigen::Index>(t.rows.size())));
    d["order"] = t.order;
    d["depends_on"] = t.depends_on;
    out.append(d);
  }
  return out;
}

// A tile's result as a dict: its samples with states, and "carried" (the
// same, for the carried samples) with "carried_rows".
py::dict TileResultDict(const Model& model, const WorkspaceTileResult& r) {
  py::dict d = SamplesDict(model, r.samples, true);
  d["carried"] = SamplesDict(model, r.carried, true);
  d["carried_rows"] = r.carried_rows;
  return d;
}

WorkspaceTileResult TileResultFromDict(const Model& model, const py::dict& d) {
  WorkspaceTileResult r;
  r.samples = SamplesFromDict(model, d);
  r.carried = SamplesFromDict(model, d["carried"].cast<py::dict>());
  r.carried_rows = d["carried_rows"].cast<std::vector<long long>>();
  return r;
}

// One tile on the calling thread. `inputs`: the results of _workspace_tile
// for the tiles it depends on, in depends_on order.
py::dict WorkspaceTileEvaluate(const Model& model, const RangeList& ranges, int resolution, int samples,
                               std::uint64_t seed, int wave_size, const ControlOptions& control, int tile_size,
                               int tile, const std::vector<py::dict>& inputs) {
  const WorkspaceOptions o = Options(model, ranges, resolution, samples, seed, 1, wave_size, control, tile_size);
  std::vector<WorkspaceTileResult> given;
  for (const py::dict& d : inputs) given.push_back(TileResultFromDict(model, d));
  WorkspaceTileResult out;
  {
    py::gil_scoped_release release;
    out = EvaluateWorkspaceTile(model, o, tile, given);
  }
  return TileResultDict(model, out);
}

// The map's table (documents/workspace_table.h) from its arrays: a
// SamplesDict without states plus "ee_std_m" and, for a compliant model,
// "stiffness_min_N_per_m".
py::object WorkspaceTableOf(const Model& model, const py::dict& map) {
  const std::vector<WorkspaceSample> samples = SamplesFromDict(model, map, false);
  documents::WorkspaceComputedColumns computed;
  computed.ee_std_m = map["ee_std_m"].cast<Eigen::VectorXd>();
  if (model.compliant()) computed.stiffness_min = map["stiffness_min_N_per_m"].cast<Eigen::VectorXd>();
  try {
    return ToTable(documents::WorkspaceTable(model, samples, computed));
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

}  // namespace

void BindWorkspace(py::module_& m) {
  m.def("_workspace_table", &WorkspaceTableOf, py::arg("model"), py::arg("map"),
        "Internal: the map's table (`ccma workspace --out`'s columns) from its arrays.");
  m.def("_workspace_compute", &WorkspaceCompute, py::arg("model"), py::arg("ranges"), py::arg("resolution"),
        py::arg("samples"), py::arg("seed"), py::arg("threads"), py::arg("wave_size"), py::arg("control"),
        py::arg("tile_size") = 0, py::arg("progress") = py::none(), py::arg("estimate") = nullptr,
        "Internal: ccma.workspace's map on local threads (analyses/workspace.h ComputeWorkspace); `estimate` "
        "(a _WorkEstimate of its samples) told of every sample and row.");
  m.def("_workspace_row_seconds", &documents::WorkspaceRowSeconds, py::arg("model"),
        "Internal: what a row's computed columns (ee_std_m, stiffness_min_N_per_m) take at home [s].");
  m.def(
      "_workspace_ee_std",
      [](const Model& model, const StateArray& states, const RowMatrix& controls,
         const Eigen::Matrix<bool, Eigen::Dynamic, 1>& reachable) {
        return TileColumn(model, states, controls, reachable, documents::WorkspaceEeStd);
      },
      py::arg("model"), py::arg("states"), py::arg("controls"), py::arg("reachable"),
      "Internal: the ee_std_m column [m] of a tile's samples.");
  m.def(
      "_workspace_stiffness_min",
      [](const Model& model, const StateArray& states, const RowMatrix& controls,
         const Eigen::Matrix<bool, Eigen::Dynamic, 1>& reachable) -> py::object {
        if (!model.compliant()) return py::none();
        return py::cast(TileColumn(model, states, controls, reachable, documents::WorkspaceStiffnessMin));
      },
      py::arg("model"), py::arg("states"), py::arg("controls"), py::arg("reachable"),
      "Internal: the stiffness_min_N_per_m column [N/m] of a compliant model's tile (None for a rigid model).");
  m.def(
      "_workspace_tile_side",
      [](const Model& model, const RangeList& ranges, int resolution, int samples, std::uint64_t seed, int wave_size,
         int tile_size) {
        return Options(model, ranges, resolution, samples, seed, 1, wave_size, ControlOptions(), tile_size).TileSide();
      },
      py::arg("model"), py::arg("ranges"), py::arg("resolution"), py::arg("samples"), py::arg("seed"),
      py::arg("wave_size"), py::arg("tile_size"), "Internal: a tile's side [cells per range].");
  m.def("_workspace_tiles", &WorkspaceTilesList, py::arg("model"), py::arg("ranges"), py::arg("resolution"),
        py::arg("samples"), py::arg("seed"), py::arg("wave_size"), py::arg("tile_size"),
        "Internal: the map's tiles (WorkspaceTiles).");
  m.def("_workspace_tile", &WorkspaceTileEvaluate, py::arg("model"), py::arg("ranges"), py::arg("resolution"),
        py::arg("samples"), py::arg("seed"), py::arg("wave_size"), py::arg("control"), py::arg("tile_size"),
        py::arg("tile"), py::arg("inputs"),
        "Internal: one tile of a distributed workspace map (EvaluateWorkspaceTile).");
}

}  // namespace ccma::python
