// Design parameters (analyses/design.h): ccma.design_parameter_sensitivity
// (ds/dp, dX_EE/dp at a solved configuration), ccma.evaluate_design and the
// loop of `ccma design` for ccma.design (python/ccma/design.py).
#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "analyses/design.h"
#include "analyses/design_objective.h"
#include "ccma/limits.h"
#include "formats/model_loader.h"
#include "documents/design_document.h"
#include "python/src/bindings.h"
#include "python/src/json_to_python.h"
#include "python/src/pose_types.h"
#include "python/src/work_bound.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

DesignParameters ParametersFrom(const Model& model, const std::vector<std::string>& vary,
                                const std::vector<std::string>& vary_length) {
  DesignParameters params;
  std::string why;
  if (!AddDesignParameters(model, vary, vary_length, &params, &why)) throw py::value_error(why);
  if (params.size() == 0) throw py::value_error("name what to vary (vary and/or vary_length)");
  return params;
}

std::vector<std::string> Labels(const DesignParameters& params) {
  std::vector<std::string> labels;
  for (const DesignParameter& q : params.list) labels.push_back(q.label);
  return labels;
}

py::list TargetsList(const std::vector<DesignTargetResult>& results) {
  py::list out;
  for (const DesignTargetResult& r : results) {
    py::dict d;
    d["reached"] = r.reached;
    d["error"] = r.error;
    d["min_singular_value"] = r.min_singular_value;
    d["within_limits"] = r.within_limits;
    d["controls"] = r.controls;
    out.append(d);
  }
  return out;
}

using TargetArray = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;

// Rows x, y, z [m], roll, pitch, yaw [rad] -> targets: 1 to kMaxDesignTargets
// rows of finite numbers within kMaxMagnitude, as a --targets CSV holds.
std::vector<PoseTarget> PoseTargets(const TargetArray& targets) {
  if (targets.rows() == 0 || targets.rows() > static_cast<Eigen::Index>(kMaxDesignTargets) || !targets.allFinite() ||
      targets.cwiseAbs().maxCoeff() > kMaxMagnitude) {
    throw py::value_error("targets: N x 6 finite numbers within [-1e4, 1e4], 1 <= N <= " +
                          std::to_string(kMaxDesignTargets) + " (got " + std::to_string(targets.rows()) + " rows)");
  }
  std::vector<PoseTarget> poses;
  for (int i = 0; i < targets.rows(); ++i) {
    poses.push_back({targets.row(i).head<3>().transpose(), targets.row(i).tail<3>().transpose()});
  }
  return poses;
}

py::dict ParameterSensitivityDict(const Model& model, const StateArray& state, const Eigen::VectorXd& controls,
                                  const std::vector<std::string>& vary, const std::vector<std::string>& vary_length) {
  const DesignParameters params = ParametersFrom(model, vary, vary_length);
  const State s = StateFromArray(model, state);
  CheckControls(model, controls);
  ParameterSensitivity sens;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = ComputeParameterSensitivity(model, params, ParameterValues(model, params), s, controls, &sens);
  }
  if (!ok) throw py::value_error("dG/ds is singular at this configuration");
  py::dict d;
  d["parameters"] = Labels(params);
  d["ds_dp"] = sens.ds_dp;
  d["dX_dp"] = sens.dX_dp;
  d["dG_dp"] = sens.dG_dp;
  d["rcond"] = sens.rcond;
  return d;
}

py::list EvaluateDesign(const Model& model, const TargetArray& targets, const Eigen::VectorXd& values,
                        const std::vector<std::string>& vary, const std::vector<std::string>& vary_length,
                        double target_tolerance) {
  const DesignParameters params = ParametersFrom(model, vary, vary_length);
  if (values.size() != params.size() || !(values.size() == 0 || values.cwiseAbs().maxCoeff() <= kMaxMagnitude)) {
    throw py::value_error("values: one finite number within [-1e4, 1e4] (m) per parameter (" +
                          std::to_string(params.size()) + ")");
  }
  DesignOptions options;
  options.target_tolerance = target_tolerance;
  std::string why;
  if (!options.IsValid(&why)) throw py::value_error(why);
  const std::vector<PoseTarget> poses = PoseTargets(targets);
  std::vector<DesignTargetResult> results;
  {
    py::gil_scoped_release release;
    results = EvaluateTargets(ApplyParameters(model, params, values), poses, options);
  }
  return TargetsList(results);
}

