// The top level of a model file: its keys, `name` and `description`, and the
// order in which the sections are read (bodies before the joints that name
// them, bases before the actuator check).
#include <string>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

ModelParser::ModelParser(const std::string& source, std::vector<std::string>* warnings)
    : magnitudes_(source), warnings_(warnings), r_(source, warnings, &magnitudes_) {
  model_.source = source;
}

Model ModelParser::Parse(const YAML::Node& root) {
  if (!root.IsDefined() || root.IsNull()) r_.Fail(root, "", "empty model file");
  if (!root.IsMap()) r_.Fail(root, "", "the top level must be a mapping of keys");
  r_.CheckKeys(root, {"name", "description", "bodies", "mobile_bases", "joints", "end_effector", "collision", "obstacles",
               "gravity"},
              "");
  ParseHeader(root);
  const YAML::Node bodies = r_.Sequence(r_.Require(root, "bodies", ""), "bodies",
                                        static_cast<std::size_t>(kMaxBodies), "bodies");
  ParseBodies(bodies);
  // `mobile_bases` may be omitted or [] when joints are actuated (checked below).
  if (YamlReader::Has(root, "mobile_bases")) ParseBases(root["mobile_bases"], bodies.size());
  ParseJoints(r_.Sequence(r_.Require(root, "joints", ""), "joints",
                          static_cast<std::size_t>(kMaxJoints), "joints"));
  if (model_.num_bases() + model_.num_actuated_joints() == 0) {
    r_.Fail(YamlReader::Has(root, "mobile_bases") ? root["mobile_bases"] : root, "mobile_bases",
            "a model needs at least one actuator: a mobile base or a joint with actuated: true");
  }
  ParseEndEffector(r_.Map(r_.Require(root, "end_effector", ""), "end_effector"));
  ParseLoads(root, root["end_effector"]);
  CheckConnected(bodies);
  ParseCollision(root);
  // Only a model that loads has its magnitudes reported.
  if (warnings_ != nullptr) magnitudes_.AppendWarnings(warnings_);
  return std::move(model_);
}

void ModelParser::ParseHeader(const YAML::Node& root) {
  model_.name = r_.Name(r_.Require(root, "name", ""), "name");
  if (!YamlReader::Has(root, "description")) return;
  const YAML::Node description = root["description"];
  if (!description.IsScalar()) r_.Fail(description, "description", "must be a string");
  if (description.Scalar().size() > kMaxDescriptionLength) {
    r_.Fail(description, "description",
            "must be at most " + std::to_string(kMaxDescriptionLength) + " bytes, got " +
                std::to_string(description.Scalar().size()));
  }
  model_.description = description.Scalar();
}

}  // namespace internal
}  // namespace ccma
