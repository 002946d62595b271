#include "ccma/model_loader.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <regex>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "ccma/rotation.h"

namespace ccma {
namespace {

// Cosine above which universal axes count as not perpendicular.
constexpr double kPerpendicularTolerance = 1e-6;

// Reads typed values out of YAML nodes, turning every problem into a
// ModelError that says file:line: key: what.
class Reader {
 public:
  Reader(std::string source, std::vector<std::string>* warnings)
      : source_(std::move(source)), warnings_(warnings) {}

  [[noreturn]] void Fail(const YAML::Node& at, const std::string& key,
                         const std::string& what) const {
    std::ostringstream os;
    os << source_;
    if (at.IsDefined() && at.Mark().line >= 0) os << ":" << at.Mark().line + 1;
    os << ": " << (key.empty() ? "" : key + ": ") << what;
    throw ModelError(os.str());
  }

  // The value of `key` in `map`, which must be present.
  YAML::Node Require(const YAML::Node& map, const std::string& key,
                     const std::string& path) const {
    const YAML::Node value = map[key];
    if (!value.IsDefined() || value.IsNull()) {
      Fail(map, Join(path, key), "missing required key");
    }
    return value;
  }

  void WarnUnknownKeys(const YAML::Node& map, const std::set<std::string>& known,
                       const std::string& path) const {
    if (warnings_ == nullptr) return;
    for (const auto& entry : map) {
      const std::string key = entry.first.Scalar();
      if (known.count(key) == 0) {
        warnings_->push_back(Location(entry.first) + ": " + Join(path, key) +
                             ": unknown key, ignored");
      }
    }
  }

  YAML::Node Map(const YAML::Node& node, const std::string& path) const {
    if (!node.IsMap()) Fail(node, path, "must be a mapping");
    return node;
  }

  YAML::Node Sequence(const YAML::Node& node, const std::string& path) const {
    if (!node.IsSequence()) Fail(node, path, "must be a list");
    return node;
  }

  std::string String(const YAML::Node& node, const std::string& path) const {
    if (!node.IsScalar() || node.Scalar().empty()) {
      Fail(node, path, "must be a non-empty string");
    }
    return node.Scalar();
  }

  double Number(const YAML::Node& node, const std::string& path) const {
    if (!node.IsScalar()) Fail(node, path, "must be a number");
    double value = 0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      Fail(node, path, "must be a number, got '" + node.Scalar() + "'");
    }
    if (!std::isfinite(value)) Fail(node, path, "must be a finite number");
    return value;
  }

  Eigen::Vector3d Vector3(const YAML::Node& node, const std::string& path) const {
    if (!node.IsSequence() || node.size() != 3) {
      Fail(node, path, "must be a list of 3 numbers");
    }
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
      v[i] = Number(node[i], path + "[" + std::to_string(i) + "]");
    }
    return v;
  }

  // A unit vector from a non-zero 3-vector.
  Eigen::Vector3d Axis(const YAML::Node& node, const std::string& path) const {
    const Eigen::Vector3d v = Vector3(node, path);
    if (v.norm() < 1e-12) Fail(node, path, "must not be the zero vector");
    return v.normalized();
  }

  std::string Location(const YAML::Node& node) const {
    std::string where = source_;
    if (node.Mark().line >= 0) where += ":" + std::to_string(node.Mark().line + 1);
    return where;
  }

  static std::string Join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

 private:
  std::string source_;
  std::vector<std::string>* warnings_;
};

