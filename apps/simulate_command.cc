// `ccma simulate --model=FILE [--controls=u0,u1,...] [--from=RESULT.json]`:
// the forward problem, from home (or a printed configuration) to the controls.
#include <fstream>
#include <iostream>
#include <sstream>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/flags.h"
#include "apps/json_output.h"
#include "apps/work_bound.h"
#include "ccma/internal/format.h"
#include "documents/simulate_document.h"

DEFINE_bool(loaded, false,
            "simulate: the nonlinear loaded equilibrium of a compliant model (stiffness keys) under gravity, the "
            "payload and --wrench, controls held as commanded (default off: the rigid assembly) [bool]");

namespace ccma::cli {
namespace {

// How deeply a --from document may nest. A printed result nests 4 levels; the
// bound keeps hostile nesting (100,000 levels in 200 KB) out of the parsed tree,
// whose recursive printing or comparison would overflow the stack.
constexpr int kMaxFromDepth = 64;

// The --from document, read with the same bounds as a model file and at most
// kMaxFromDepth levels of arrays and objects.
nlohmann::json ReadResultDocument(const std::string& path) {
  std::string text, error;
  if (!internal::ReadRegularFile(path, kMaxModelFileBytes, "result document", &text, &error)) {
    throw UsageError("--from: " + error);
  }
  bool too_deep = false;
  // depth counts the containers around the one that starts; deeper ones are dropped.
  const nlohmann::json::parser_callback_t bound = [&too_deep](int depth, nlohmann::json::parse_event_t event,
                                                              nlohmann::json&) {
    const bool opens = event == nlohmann::json::parse_event_t::object_start ||
                       event == nlohmann::json::parse_event_t::array_start;
    if (opens && depth >= kMaxFromDepth) too_deep = true;
    return !too_deep;
  };
  const nlohmann::json document = nlohmann::json::parse(text, bound, /*allow_exceptions=*/false);
  if (too_deep) {
    throw UsageError("--from: " + path + ": nested more than " + std::to_string(kMaxFromDepth) +
                     " levels deep (not a document printed by ccma)");
  }
  if (document.is_discarded()) throw UsageError("--from: " + path + ": not a JSON document");
  return document;
}

// A value from an untrusted document, for a message: a string in double
// quotes, cut and escaped by Printable (format.h), else its JSON type.
std::string ShortQuote(const nlohmann::json& value) {
  if (!value.is_string()) return std::string("(a JSON ") + value.type_name() + ")";
  return "\"" + Printable(value.get_ref<const std::string&>()) + "\"";
}

// Starts `forward` from the --from document; returns its controls.
Eigen::VectorXd StartFrom(const Model& model, const std::string& path, ForwardProblem* forward) {
  const nlohmann::json document = ReadResultDocument(path);
  if (document.contains("model") && document["model"] != model.name) {
    std::cerr << "ccma simulate: warning: --from was printed for model " << ShortQuote(document["model"])
              << ", not '" << model.name << "'\n";
  }
  if (!document.contains("controls") || !document["controls"].is_array() ||
      document["controls"].size() != static_cast<size_t>(model.num_controls())) {
    throw UsageError("--from: " + path + ": controls: expected " + std::to_string(model.num_controls()) + " numbers");
  }
  Eigen::VectorXd u(model.num_controls());
  for (int i = 0; i < u.size(); ++i) {
    const nlohmann::json& v = document["controls"][static_cast<size_t>(i)];
    if (!v.is_number() || !(std::abs(v.get<double>()) <= kMaxMagnitude)) {
      throw UsageError("--from: " + path + ": controls[" + std::to_string(i) + "]: not a number of magnitude <= 1e4");
    }
    u[i] = v.get<double>();
  }
  forward->Restore(StateFromJson(model, document, "--from: " + path), u);
  return u;
}

// A base control outside its type's limits (a legged base's body_limits) is
// bad input (exit 2).
void CheckBaseControlLimits(const Model& model, const Eigen::VectorXd& u) {
  for (int k = 0; k < model.num_bases(); ++k) {
    const MobileBase& base = model.mobile_bases[static_cast<size_t>(k)];
    const BaseKind& kind = KindOf(base);
    const std::vector<ControlRange> limits = kind.Limits(base);
    for (int i = 0; i < kind.num_controls(); ++i) {
      const ControlRange& range = limits[static_cast<size_t>(i)];
      const int c = model.base_control(k) + i;
      if (!range.limited || (u[c] >= range.lower - 1e-9 && u[c] <= range.upper + 1e-9)) continue;
      throw UsageError("--controls: entry " + std::to_string(c) + " (" + FormatG(u[c], 17) + ") puts base '" +
                       base.name + "' " + kind.controls()[static_cast<size_t>(i)].name + " outside its limits [" +
                       FormatG(range.lower) + ", " + FormatG(range.upper) + "] (body_limits)");
    }
  }
}

// An actuated joint's control outside its limits is bad input (exit 2).
void CheckActuatedLimits(const Model& model, const Eigen::VectorXd& u) {
  CheckBaseControlLimits(model, u);
  for (const Joint& joint : model.joints) {
    if (!joint.actuated || !joint.limited) continue;
    const double q = u[joint.control];
    // The same tolerance as limits_violated: control's own output lands within it.
    if (q < joint.lower - 1e-9 || q > joint.upper + 1e-9) {
      throw UsageError("--controls: entry " + std::to_string(joint.control) + " (" + FormatG(q, 17) +
                       ") drives joint '" + joint.name + "' outside its limits [" + FormatG(joint.lower) + ", " +
                       FormatG(joint.upper) + "]");
    }
  }
}

// The loaded equilibrium at the rigid assembly (--loaded).
LoadedEquilibrium Loaded(const Model& model, const ForwardProblem& forward) {
  try {
    return SolveLoadedEquilibrium(model, forward.state(), forward.controls(), WrenchFlag());
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("ccma simulate --loaded: ") + e.what());
  }
}

}  // namespace

int RunSimulate(const std::vector<std::string>& args) {
  ParseCommandFlags(args, "simulate");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "simulate"));
  ForwardProblem forward(model);
  Eigen::VectorXd u = ControlsFlagOrHome(model);
  if (!FLAGS_from.empty()) {
    const Eigen::VectorXd from_controls = StartFrom(model, FLAGS_from, &forward);
    if (FLAGS_controls.empty()) u = from_controls;
  }
  CheckActuatedLimits(model, u);
  if (!FLAGS_wrench.empty() && !FLAGS_loaded) throw UsageError("--wrench: only with --loaded (the loads of the loaded equilibrium)");
  // Work bounded by its cost (--max_minutes): the sub-steps timed as they
  // are made (a far, torn walk can take minutes).
  WorkEstimate estimate(CommandWorkEstimate("simulate", "assembly sub-steps", false), forward.SubstepsTo(u));
  forward.SetSubstepObserver([&estimate](int substep, int) { estimate.Update(substep); });
  const ForwardResult result = forward.Assemble(u);

  documents::ForwardSolution solution =
      documents::MakeForwardSolution(forward, result, FLAGS_from.empty() ? "home" : FLAGS_from);
  solution.controls = u;
  // --loaded: the deflected configuration replaces the rigid one (no rigid
  // assembly: nothing to load, said by the warning).
  if (FLAGS_loaded && result.assembled) solution.loaded = Loaded(model, forward);
  PrintDocument(documents::SimulateDocument(solution), "simulate");
  return 0;
}

}  // namespace ccma::cli
