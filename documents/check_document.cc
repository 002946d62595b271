#include "documents/check_document.h"

#include <algorithm>
#include <string>
#include <vector>

#include "ccma/end_effector.h"
#include "ccma/internal/format.h"
#include "documents/json_values.h"

namespace ccma::documents {
namespace {

// The counts and the mobility at home (docs/cli.md, `ccma check`).
nlohmann::json CheckJson(const Model& model, const MobilityReport& mobility, bool assembled) {
  nlohmann::json out;
  out["model"] = model.name;
  out["bodies"] = model.num_bodies();
  out["mobile_bases"] = model.num_bases();
  out["joints"] = model.joints.size();
  out["state_size"] = model.state_size();
  out["controls"] = model.num_controls();
  out["effective_controls"] = model.effective_control_indices().size();
  out["constraints"] = mobility.constraint_rows;
  out["rigid_with_controls_fixed"] = mobility.rigid_with_controls_fixed;
  out["end_effector_dof"] = mobility.end_effector_dof;
  out["end_effector_dof_nonholonomic"] = mobility.end_effector_dof_nonholonomic;
  out["assembled_at_home"] = assembled;
  out["constraint_rank"] = mobility.constraint_rank;
  out["dof_with_controls_fixed"] = mobility.dof_with_controls_fixed;
  out["dof_with_controls_free"] = mobility.dof_with_controls_free;
  out["smallest_singular_value"] = mobility.smallest_singular_value;
  out["energy_at_home"] = mobility.energy;
  out["independent_controls"] = mobility.independent_controls;
  nlohmann::json controlled = nlohmann::json::array();
  for (int c = 0; c < 6; ++c) {
    if (model.end_effector.controlled[c]) controlled.push_back(kEndEffectorComponentNames[c]);
  }
  out["controlled"] = controlled;
  nlohmann::json motions = nlohmann::json::array();
  for (const FreeMotion& motion : mobility.free_motions) {
    nlohmann::json bodies = nlohmann::json::array();
    for (const int b : motion.bodies) bodies.push_back(model.bodies[b].name);
    nlohmann::json joints = nlohmann::json::array();
    for (const int j : motion.joints) joints.push_back(model.joints[j].name);
    motions.push_back({{"bodies", bodies}, {"joints", joints}});
  }
  out["free_motions"] = motions;
  return out;
}

// "motion 1 moves post2, link2; motion 2 moves link2".
std::string FreeMotionText(const Model& model, const std::vector<FreeMotion>& motions) {
  std::string text;
  for (size_t m = 0; m < motions.size(); ++m) {
    text += (m ? "; motion " : "motion ") + std::to_string(m + 1) + " moves ";
    for (size_t i = 0; i < motions[m].bodies.size(); ++i) {
      text += (i ? ", " : "") + model.bodies[motions[m].bodies[i]].name;
    }
    for (size_t i = 0; i < motions[m].joints.size(); ++i) {
      text += (i ? ", " : " (joints ") + model.joints[motions[m].joints[i]].name;
    }
    if (!motions[m].joints.empty()) text += ")";
  }
  return text;
}

// The end of the free-motion warning: what the motions do to the
// end-effector, and so whether simulation and control are well-posed.
std::string FreeMotionVerdict(const Model& model, FreeMotionReach reach) {
  if (reach == FreeMotionReach::kIdle) {
    return "; none moves the end-effector (idle motions, docs/numerics.md): control resolves them, simulation "
           "leaves them where they are";
  }
  if (reach == FreeMotionReach::kControlled) return "; simulation and control are ill-posed";
  std::string controlled, free;
  for (int c = 0; c < 6; ++c) {
    std::string& list = model.end_effector.controlled[c] ? controlled : free;
    list += (list.empty() ? "" : ", ") + std::string(kEndEffectorComponentNames[c]);
  }
  return "; none moves what the model controls (" + controlled + "), which the controls determine; they move only "
         "the end-effector's uncontrolled components (" + free + "), which simulation leaves where they are";
}

// What a user would not expect of the mechanism, one sentence each.
nlohmann::json CheckWarnings(const Model& model, const MobilityReport& mobility, bool assembled) {
  const ForwardOptions defaults;
  int controlled_count = 0;
  for (int c = 0; c < 6; ++c) controlled_count += model.end_effector.controlled[c] ? 1 : 0;
  nlohmann::json warnings = nlohmann::json::array();
  if (!mobility.rigid_with_controls_fixed) {
    const FreeMotionReach reach = ReachOfFreeMotions(model, State::Home(model), mobility);
    warnings.push_back("not rigid with its controls fixed: " + std::to_string(mobility.dof_with_controls_fixed) +
                       " free motion(s) remain (smallest singular value of dC/ds " +
                       FormatG(mobility.smallest_singular_value) + "): " +
                       (mobility.free_motions_listed ? FreeMotionText(model, mobility.free_motions)
                                                     : std::string("too many to list them")) +
                       FreeMotionVerdict(model, reach));
  }
  if (!assembled) {
    warnings.push_back("not assembled at home: E = " + FormatG(mobility.energy) + " m^2 (above " +
                       FormatG(defaults.assembly_tolerance) + "); check the joint points and axes");
  }
  if (mobility.end_effector_dof < controlled_count) {
    warnings.push_back("the controls move only " + std::to_string(mobility.end_effector_dof) +
                       " end-effector DOF at home, fewer than the " + std::to_string(controlled_count) +
                       " controlled components");
  }
  const int effective = static_cast<int>(model.effective_control_indices().size());
  if (ClassifyControls(model, mobility) == ControlDependence::kDependent) {
    warnings.push_back("only " + std::to_string(mobility.independent_controls) + " of the " +
                       std::to_string(effective) + " effective controls are independent at home: most control "
                       "vectors cannot be assembled (ccma simulate --controls=... says not assembled); control and "
                       "trajectory keep the controls consistent");
  }
  if (mobility.end_effector_dof_nonholonomic < std::min(controlled_count, mobility.end_effector_dof)) {
    warnings.push_back("the differential bases, which cannot move sideways, leave the end-effector only " +
                       std::to_string(mobility.end_effector_dof_nonholonomic) + " instantaneous DOF at home, fewer than the " +
                       std::to_string(controlled_count) + " controlled components: most paths are infeasible");
  }
  return warnings;
}

}  // namespace

Document CheckDocument(const Model& model) {
  const State home = State::Home(model);
  const MobilityReport mobility = AnalyzeMobility(model, home, model.home_controls());
  const bool assembled = mobility.energy < ForwardOptions().assembly_tolerance;
  Document doc;
  doc.json = CheckJson(model, mobility, assembled);
  const nlohmann::json warnings = CheckWarnings(model, mobility, assembled);
  if (!warnings.empty()) {
    doc.json["warnings"] = warnings;
    for (const auto& w : warnings) doc.warnings.push_back(w.get<std::string>());
  }
  AddClearance(model, home, &doc.json, &doc.warnings);  // at home
  if (!doc.warnings.empty()) {
    std::string joined;
    for (const std::string& w : doc.warnings) JoinWarning(w, &joined);
    doc.json["warning"] = joined;
  }
  const int effective = static_cast<int>(model.effective_control_indices().size());
  if (ClassifyControls(model, mobility) == ControlDependence::kRedundantByDesign) {
    doc.notes.push_back("over-actuated by design: " + std::to_string(mobility.independent_controls) + " of the " +
                        std::to_string(effective) + " effective controls are independent at home (redundant "
                        "actuation: the controls are tied by the mechanism they drive); control and trajectory keep "
                        "the controls consistent, ccma simulate --controls=... needs consistent ones");
    doc.json["note"] = doc.notes.back();
  }
  return doc;
}

}  // namespace ccma::documents
