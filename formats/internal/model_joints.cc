// `joints`: each joint's name, type and the two bodies it connects (its
// geometry, motor and limits are read by model_joint_geometry.cc and
// model_actuation_limits.cc); then the controls of actuated joints, and the
// check that every body hangs from a base or the ground.
#include <set>
#include <string>

#include "ccma/internal/format.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

// Joints of the passive chain.
void ModelParser::ParseJoints(const YAML::Node& joints) {
  components_ = Components(model_.num_bodies());
  JointNames names;  // given names
  std::vector<bool> named(joints.size(), false);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const std::string path = Indexed("joints", j);
    const YAML::Node node = r_.Map(joints[j], path);
    r_.CheckKeys(node, {"type", "between", "point", "axis", "axes", "name", "actuated", "limits", "q_home", "effort_limits", "velocity_limit", "stiffness"}, path);
    if (YamlReader::Has(node, "name")) {
      const std::string name = r_.Name(node["name"], path + ".name");
      const auto it = names.find(name);
      if (it != names.end()) {
        r_.Fail(node["name"], path + ".name",
                "duplicate joint name '" + name + "' (first defined at " + r_.Location(it->second.first) + ")");
      }
      names.emplace(name, std::make_pair(node["name"], j));
      named[j] = true;
    }
    model_.joints.push_back(ParseJoint(node, path));
    model_.joints.back().name = named[j] ? node["name"].Scalar() : "joint" + std::to_string(j);
  }
  // Controls: each base's (three, six for a legged base), then one per
  // actuated joint in file order.
  int control = model_.num_base_controls();
  for (Joint& joint : model_.joints) {
    if (joint.actuated) joint.control = control++;
  }
  CheckDefaultJointNames(names, named);
}

// A joint without a name is called joint<i>; no other joint may take that.
void ModelParser::CheckDefaultJointNames(const JointNames& names, const std::vector<bool>& named) const {
  for (std::size_t j = 0; j < named.size(); ++j) {
    const auto it = named[j] ? names.end() : names.find("joint" + std::to_string(j));
    if (it != names.end()) {
      r_.Fail(it->second.first, Indexed("joints", it->second.second) + ".name",
              "duplicate joint name '" + it->first + "': it is the default name of the unnamed " +
                  Indexed("joints", j));
    }
  }
}

// The joint's type and bodies; its keys are checked by ParseJoints.
Joint ModelParser::ParseJoint(const YAML::Node& node, const std::string& path) {
  Joint joint;
  joint.line = node.Mark().line + 1;
  const YAML::Node type_node = r_.Require(node, "type", path);
  const std::string type = r_.String(type_node, path + ".type");
  static const std::map<std::string, JointType> kTypes = {
      {"revolute", JointType::kRevolute},   {"spherical", JointType::kSpherical},
      {"universal", JointType::kUniversal}, {"prismatic", JointType::kPrismatic},
      {"fixed", JointType::kFixed}};
  const auto type_it = kTypes.find(type);
  if (type_it == kTypes.end()) {
    r_.Fail(type_node, path + ".type",
            "unknown joint type " + Quote(type) + " (known: revolute, spherical, universal, prismatic, fixed)");
  }
  joint.type = type_it->second;

  const YAML::Node between = r_.Require(node, "between", path);
  if (!between.IsSequence() || between.size() != 2) {
    r_.Fail(between, path + ".between", "must be a list of 2 body names");
  }
  joint.body_a = BodyOrWorldAt(between[0], path + ".between[0]");
  joint.body_b = BodyOrWorldAt(between[1], path + ".between[1]");
  if (joint.body_a == joint.body_b) {
    r_.Fail(between, path + ".between", "names the same body '" + NameOf(joint.body_a) + "' twice");
  }
  ParseJointGeometry(node, path, &joint);
  ParseActuationAndLimits(node, path, &joint);
  ParseEffortLimits(node, path, &joint);
  ParseJointVelocityLimit(node, path, &joint);
  ParseJointStiffness(node, path, &joint);
  if (joint.body_a == kWorld || joint.body_b == kWorld) {
    grounded_bodies_.push_back(joint.body_a == kWorld ? joint.body_b : joint.body_a);
  } else {
    components_.Unite(joint.body_a, joint.body_b);
  }
  return joint;
}

// Every body must hang, through joints, from some mobile base or `world`.
void ModelParser::CheckConnected(const YAML::Node& bodies) {
  std::set<int> grounded;
  for (const MobileBase& base : model_.mobile_bases) grounded.insert(components_.Find(base.body));
  for (int body : grounded_bodies_) grounded.insert(components_.Find(body));
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (grounded.count(components_.Find(static_cast<int>(i))) == 0) {
      r_.Fail(bodies[i], Indexed("bodies", i),
              "body '" + model_.bodies[i].name +
                  "' is not connected through joints to any mobile base or to world");
    }
  }
}

}  // namespace internal
}  // namespace ccma
