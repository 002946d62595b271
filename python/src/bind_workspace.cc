// Workspace maps (analyses/workspace.h) for ccma.workspace (python/ccma/workspace.py):
//   _workspace_compute(model, ranges, ..., evaluate_batch=None) -> dict of arrays
//   _workspace_evaluate(model, ranges, poses, states, controls, ...) -> dict of arrays
// Private: the public call is ccma.workspace, which adds the Dask path by
// passing an `evaluate_batch` that sends each wave to the workers in chunks,
// where _workspace_evaluate runs. States cross as (bodies x 7) arrays copied
// bit for bit, so a distributed run gives the same numbers as a local one.
#include <cstdint>
#include <tuple>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "ccma/model.h"
#include "analyses/workspace.h"
#include "python/src/bindings.h"
#include "python/src/conversions.h"
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
    if (component < 0) throw std::invalid_argument("ranges: '" + name + "' is not one of x y z roll pitch yaw");
    out.push_back({component, lo, hi});
  }
  return out;
}

WorkspaceOptions Options(const Model& model, const RangeList& ranges, int resolution, int samples,
                         std::uint64_t seed, int threads, int wave_size, const ControlOptions& control) {
  WorkspaceOptions o;
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
  Eigen::VectorXi wave(n), steps(n);
  Eigen::Matrix<long long, Eigen::Dynamic, 1> start(n);
  std::vector<std::string> limited_by, warning;
  py::list states;
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
    steps[i] = s.steps;
    start[i] = s.start;
    limited_by.push_back(s.limited_by);
    warning.push_back(s.warning);
    if (with_states) states.append(ToArray(s.state));
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
  d["limited_by"] = limited_by;
  d["warning"] = warning;
  if (with_states) d["states"] = states;
  return d;
}

// The inverse of SamplesDict (with states), for results coming back from workers.
std::vector<WorkspaceSample> SamplesFromDict(const Model& model, const py::dict& d, size_t expected) {
  const auto reachable = d["reachable"].cast<Eigen::Matrix<bool, Eigen::Dynamic, 1>>();
  const auto converged = d["converged"].cast<Eigen::Matrix<bool, Eigen::Dynamic, 1>>();
  const auto assembled = d["assembled"].cast<Eigen::Matrix<bool, Eigen::Dynamic, 1>>();
  const auto controls = d["controls"].cast<RowMatrix>();
  const auto energy = d["residual_energy"].cast<Eigen::VectorXd>();
  const auto error = d["error"].cast<Eigen::VectorXd>();
  const auto sigma = d["sigma_min"].cast<Eigen::VectorXd>();
  const auto rcond = d["rcond"].cast<Eigen::VectorXd>();
  const auto violation = d["max_limit_violation"].cast<Eigen::VectorXd>();
  const auto steps = d["steps"].cast<Eigen::VectorXi>();
  const auto limited_by = d["limited_by"].cast<std::vector<std::string>>();
  const auto warning = d["warning"].cast<std::vector<std::string>>();
  const auto states = d["states"].cast<std::vector<StateArray>>();
  const auto n = static_cast<Eigen::Index>(expected);
  if (reachable.size() != n || converged.size() != n || assembled.size() != n || controls.rows() != n ||
      controls.cols() != model.num_controls() || energy.size() != n || error.size() != n || sigma.size() != n ||
      rcond.size() != n || violation.size() != n || steps.size() != n || limited_by.size() != expected ||
      warning.size() != expected || states.size() != expected) {
    throw std::runtime_error("workspace: the batch evaluator returned arrays of the wrong shape");
  }
  std::vector<WorkspaceSample> out(expected);
  for (Eigen::Index i = 0; i < n; ++i) {
    WorkspaceSample& s = out[static_cast<size_t>(i)];
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
    s.limited_by = limited_by[static_cast<size_t>(i)];
    s.warning = warning[static_cast<size_t>(i)];
    s.state = FromArray(model, states[static_cast<size_t>(i)]);
  }
  return out;
}

