// `ccma design --model=FILE --targets=FILE.csv --out=NEW.yaml [--vary=...] [--vary_length=...]`:
// moves the named geometry (analyses/design.h) until every target pose is
// reachable with margin; writes the model file with only those numbers
// changed and prints {reached, changed, converged, ...}.
#include <cmath>
#include <limits>
#include <iostream>
#include <sstream>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/output_file.h"
#include "apps/work_bound.h"
#include "ccma/limits.h"
#include "formats/model_loader.h"
#include "formats/waypoints.h"
#include "analyses/design.h"
#include "analyses/design_objective.h"

DEFINE_string(targets, "", "design: target poses, waypoint CSV (docs/waypoints.md; time is ignored) [path]");
DEFINE_string(vary, "",
              "design: joint points to vary, comma-separated JOINT.x|JOINT.y|JOINT.z|JOINT.point "
              "(world home coordinates; one item per joint) [list]");
DEFINE_string(vary_length, "",
              "design: link lengths to vary, comma-separated ANCHOR:JOINT (JOINT moves along the line from "
              "ANCHOR; both on one body) [list]");
DEFINE_double(max_change, 0.5, "design: largest change of any varied quantity, (0, 100] [m]");
DEFINE_double(min_length, 0.02, "design: smallest allowed varied link length, (0, 100] [m]");
DEFINE_double(min_singular_value, 0.02,
              "design: required smallest singular value of dX/du at every target, [0, 100] [m or rad per control unit]");
DEFINE_double(target_tolerance, 1e-6, "design: a target is reached within this, [1e-12, 1] [m or rad]");
DEFINE_int32(design_iterations, 30, "design: outer iterations per phase, [1, 1000] [count]");
DEFINE_string(objective, "reach",
              "design: what to improve once every target is reached with margin: reach (nothing more), payload "
              "(largest payload within the effort and push limits), peak_push (smallest largest base push), ee_std "
              "(smallest end-effector position standard deviation from --mocap_noise_m/_rad), stiffness (smallest largest "
              "translational compliance of a compliant model, m/N), deflection (smallest end-effector deflection "
              "under gravity and the payload, m) [name]");

