// `ccma design --model=FILE --targets=FILE.csv --out=NEW.yaml [--vary=...] [--vary_length=...]`:
// moves the named geometry (analyses/design.h) until every target pose is
// reachable with margin; writes the model file with only those numbers
// changed and prints {reached, changed, converged, ...}.
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
#include "documents/design_document.h"

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

// The --targets poses (times ignored); UsageError for a bad file or count.
std::vector<PoseTarget> TargetsFlag() {
  std::vector<Waypoint> waypoints;
  try {
    waypoints = LoadWaypoints(RequireFlag(FLAGS_targets, "targets", "design"));
  } catch (const WaypointError& e) {
    throw UsageError(std::string("ccma design: --targets: ") + e.what());
  }
  if (waypoints.empty() || waypoints.size() > kMaxDesignTargets) {
    throw UsageError("ccma design: --targets: between 1 and " + std::to_string(kMaxDesignTargets) + " targets needed, got " +
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
  if (!AddDesignParameters(model, SplitList(FLAGS_vary), SplitList(FLAGS_vary_length), &params, &why)) {
    throw UsageError("--" + why);
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
  if (!IsValidAsDesignCommand(options, &why)) throw UsageError("ccma design: " + why);
  return options;
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
  if (NeedsSprings(options.objective) && !model.compliant()) {
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

  documents::Document document = documents::DesignDocument(model, designed, params, options, result, final_check);
  document.json["out"] = out_path;
  PrintDocument(document, "design");
  return 0;
}

}  // namespace ccma::cli
