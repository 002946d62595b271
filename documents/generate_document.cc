#include "documents/generate_document.h"

#include <stdexcept>

#include "formats/model_generator.h"
#include "formats/model_loader.h"

namespace ccma::documents {

bool GenerateSettings::IsValid(std::string* why) const {
  if (kind != "ccma" && kind != "stewart_gough" && kind != "legged") {
    *why = "--kind must be ccma, stewart_gough or legged";
  } else if (agents < 3) {
    *why = "--agents must be an integer >= 3";
  } else if (agents > 1000) {
    *why = "--agents must be at most 1000";
  } else if (kind == "stewart_gough" && agents < 6) {
    *why = "--kind=stewart_gough needs --agents >= 6";
  } else {
    return true;
  }
  return false;
}

Generated GenerateModel(const GenerateSettings& settings, const std::string& source) {
  if (std::string why; !settings.IsValid(&why)) throw std::invalid_argument(why);
  Generated out;
  if (settings.kind == "legged") {
    LeggedOptions options;
    options.agents = settings.agents;
    out.text = GenerateLeggedModel(options);
  } else {
    StewartOptions options;
    options.agents = settings.agents;
    out.text = settings.kind == "ccma" ? GenerateStewartModel(options) : GenerateStewartGoughModel(options);
  }
  out.model = LoadModelFromString(out.text, source);
  const Model& m = out.model;
  out.document.json = {{"model", m.name},
                       {"agents", m.num_bases()},
                       {"actuated_joints", m.num_actuated_joints()},
                       {"bodies", m.num_bodies()},
                       {"state_size", m.state_size()},
                       {"controls", m.num_controls()}};
  return out;
}

}  // namespace ccma::documents
