#include "documents/design_document.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "analyses/design_objective.h"
#include "documents/json_values.h"

namespace ccma::documents {
namespace {

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

// "reached" (reached_only: a bool per target) or "targets" (reached, error
// [m or rad; -1 where none], min_singular_value, within_limits per target).
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
    if (a != b) {
      points.push_back({{"joint", model.joints[j].name}, {"old_point", ToJson(Eigen::VectorXd(a))},
                        {"new_point", ToJson(Eigen::VectorXd(b))}});
    }
  }
  (*out)["changed_points"] = points;
}

nlohmann::json ObjectiveValueJson(const ObjectiveAtTarget& v) {
  if (!v.defined) return nullptr;
  return {{"value", v.value}, {"limiting", v.limiting}};
}

// "objective": what phase 3 improved (null values where not defined).
nlohmann::json ObjectiveJson(const DesignOptions& options, const DesignResult& result) {
  return {{"name", DesignObjectiveName(options.objective)},
          {"unit", DesignObjectiveUnit(options.objective)},
          {"maximised", IsMaximised(options.objective)},
          {"before", ObjectiveValueJson(result.objective_before)},
          {"after", ObjectiveValueJson(result.objective_after)},
          {"iterations", result.objective_iterations},
          {"stopped", result.objective_message}};
}

}  // namespace

Document DesignDocument(const Model& model, const Model& designed, const DesignParameters& params,
                        const DesignOptions& options, const DesignResult& result,
                        const std::vector<DesignTargetResult>& final_check) {
  const bool converged = ConvergedIn(final_check, options);
  Document doc;
  nlohmann::json& out = doc.json;
  out["model"] = model.name;
  out["converged"] = converged;
  out["reached"] = TargetsJson(final_check, true);
  out["reached_before"] = TargetsJson(result.initial, true);
  out["targets"] = TargetsJson(final_check, false);
  out["iterations"] = result.iterations;
  AddChanges(model, designed, params, result, &out);
  if (options.objective != DesignObjective::kReach) {
    out["objective"] = ObjectiveJson(options, result);
    if (converged && !result.objective_after.defined) {
      const std::string warning = "the " + std::string(DesignObjectiveName(options.objective)) +
                                  " objective is not defined: " + result.objective_after.why;
      out["warning"] = warning;
      doc.warnings.push_back(warning);
    }
  }
  if (!converged) {
    const std::string message = result.message.empty() ? "not every target is reached with margin" : result.message;
    out["warning"] = message;
    doc.warnings.push_back("not converged: " + message);
  }
  return doc;
}

}  // namespace ccma::documents
