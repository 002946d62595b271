// `mobile_bases`: each base's name, type, actuation and home pose. A base is
// a body too, appended after the bodies of the passive chain.
#include <string>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "ccma/rotation.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

// Mobile bases: bodies too, appended after the chain's bodies.
void ModelParser::ParseBases(const YAML::Node& bases_node, std::size_t num_bodies) {
  const YAML::Node bases = r_.Sequence(bases_node, "mobile_bases");
  if (num_bodies + bases.size() > static_cast<std::size_t>(kMaxBodies)) {
    r_.Fail(bases, "mobile_bases",
            std::to_string(num_bodies) + " bodies and " + std::to_string(bases.size()) +
                " mobile bases; at most " + std::to_string(kMaxBodies) + " together are allowed");
  }
  for (std::size_t k = 0; k < bases.size(); ++k) {
    const MobileBase base = ParseBase(bases[k], Indexed("mobile_bases", k));
    Body body;
    body.name = base.name;
    body.base_index = model_.num_bases();
    body.p_WB_home = Eigen::Vector3d(base.home_pose.x(), base.home_pose.y(), 0.0);
    body.R_WB_home = RotationZ(base.home_pose.z());
    if (YamlReader::Has(bases[k], "meshes")) {
      body.meshes = ParseMeshes(bases[k]["meshes"], Indexed("mobile_bases", k) + ".meshes", body);
    }
    body.inertia = ParseMassProperties(bases[k], Indexed("mobile_bases", k), body);
    model_.bodies.push_back(body);
    model_.mobile_bases.push_back(base);
    base_radius_given_.push_back(BaseRadius(bases[k], Indexed("mobile_bases", k)));
  }
}

MobileBase ModelParser::ParseBase(const YAML::Node& at, const std::string& path) {
  const YAML::Node node = r_.Map(at, path);
  r_.CheckKeys(node, {"name", "type", "actuation", "pose", "wheels", "meshes", "radius", "mass", "com", "push_limit", "stiffness"}, path);
  MobileBase base;
  base.name = AddBodyName(r_.Require(node, "name", path), path + ".name");
  base.body = model_.num_bodies();
  if (YamlReader::Has(node, "type")) {
    const std::string type = r_.String(node["type"], path + ".type");
    if (type == "differential") {
      base.type = BaseType::kDifferential;
    } else if (type != "omni") {
      r_.Fail(node["type"], path + ".type",
              "unknown base type " + Quote(type) + " (known: omni, differential)");
    }
  }
  ParseActuation(node, path, &base);
  base.push_limit = ParsePushLimit(node, path);
  base.stiffness = ParseBaseStiffness(node, path);
  base.home_pose = r_.Vector3(r_.Require(node, "pose", path), path + ".pose", {"m", "m", "rad"});
  if (YamlReader::Has(node, "wheels")) {
    if (base.type == BaseType::kDifferential) {
      base.differential = ParseDifferentialWheels(node["wheels"], path + ".wheels");
    } else {
      base.wheels = ParseWheels(node["wheels"], path + ".wheels");
    }
  }
  return base;
}

// A differential base's x, y and theta are all controls: complete, and
// `actuation` may be omitted.
void ModelParser::ParseActuation(const YAML::Node& node, const std::string& path, MobileBase* base) const {
  const bool differential = base->type == BaseType::kDifferential;
  const bool given = !differential || YamlReader::Has(node, "actuation");
  const YAML::Node actuation_node = given ? r_.Require(node, "actuation", path) : node;
  const std::string actuation = given ? r_.String(actuation_node, path + ".actuation") : "complete";
  if (actuation == "complete") {
    base->actuation = Actuation::kComplete;
  } else if (actuation == "reduced" && !differential) {
    base->actuation = Actuation::kReduced;
  } else {
    r_.Fail(actuation_node, path + ".actuation",
            "unknown actuation " + Quote(actuation) +
                (differential ? " for a differential base (known: complete)" : " (known: complete, reduced)"));
  }
}

}  // namespace internal
}  // namespace ccma
