#include "documents/import_document.h"

#include "documents/json_values.h"

namespace ccma::documents {

Document ImportDocument(const ImportedRobot& imported, const ImportOptions& options) {
  Document doc;
  nlohmann::json& out = doc.json;
  out = {{"bodies", imported.model.num_bodies()},
         {"joints", static_cast<int>(imported.model.joints.size())},
         {"closures", imported.closures},
         {"actuated", imported.actuated},
         {"controlled", imported.controlled},
         {"controlled_chosen", imported.controlled_chosen},
         {"assembled", true},
         {"residual_energy", imported.residual_energy},
         {"controls", ToJson(imported.model.home_controls())}};
  out["closure_gaps"] = nlohmann::json::array();
  for (const ClosureGap& g : imported.closure_gaps) {
    out["closure_gaps"].push_back({{"name", g.name}, {"gap_m", g.gap_m}, {"gap_rad", g.gap_rad}});
  }
  out["motor_moves"] = nlohmann::json::array();
  for (const MotorMove& m : imported.motor_moves) out["motor_moves"].push_back({{"name", m.name}, {"move", m.move}});
  if (options.collision_radius > 0) {
    out["collision_capsules"] = imported.collision_capsules;
    out["collision_ignored_pairs"] = imported.collision_ignored_pairs;
  }
  doc.warnings = imported.warnings;
  return doc;
}

}  // namespace ccma::documents
