#include "documents/simulate_document.h"

#include "ccma/internal/format.h"
#include "documents/json_values.h"

namespace ccma::documents {
namespace {

// The configuration the document describes: the loaded one when there is one.
const State& Reported(const ForwardSolution& s) { return s.loaded ? s.loaded->state : s.state; }

// The rigid solve's warning (limits, assembly, convergence, branch jump).
std::string RigidWarning(const ForwardSolution& s) {
  std::string warning;
  const nlohmann::json limits_violated = LimitsViolatedToJson(*s.model, Reported(s));
  if (!limits_violated.empty()) warning = "joints outside their limits: " + limits_violated.dump();
  if (!s.assembled) {
    JoinWarning("not assembled: residual energy " + FormatG(s.residual_energy) +
                    " m^2 stays above the assembly tolerance; the controls cannot be reached from this start",
                &warning);
  } else if (!s.converged) {
    JoinWarning("the solver did not report convergence (" + s.message + ")", &warning);
  }
  if (s.branch_jump) {
    JoinWarning("jumped to another assembly branch at sub-step " + std::to_string(s.branch_jump_substep) + " of " +
                    std::to_string(s.substeps) + " (" + FormatG(s.branch_jump_size) + " m or rad beyond the prediction)",
                &warning);
  }
  return warning;
}

std::string LoadedWarning(const ForwardSolution& s) {
  return s.loaded && !s.loaded->converged ? "the loaded equilibrium was not found: " + s.loaded->message : "";
}

}  // namespace

ForwardSolution MakeForwardSolution(const ForwardProblem& problem, const ForwardResult& result,
                                    const std::string& start) {
  ForwardSolution s;
  static_cast<ForwardResult&>(s) = result;
  s.end_effector = problem.end_effector();
  s.controls = problem.controls();
  s.model = &problem.model();
  s.state = problem.state();
  s.assembly_tolerance = problem.options().assembly_tolerance;
  s.start = start;
  return s;
}

std::string SimulateWarning(const ForwardSolution& s) {
  std::string warning = RigidWarning(s);
  const std::string loaded = LoadedWarning(s);
  if (!loaded.empty()) JoinWarning(loaded, &warning);
  return warning;
}

Document SimulateDocument(const ForwardSolution& s) {
  const Model& model = *s.model;
  Document doc;
  nlohmann::json& out = doc.json;
  out["model"] = model.name;
  out["converged"] = s.converged;
  out["assembled"] = s.assembled;
  out["residual_energy"] = s.residual_energy;
  out["assembly_tolerance"] = s.assembly_tolerance;
  out["iterations"] = s.iterations;
  out["substeps"] = s.substeps;
  out["branch_jump"] = s.branch_jump;
  out["solve_time_ms"] = s.solve_time_ms;
  out["start"] = s.start;
  out["controls"] = ToJson(s.controls);
  out["end_effector"] = ToJson(s.end_effector);
  out["bodies"] = BodiesToJson(model, s.state);
  out["joints"] = JointsToJson(model, s.state);
  if (s.loaded) AddLoadedJson(model, *s.loaded, &out);
  out["limits_violated"] = LimitsViolatedToJson(model, Reported(s));
  AddClearance(model, Reported(s), &out, &doc.warnings);
  out["message"] = s.message;
  for (const std::string& w : {RigidWarning(s), LoadedWarning(s)}) {
    if (!w.empty()) doc.warnings.push_back(w);
  }
  const std::string warning = SimulateWarning(s);
  if (!warning.empty()) out["warning"] = warning;
  return doc;
}

}  // namespace ccma::documents
