// `bodies`, and the one namespace that bodies and mobile bases share: every
// name a joint or the end-effector uses is looked up here.
#include <string>

#include "ccma/internal/format.h"
#include "ccma/rotation.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

// Bodies of the passive chain.
void ModelParser::ParseBodies(const YAML::Node& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::string path = Indexed("bodies", i);
    const YAML::Node node = r_.Map(bodies[i], path);
    r_.CheckKeys(node, {"name", "position", "rpy", "meshes", "mass", "com", "inertia"}, path);
    Body body;
    body.name = AddBodyName(r_.Require(node, "name", path), path + ".name");
    body.p_WB_home = r_.Vector3(r_.Require(node, "position", path), path + ".position", "m");
    if (YamlReader::Has(node, "rpy")) {
      body.R_WB_home = RotationFromRpy(r_.Vector3(node["rpy"], path + ".rpy", "rad"));
    }
    if (YamlReader::Has(node, "meshes")) body.meshes = ParseMeshes(node["meshes"], path + ".meshes", body);
    body.inertia = ParseMassProperties(node, path, body);
    model_.bodies.push_back(body);
  }
}

// Declares the body `model_.bodies.size()` under the name at `node`.
std::string ModelParser::AddBodyName(const YAML::Node& node, const std::string& path) {
  const std::string name = r_.Name(node, path);
  if (name == "world") r_.Fail(node, path, "'world' is reserved for the ground");
  const auto it = body_names_.find(name);
  if (it != body_names_.end()) {
    r_.Fail(node, path,
            "duplicate name '" + name + "' (first defined at " + r_.Location(it->second.node) + ")");
  }
  body_names_.emplace(name, NamedBody{model_.num_bodies(), node});
  return name;
}

// The body named at `node`, or kWorld for `world`.
int ModelParser::BodyOrWorldAt(const YAML::Node& node, const std::string& path) const {
  return r_.String(node, path) == "world" ? kWorld : BodyAt(node, path);
}

std::string ModelParser::NameOf(int body) const {
  return body == kWorld ? "world" : model_.bodies[body].name;
}

// The index of the body named at `node`, which must exist.
int ModelParser::BodyAt(const YAML::Node& node, const std::string& path) const {
  const std::string name = r_.String(node, path);
  const auto it = body_names_.find(name);
  if (it == body_names_.end()) r_.Fail(node, path, "unknown body " + Quote(name));
  return it->second.index;
}

}  // namespace internal
}  // namespace ccma