// Sends each wave to Python's `evaluate_batch(poses, states, controls)` (the
// Dask path of ccma.workspace) and reads its dict of arrays back. Captures
// by reference (no Python object is copied while the GIL is released); both
// outlive the map's computation.
WorkspaceBatchEvaluator PythonBatchEvaluator(const Model& model, const py::object& evaluate_batch) {
  return [&model, &evaluate_batch](const std::vector<PoseTarget>& poses, const std::vector<WorkspaceStart>& starts) {
    py::gil_scoped_acquire gil;
    py::list states;
    RowMatrix controls(static_cast<Eigen::Index>(starts.size()), model.num_controls());
    for (size_t k = 0; k < starts.size(); ++k) {
      states.append(ToArray(starts[k].state));
      controls.row(static_cast<Eigen::Index>(k)) = starts[k].controls.transpose();
    }
    const py::dict result = evaluate_batch(PosesArray(poses), states, controls);
    return SamplesFromDict(model, result, poses.size());
  };
}

py::dict WorkspaceCompute(const Model& model, const RangeList& ranges, int resolution, int samples,
                          std::uint64_t seed, int threads, int wave_size, const ControlOptions& control,
                          const py::object& evaluate_batch) {
  const WorkspaceOptions o = Options(model, ranges, resolution, samples, seed, threads, wave_size, control);
  WorkspaceBatchEvaluator batch;
  if (!evaluate_batch.is_none()) batch = PythonBatchEvaluator(model, evaluate_batch);
  WorkspaceResult r;
  {
    py::gil_scoped_release release;
    r = ComputeWorkspace(model, o, nullptr, batch);
  }
  py::dict d = SamplesDict(model, r.samples, false);
  std::vector<std::string> components;
  for (int c : r.components) components.emplace_back(kEndEffectorComponentNames[static_cast<size_t>(c)]);
  d["components"] = components;
  d["seconds"] = r.seconds;
  return d;
}

py::dict WorkspaceEvaluate(const Model& model, const RangeList& ranges, const RowMatrix& poses,
                           const std::vector<StateArray>& states, const RowMatrix& controls, int threads,
                           const ControlOptions& control) {
  const WorkspaceOptions o = Options(model, ranges, 1, 0, 1, threads, 64, control);
  if (poses.cols() != 6 || poses.rows() > WorkspaceOptions::kMaxSamples || !poses.allFinite()) {
    throw std::invalid_argument("workspace: poses must be n x 6 finite numbers, n <= 1e6");
  }
  std::vector<PoseTarget> targets(static_cast<size_t>(poses.rows()));
  for (Eigen::Index i = 0; i < poses.rows(); ++i) {
    targets[static_cast<size_t>(i)].position = poses.row(i).head<3>().transpose();
    targets[static_cast<size_t>(i)].rpy = poses.row(i).tail<3>().transpose();
  }
  if (states.size() != targets.size() || controls.rows() != poses.rows() ||
      controls.cols() != model.num_controls()) {
    throw std::invalid_argument("workspace: one start state and one row of controls per pose");
  }
  std::vector<WorkspaceStart> starts;
  for (size_t i = 0; i < states.size(); ++i) {
    starts.push_back({FromArray(model, states[i]), controls.row(static_cast<Eigen::Index>(i)).transpose()});
  }
  std::vector<WorkspaceSample> samples;
  {
    py::gil_scoped_release release;
    samples = EvaluateWorkspacePoses(model, o, targets, starts);
  }
  return SamplesDict(model, samples, true);
}

}  // namespace

void BindWorkspace(py::module_& m) {
  m.def("_workspace_compute", &WorkspaceCompute, py::arg("model"), py::arg("ranges"), py::arg("resolution"),
        py::arg("samples"), py::arg("seed"), py::arg("threads"), py::arg("wave_size"), py::arg("control"),
        py::arg("evaluate_batch") = py::none(),
        "Internal: ccma.workspace's map (analyses/workspace.h ComputeWorkspace).");
  m.def("_workspace_evaluate", &WorkspaceEvaluate, py::arg("model"), py::arg("ranges"), py::arg("poses"),
        py::arg("states"), py::arg("controls"), py::arg("threads"), py::arg("control"),
        "Internal: one chunk of a distributed workspace map (EvaluateWorkspacePoses).");
}

}  // namespace ccma::python
