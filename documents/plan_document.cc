#include "documents/plan_document.h"

#include <cmath>
#include <string>

#include "documents/json_values.h"
#include "documents/trajectory_document.h"

namespace ccma::documents {
namespace {

nlohmann::json MeasuresJson(const PathMeasures& m) {
  nlohmann::json j = {{"reached_waypoints", m.reached_waypoints}, {"travel_m", m.travel_m}};
  if (std::isfinite(m.min_clearance_m)) j["min_clearance_m"] = m.min_clearance_m;
  return j;
}

// Where the finished plan stays below the clearance margin, or tears.
nlohmann::json ShortfallJson(const PlanShortfall& f) {
  nlohmann::json j = {{"step", f.step}, {"midpoint", f.midpoint}, {"time_s", f.time_s}, {"torn", f.torn}};
  if (f.torn) {
    j["residual_energy"] = f.residual_energy;
  } else {
    j["pair"] = {f.a, f.b};
    j["clearance_m"] = f.clearance_m;
    j["floor_m"] = f.floor_m;
    j["shortfall_m"] = f.shortfall_m;
  }
  return j;
}

std::string PlanWarning(const PlanResult& r) {
  std::string warning;
  if (!r.used_plan) warning = "kept the greedy trajectory: " + r.note;
  if (!r.converged) {
    JoinWarning(std::string("not every waypoint was reached") +
                    (r.greedy_warning.empty() ? "" : " (greedy: " + r.greedy_warning + ")"),
                &warning);
  }
  return warning;
}

}  // namespace

Document PlanDocument(const ControlProblem& control, const PlanResult& r, std::size_t waypoints,
                      const ClearanceSummary& path_clearance) {
  const Model& model = control.forward().model();
  Document doc;
  nlohmann::json& out = doc.json;
  out["model"] = model.name;
  out["converged"] = r.converged;
  out["used"] = r.used_plan ? "plan" : "greedy";
  out["waypoints"] = waypoints;
  out["steps"] = r.steps.size();
  out["iterations"] = r.iterations;
  // How the optimisation stopped and the plan was finished.
  out["stopped_by"] = r.stopped_by;
  out["finishing"] = {{"repaired_rows", r.repaired_rows}, {"inserted_rows", r.inserted_rows}};
  if (r.shortfall.any) out["shortfall"] = ShortfallJson(r.shortfall);
  out["greedy"] = MeasuresJson(r.greedy);
  out["plan"] = MeasuresJson(r.plan);
  out["solve_time_ms"] = r.solve_time_ms;
  out["controls"] = ToJson(control.controls());
  out["end_effector"] = ToJson(control.forward().end_effector());
  AddClearance(model, control.forward().state(), &out, &doc.warnings);
  AddPathClearance(path_clearance, &out);
  const std::string warning = PlanWarning(r);
  doc.Warn(warning);
  return doc;
}

}  // namespace ccma::documents