std::string Indexed(const std::string& list, size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

// Union-find over body indices, to find bodies no joint ties to a base.
class Components {
 public:
  explicit Components(int n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int Find(int i) { return parent_[i] == i ? i : parent_[i] = Find(parent_[i]); }
  void Unite(int a, int b) { parent_[Find(a)] = Find(b); }

 private:
  std::vector<int> parent_;
};

Model Parse(const YAML::Node& root, const std::string& source,
            std::vector<std::string>* warnings) {
  const Reader r(source, warnings);
  if (!root.IsDefined() || root.IsNull()) r.Fail(root, "", "empty model file");
  if (!root.IsMap()) r.Fail(root, "", "the top level must be a mapping of keys");
  r.WarnUnknownKeys(root, {"name", "description", "bodies", "mobile_bases", "joints",
                           "end_effector"},
                    "");

  Model model;
  model.source = source;
  model.name = r.String(r.Require(root, "name", ""), "name");
  if (!std::regex_match(model.name, std::regex("[A-Za-z0-9_-]+"))) {
    r.Fail(root["name"], "name", "'" + model.name + "' must match [A-Za-z0-9_-]+");
  }
  if (root["description"].IsDefined() && !root["description"].IsNull()) {
    if (!root["description"].IsScalar()) {
      r.Fail(root["description"], "description", "must be a string");
    }
    model.description = root["description"].Scalar();
  }

  std::map<std::string, YAML::Node> name_nodes;  // for duplicate detection
  auto add_name = [&](const YAML::Node& node, const std::string& path) {
    const std::string body_name = r.String(node, path);
    const auto it = name_nodes.find(body_name);
    if (it != name_nodes.end()) {
      r.Fail(node, path,
             "duplicate name '" + body_name + "' (first defined at " +
                 r.Location(it->second) + ")");
    }
    name_nodes.emplace(body_name, node);
    return body_name;
  };

  // Bodies of the passive chain.
  const YAML::Node bodies = r.Sequence(r.Require(root, "bodies", ""), "bodies");
  for (size_t i = 0; i < bodies.size(); ++i) {
    const std::string path = Indexed("bodies", i);
    const YAML::Node node = r.Map(bodies[i], path);
    r.WarnUnknownKeys(node, {"name", "position", "rpy"}, path);
    Body body;
    body.name = add_name(r.Require(node, "name", path), path + ".name");
    body.p_WB_home = r.Vector3(r.Require(node, "position", path), path + ".position");
    if (node["rpy"].IsDefined() && !node["rpy"].IsNull()) {
      body.R_WB_home = RotationFromRpy(r.Vector3(node["rpy"], path + ".rpy"));
    }
    model.bodies.push_back(body);
  }

  // Mobile bases: bodies too, appended after the chain's bodies.
  const YAML::Node bases =
      r.Sequence(r.Require(root, "mobile_bases", ""), "mobile_bases");
  if (bases.size() == 0) r.Fail(bases, "mobile_bases", "a model needs at least one mobile base");
  for (size_t k = 0; k < bases.size(); ++k) {
    const std::string path = Indexed("mobile_bases", k);
    const YAML::Node node = r.Map(bases[k], path);
    r.WarnUnknownKeys(node, {"name", "type", "actuation", "pose", "wheels"}, path);
    MobileBase base;
    base.name = add_name(r.Require(node, "name", path), path + ".name");
    if (node["type"].IsDefined() && !node["type"].IsNull()) {
      const std::string type = r.String(node["type"], path + ".type");
      if (type != "omni") {
        r.Fail(node["type"], path + ".type",
               "unknown base type '" + type + "' (known: omni)");
      }
    }
    const YAML::Node actuation_node = r.Require(node, "actuation", path);
    const std::string actuation = r.String(actuation_node, path + ".actuation");
    if (actuation == "complete") {
      base.actuation = Actuation::kComplete;
    } else if (actuation == "reduced") {
      base.actuation = Actuation::kReduced;
    } else {
      r.Fail(actuation_node, path + ".actuation",
             "unknown actuation '" + actuation + "' (known: complete, reduced)");
    }
    base.home_pose = r.Vector3(r.Require(node, "pose", path), path + ".pose");
    if (node["wheels"].IsDefined() && !node["wheels"].IsNull()) {
      const YAML::Node wheels = r.Sequence(node["wheels"], path + ".wheels");
      base.wheels.clear();
      for (size_t i = 0; i < wheels.size(); ++i) {
        const std::string wpath = Indexed(path + ".wheels", i);
        const YAML::Node w = r.Map(wheels[i], wpath);
        r.WarnUnknownKeys(w, {"angle", "distance", "radius", "mounting", "roller"}, wpath);
        Wheel wheel;
        wheel.angle = r.Number(r.Require(w, "angle", wpath), wpath + ".angle");
        wheel.distance = r.Number(r.Require(w, "distance", wpath), wpath + ".distance");
        wheel.radius = r.Number(r.Require(w, "radius", wpath), wpath + ".radius");
        if (w["mounting"].IsDefined()) wheel.mounting = r.Number(w["mounting"], wpath + ".mounting");
        if (w["roller"].IsDefined()) wheel.roller = r.Number(w["roller"], wpath + ".roller");
        base.wheels.push_back(wheel);
      }
      try {
        OmniWheelKinematics check(base.wheels);
      } catch (const std::invalid_argument& e) {
        r.Fail(wheels, path + ".wheels", e.what());
      }
    }
    base.body = static_cast<int>(model.bodies.size());
    Body body;
    body.name = base.name;
    body.base_index = static_cast<int>(model.mobile_bases.size());
    body.p_WB_home = Eigen::Vector3d(base.home_pose.x(), base.home_pose.y(), 0.0);
    body.R_WB_home = RotationZ(base.home_pose.z());
    model.bodies.push_back(body);
    model.mobile_bases.push_back(base);
  }

  // Joints of the passive chain.
  const YAML::Node joints = r.Sequence(r.Require(root, "joints", ""), "joints");
  Components components(model.num_bodies());
  for (size_t j = 0; j < joints.size(); ++j) {
    const std::string path = Indexed("joints", j);
    const YAML::Node node = r.Map(joints[j], path);
    r.WarnUnknownKeys(node, {"type", "between", "point", "axis", "axes", "name"}, path);
    Joint joint;
    joint.line = node.Mark().line + 1;
    const YAML::Node type_node = r.Require(node, "type", path);
    const std::string type = r.String(type_node, path + ".type");
    static const std::map<std::string, JointType> kTypes = {
        {"revolute", JointType::kRevolute},   {"spherical", JointType::kSpherical},
        {"universal", JointType::kUniversal}, {"prismatic", JointType::kPrismatic},
        {"fixed", JointType::kFixed}};
    const auto type_it = kTypes.find(type);
    if (type_it == kTypes.end()) {
      r.Fail(type_node, path + ".type",
             "unknown joint type '" + type +
                 "' (known: revolute, spherical, universal, prismatic, fixed)");
    }
    joint.type = type_it->second;

    const YAML::Node between = r.Require(node, "between", path);
    if (!between.IsSequence() || between.size() != 2) {
      r.Fail(between, path + ".between", "must be a list of 2 body names");
    }
    int ends[2];
    for (int e = 0; e < 2; ++e) {
      const std::string end_path = path + ".between[" + std::to_string(e) + "]";
      const std::string end_name = r.String(between[e], end_path);
      ends[e] = model.FindBody(end_name);
      if (ends[e] < 0) r.Fail(between[e], end_path, "unknown body '" + end_name + "'");
    }
    if (ends[0] == ends[1]) {
      r.Fail(between, path + ".between",
             "names the same body '" + model.bodies[ends[0]].name + "' twice");
    }
    joint.body_a = ends[0];
    joint.body_b = ends[1];
    const Body& A = model.bodies[ends[0]];
    const Body& B = model.bodies[ends[1]];

    const Eigen::Vector3d p_W = r.Vector3(r.Require(node, "point", path), path + ".point");
    joint.p_A = A.R_WB_home.transpose() * (p_W - A.p_WB_home);
    joint.p_B = B.R_WB_home.transpose() * (p_W - B.p_WB_home);

    if (joint.type == JointType::kRevolute || joint.type == JointType::kPrismatic) {
      const Eigen::Vector3d a_W = r.Axis(r.Require(node, "axis", path), path + ".axis");
      joint.a_A = A.R_WB_home.transpose() * a_W;
      joint.a_B = B.R_WB_home.transpose() * a_W;
    }
    if (joint.type == JointType::kUniversal) {
      const YAML::Node axes = r.Require(node, "axes", path);
      if (!axes.IsSequence() || axes.size() != 2) {
        r.Fail(axes, path + ".axes", "must be a list of 2 axes");
      }
      const Eigen::Vector3d a_W = r.Axis(axes[0], path + ".axes[0]");
      const Eigen::Vector3d b_W = r.Axis(axes[1], path + ".axes[1]");
      if (std::abs(a_W.dot(b_W)) > kPerpendicularTolerance) {
        r.Fail(axes, path + ".axes",
               "the two axes must be perpendicular at home (cosine " +
                   std::to_string(a_W.dot(b_W)) + ")");
      }
      joint.a_A = A.R_WB_home.transpose() * a_W;
      joint.b_B = B.R_WB_home.transpose() * b_W;
    }
    if (joint.type == JointType::kFixed || joint.type == JointType::kPrismatic) {
      joint.d1_A = A.R_WB_home.transpose() * Eigen::Vector3d::UnitX();
      joint.d1_B = B.R_WB_home.transpose() * Eigen::Vector3d::UnitX();
      joint.d2_A = A.R_WB_home.transpose() * Eigen::Vector3d::UnitY();
      joint.d2_B = B.R_WB_home.transpose() * Eigen::Vector3d::UnitY();
    }
    components.Unite(ends[0], ends[1]);
    model.joints.push_back(joint);
  }

  // End-effector.
  const YAML::Node ee = r.Map(r.Require(root, "end_effector", ""), "end_effector");
  r.WarnUnknownKeys(ee, {"body", "point", "controlled"}, "end_effector");
  const YAML::Node ee_body = r.Require(ee, "body", "end_effector");
  const std::string ee_name = r.String(ee_body, "end_effector.body");
  model.end_effector.body = model.FindBody(ee_name);
  if (model.end_effector.body < 0) {
    r.Fail(ee_body, "end_effector.body", "unknown body '" + ee_name + "'");
  }
  const Body& ee_frame = model.bodies[model.end_effector.body];
  model.end_effector.p_W_home =
      r.Vector3(r.Require(ee, "point", "end_effector"), "end_effector.point");
  model.end_effector.p_B =
      ee_frame.R_WB_home.transpose() * (model.end_effector.p_W_home - ee_frame.p_WB_home);
  const YAML::Node controlled =
      r.Sequence(r.Require(ee, "controlled", "end_effector"), "end_effector.controlled");
  if (controlled.size() == 0) {
    r.Fail(controlled, "end_effector.controlled", "must name at least one component");
  }
  for (size_t c = 0; c < controlled.size(); ++c) {
    const std::string path = Indexed("end_effector.controlled", c);
    const std::string component = r.String(controlled[c], path);
    int index = -1;
    for (int k = 0; k < 6; ++k) {
      if (component == kEndEffectorComponentNames[k]) index = k;
    }
    if (index < 0) {
      r.Fail(controlled[c], path,
             "unknown component '" + component + "' (known: x y z roll pitch yaw)");
    }
    if (model.end_effector.controlled[index]) {
      r.Fail(controlled[c], path, "component '" + component + "' listed twice");
    }
    model.end_effector.controlled[index] = true;
  }

  // Every body must hang, through joints, from some mobile base.
  std::set<int> grounded;
  for (const MobileBase& base : model.mobile_bases) grounded.insert(components.Find(base.body));
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (grounded.count(components.Find(static_cast<int>(i))) == 0) {
      r.Fail(bodies[i], Indexed("bodies", i),
             "body '" + model.bodies[i].name +
                 "' is not connected through joints to any mobile base");
    }
  }
  return model;
}

}  // namespace

Model LoadModelFromString(const std::string& text, const std::string& source_name,
                          std::vector<std::string>* warnings) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    std::ostringstream os;
    os << source_name;
    if (e.mark.line >= 0) os << ":" << e.mark.line + 1;
    os << ": not valid YAML: " << e.msg;
    throw ModelError(os.str());
  }
  try {
    return Parse(root, source_name, warnings);
  } catch (const YAML::Exception& e) {  // a conversion we did not foresee
    std::ostringstream os;
    os << source_name;
    if (e.mark.line >= 0) os << ":" << e.mark.line + 1;
    os << ": " << e.msg;
    throw ModelError(os.str());
  }
}

Model LoadModel(const std::string& path, std::vector<std::string>* warnings) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw ModelError(path + ": is a directory, not a model file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError(path + ": cannot open the model file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ModelError(path + ": cannot read the model file");
  return LoadModelFromString(text.str(), path, warnings);
}

}  // namespace ccma