// The options of ccma.design's keywords (ValueError for a bad one).
DesignOptions DesignOptionsFrom(const Model& model, double max_change, double min_length, double min_singular_value,
                                double target_tolerance, int design_iterations, const std::string& objective,
                                double mocap_noise_m, double mocap_noise_rad) {
  DesignOptions options;
  if (!ParseDesignObjective(objective, &options.objective)) {
    throw py::value_error("design: objective must be reach, payload, peak_push, ee_std, stiffness or deflection, got '" +
                          objective + "'");
  }
  if (NeedsSprings(options.objective) && !model.compliant()) {
    throw py::value_error("design: objective '" + objective + "': model " + Quote(model.name) +
                          " has no stiffness keys: a rigid mechanism has no compliance to lower");
  }
  options.noise = {mocap_noise_m, mocap_noise_rad};
  options.max_change = max_change;
  options.min_length = min_length;
  options.min_singular_value = min_singular_value;
  options.target_tolerance = target_tolerance;
  options.max_iterations = design_iterations;
  std::string why;
  if (!IsValidAsDesignCommand(options, &why)) throw py::value_error(why);
  return options;
}

// `ccma design` without the file: (document, the designed Model, the patched
// model text or None). With the model's text, as the command: the numbers are
// patched into the text, the text loaded back (as `source`) and the targets
// checked in that model; without, in the designed Model itself. A design
// estimated beyond `max_minutes` raises ccma.WorkBoundError.
py::tuple RunDesign(const Model& model, const std::optional<std::string>& text, const std::string& source,
                    const TargetArray& targets, const std::vector<std::string>& vary,
                    const std::vector<std::string>& vary_length, double max_change, double min_length,
                    double min_singular_value, double target_tolerance, int design_iterations,
                    const std::string& objective, double mocap_noise_m, double mocap_noise_rad, double max_minutes) {
  const DesignParameters params = ParametersFrom(model, vary, vary_length);
  DesignOptions options = DesignOptionsFrom(model, max_change, min_length, min_singular_value, target_tolerance,
                                            design_iterations, objective, mocap_noise_m, mocap_noise_rad);
  const std::vector<PoseTarget> poses = PoseTargets(targets);
  WorkEstimateOptions bound = PythonWorkEstimate("design", "design iterations", max_minutes);
  bound.up_to = true;
  WorkEstimate estimate(bound, MaxDesignIterations(options));
  options.estimate = &estimate;
  nlohmann::json document;
  Model written;
  std::optional<std::string> new_text;
  {
    py::gil_scoped_release release;
    const DesignResult r = Design(model, params, poses, options);
    const Model designed = ApplyParameters(model, params, r.p);
    written = designed;
    if (text) {
      new_text = PatchModelText(*text, model, designed, params);
      written = LoadModelFromString(*new_text, source);
    }
    document = documents::DesignDocument(model, designed, params, options, r, EvaluateTargets(written, poses, options)).json;
  }
  return py::make_tuple(ToPython(document), written, new_text ? py::object(py::str(*new_text)) : py::object(py::none()));
}

}  // namespace

void BindDesign(py::module_& m) {
  const std::vector<std::string> none;
  m.def("design_parameter_sensitivity", &ParameterSensitivityDict, py::arg("model"), py::arg("state"),
        py::arg("controls"), py::arg("vary") = none, py::arg("vary_length") = none,
        "ds/dp (tangent per m), dX_EE/dp (6 x P) and dG/dp at a forward solution (state (num_bodies x 7), rows "
        "[qw, qx, qy, qz, px, py, pz] as ForwardProblem.state; controls) for the named parameters "
        "('JOINT.x|y|z|point', 'ANCHOR:JOINT'); docs/design.md.");
  m.def("evaluate_design", &EvaluateDesign, py::arg("model"), py::arg("targets"), py::arg("values"),
        py::arg("vary") = none, py::arg("vary_length") = none, py::arg("target_tolerance") = 1e-6,
        "Reachability of targets (N x 6) on the model with the named parameters set to `values` [m] (one "
        "candidate design, no optimisation): per target reached, error, min_singular_value, within_limits, "
        "controls.");
  m.def("_design", &RunDesign, py::arg("model"), py::arg("text"), py::arg("source"), py::arg("targets"),
        py::arg("vary"), py::arg("vary_length"), py::arg("max_change"), py::arg("min_length"),
        py::arg("min_singular_value"), py::arg("target_tolerance"), py::arg("design_iterations"), py::arg("objective"),
        py::arg("mocap_noise_m"), py::arg("mocap_noise_rad"), py::arg("max_minutes") = kDefaultMaxMinutes,
        "Internal: ccma.design (python/ccma/design.py): (the JSON of `ccma design` without out, the designed "
        "Model, the patched model text or None).");
}

}  // namespace ccma::python