namespace ccma::cli {
namespace {

constexpr std::size_t kMaxTargets = 1000;  // each costs a control solve per design trial

std::vector<std::string> SplitList(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

// Loads the model at `path` and keeps its text in `text`: the numbers are
// later patched into the very text that was loaded (read once, with the
// loader's bounds). Throws ModelError like LoadModel; warnings go to stderr.
Model LoadModelKeepingText(const std::string& path, std::string* text) {
  std::string error;
  if (!internal::ReadRegularFile(path, kMaxModelFileBytes, "model file", text, &error)) throw ModelError(error);
  std::vector<std::string> warnings;
  Model model = LoadModelFromString(*text, path, &warnings);
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  return model;
}

nlohmann::json TargetsJson(const std::vector<DesignTargetResult>& results, bool reached_only) {
  nlohmann::json out = nlohmann::json::array();
  for (const DesignTargetResult& r : results) {
    if (reached_only) {
      out.push_back(r.reached);
    } else {
      out.push_back({{"reached", r.reached},
                     {"error", std::isfinite(r.error) ? r.error : -1.0},
                     {"min_singular_value", r.min_singular_value},
                     {"within_limits", r.within_limits}});
    }
  }
  return out;
}

// The --targets poses (times ignored); UsageError for a bad file or count.
std::vector<PoseTarget> TargetsFlag() {
  std::vector<Waypoint> waypoints;
  try {
    waypoints = LoadWaypoints(RequireFlag(FLAGS_targets, "targets", "design"));
  } catch (const WaypointError& e) {
    throw UsageError(std::string("ccma design: --targets: ") + e.what());
  }
  if (waypoints.empty() || waypoints.size() > kMaxTargets) {
    throw UsageError("ccma design: --targets: between 1 and " + std::to_string(kMaxTargets) + " targets needed, got " +
                     std::to_string(waypoints.size()));
  }
  std::vector<PoseTarget> targets;
  for (const Waypoint& w : waypoints) targets.push_back({w.position, w.rpy});
  return targets;
}

// What --vary and --vary_length name; UsageError when nothing or a bad item.
DesignParameters ParametersFromFlags(const Model& model) {
  DesignParameters params;
  std::string why;
  for (const std::string& item : SplitList(FLAGS_vary)) {
    if (!AddJointCoordinates(model, item, &params, &why)) throw UsageError("--vary: " + why);
  }
  for (const std::string& item : SplitList(FLAGS_vary_length)) {
    if (!AddLinkLength(model, item, &params, &why)) throw UsageError("--vary_length: " + why);
  }
  if (params.size() == 0) throw UsageError("ccma design: name what to vary with --vary and/or --vary_length");
  return params;
}

DesignOptions DesignOptionsFromFlags() {
  DesignOptions options;
  options.control = ControlOptionsFromFlags();
  options.max_change = FLAGS_max_change;
  options.min_length = FLAGS_min_length;
  options.min_singular_value = FLAGS_min_singular_value;
  options.target_tolerance = FLAGS_target_tolerance;
  options.max_iterations = FLAGS_design_iterations;
  if (!ParseDesignObjective(FLAGS_objective, &options.objective)) {
    throw UsageError("ccma design: --objective must be reach, payload, peak_push, ee_std, stiffness or deflection, "
                     "got " + Quote(FLAGS_objective));
  }
  options.noise = PoseNoiseFromFlags();
  std::string why;
  if (!options.IsValid(&why)) throw UsageError("ccma design: " + why);
  return options;
}

// Every target reached in `check`, with sigma_min at least the threshold.
bool ConvergedIn(const std::vector<DesignTargetResult>& check, const DesignOptions& options) {
  bool all_reached = true;
  double min_sigma = std::numeric_limits<double>::infinity();
  for (const DesignTargetResult& r : check) {
    all_reached = all_reached && r.reached;
    min_sigma = std::min(min_sigma, r.min_singular_value);
  }
  return all_reached && min_sigma >= options.min_singular_value;
}

// "changed" (parameter, old, new) and "changed_points" (joint, old and new world point).
void AddChanges(const Model& model, const Model& designed, const DesignParameters& params,
                const DesignResult& result, nlohmann::json* out) {
  nlohmann::json changed = nlohmann::json::array();
  for (int k = 0; k < params.size(); ++k) {
    changed.push_back({{"parameter", params.list[k].label}, {"old", result.p0[k]}, {"new", result.p[k]}, {"unit", "m"}});
  }
  (*out)["changed"] = changed;
  nlohmann::json points = nlohmann::json::array();
  for (int j = 0; j < static_cast<int>(model.joints.size()); ++j) {
    const Eigen::Vector3d a = JointPointWorld(model, j), b = JointPointWorld(designed, j);
    if (a != b) points.push_back({{"joint", model.joints[j].name}, {"old_point", ToJson(Eigen::VectorXd(a))},
                                  {"new_point", ToJson(Eigen::VectorXd(b))}});
  }
  (*out)["changed_points"] = points;
}

nlohmann::json ObjectiveValueJson(const ObjectiveAtTarget& v) {
  if (!v.defined) return nullptr;
  return {{"value", v.value}, {"limiting", v.limiting}};
}

// "objective": what phase 3 improved (null values where not defined).
nlohmann::json ObjectiveJson(const DesignOptions& options, const DesignResult& result) {
  nlohmann::json out = {{"name", DesignObjectiveName(options.objective)},
                        {"unit", DesignObjectiveUnit(options.objective)},
                        {"maximised", IsMaximised(options.objective)},
                        {"before", ObjectiveValueJson(result.objective_before)},
                        {"after", ObjectiveValueJson(result.objective_after)},
                        {"iterations", result.objective_iterations},
                        {"stopped", result.objective_message}};
  return out;
}

// The JSON on stdout (docs/cli.md, "ccma design"); warnings also on stderr.
nlohmann::json DesignJson(const Model& model, const Model& designed, const DesignParameters& params,
                          const DesignOptions& options, const DesignResult& result,
                          const std::vector<DesignTargetResult>& final_check, const std::string& out_path) {
  const bool converged = ConvergedIn(final_check, options);
  nlohmann::json out;
  out["model"] = model.name;
  out["out"] = out_path;
  out["converged"] = converged;
  out["reached"] = TargetsJson(final_check, true);
  out["reached_before"] = TargetsJson(result.initial, true);
  out["targets"] = TargetsJson(final_check, false);
  out["iterations"] = result.iterations;
  AddChanges(model, designed, params, result, &out);
  if (options.objective != DesignObjective::kReach) {
    out["objective"] = ObjectiveJson(options, result);
    if (converged && !result.objective_after.defined) {
      out["warning"] = "the " + std::string(DesignObjectiveName(options.objective)) +
                       " objective is not defined: " + result.objective_after.why;
      std::cerr << "ccma design: warning: " << out["warning"].get<std::string>() << "\n";
    }
  }
  if (!converged) {
    const std::string message = result.message.empty() ? "not every target is reached with margin" : result.message;
    out["warning"] = message;
    std::cerr << "ccma design: warning: not converged: " << message << "\n";
  }
  return out;
}

}  // namespace

int RunDesign(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "design");
  const std::string model_path = RequireFlag(FLAGS_model, "model", "design");
  std::string model_text;
  const Model model = LoadModelKeepingText(model_path, &model_text);
  const std::vector<PoseTarget> targets = TargetsFlag();
  const std::string out_path = RequireFlag(FLAGS_out, "out", "design");
  const DesignParameters params = ParametersFromFlags(model);
  DesignOptions options = DesignOptionsFromFlags();
  const bool needs_springs =
      options.objective == DesignObjective::kStiffness || options.objective == DesignObjective::kDeflection;
  if (needs_springs && !model.compliant()) {
    throw UsageError("ccma design: --objective=" + FLAGS_objective + ": model " + Quote(model.name) +
                     " has no stiffness keys: a rigid mechanism has no compliance to lower (model_format.md, "
                     "\"Compliance\")");
  }
  OutputFile file(out_path, "out");  // checked before the long run
  // Work bounded by its cost (--max_minutes): the iterations timed as they go.
  WorkEstimateOptions bound = CommandWorkEstimate("design", "design iterations", false);
  bound.up_to = true;
  WorkEstimate estimate(bound, MaxDesignIterations(options));
  options.estimate = &estimate;

  const DesignResult result = Design(model, params, targets, options);
  const Model designed = ApplyParameters(model, params, result.p);
  const std::string text = PatchModelText(model_text, model, designed, params);
  // Reachability in the model as written (loaded back from the new text).
  const Model written = LoadModelFromString(text, out_path);
  const std::vector<DesignTargetResult> final_check = EvaluateTargets(written, targets, options);

  file.stream() << text;
  file.Commit();

  PrintJson(DesignJson(model, designed, params, options, result, final_check, out_path));
  return 0;
}

}  // namespace ccma::cli
