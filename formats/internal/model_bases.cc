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
    KindOf(base).HomeFrame(base, &body.R_WB_home, &body.p_WB_home);
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
  r_.CheckKeys(node, {"name", "type", "actuation", "pose", "wheels", "meshes", "radius", "mass", "com", "inertia", "push_limit", "velocity_limit",
                      "stiffness", "body_height", "body_limits", "footprint"},
               path);
  MobileBase base;
  base.name = AddBodyName(r_.Require(node, "name", path), path + ".name");
  base.body = model_.num_bodies();
  if (YamlReader::Has(node, "type")) {
    const std::string type = r_.String(node["type"], path + ".type");
    if (FindBaseKind(type, &base.type) == nullptr) {
      r_.Fail(node["type"], path + ".type", "unknown base type " + Quote(type) + " (known: " + KnownBaseKinds() + ")");
    }
  }
  CheckTypeKeys(node, path, base.type);
  base.home_pose = r_.Vector3(r_.Require(node, "pose", path), path + ".pose", {"m", "m", "rad"});
  if (base.type == BaseType::kLegged) {
    base.legged = ParseLeggedBody(node, path);
  } else {
    ParseActuation(node, path, &base);
  }
  base.stiffness = ParseBaseStiffness(node, path);
  base.push_limit = ParsePushLimit(node, path);
  base.velocity_limit = ParseBaseVelocityLimit(node, path, base.type);
  if (YamlReader::Has(node, "wheels")) {
    if (base.type == BaseType::kDifferential) {
      base.differential = ParseDifferentialWheels(node["wheels"], path + ".wheels");
    } else {
      base.wheels = ParseWheels(node["wheels"], path + ".wheels");
    }
  }
  return base;
}

// The keys only one base type reads: given on another type, they are a
// mistake (a legged base's `actuation`, an omni base's `body_height`).
void ModelParser::CheckTypeKeys(const YAML::Node& node, const std::string& path, BaseType type) const {
  const bool legged = type == BaseType::kLegged;
  for (const char* key : {"body_height", "body_limits", "footprint"}) {
    if (!legged && YamlReader::Has(node, key)) {
      r_.Fail(node[key], path + "." + key, std::string("only legged bases have ") + key);
    }
  }
  for (const char* key : {"actuation", "wheels"}) {
    if (legged && YamlReader::Has(node, key)) {
      r_.Fail(node[key], path + "." + key, std::string("is not a key of a legged base (all six controls are effective)"));
    }
  }
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
