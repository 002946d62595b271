#include "formats/model_loader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <unordered_map>

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include "ccma/limits.h"
#include "ccma/internal/format.h"
#include "ccma/rotation.h"

namespace ccma {
namespace {

// Cosine above which universal axes count as not perpendicular.
constexpr double kPerpendicularTolerance = 1e-6;
// Axes shorter than this are "the zero vector".
constexpr double kMinAxisNorm = 1e-12;
// Flow collections ([...], {...}) nested deeper than this are rejected before
// yaml-cpp sees them. yaml-cpp 0.7 itself stops any nesting (flow or block)
// with YAML::DeepRecursion after a few hundred levels, but says only "bad file".
constexpr int kMaxFlowNesting = 256;
// Names: 1 to kMaxNameLength characters from [A-Za-z0-9_-].
bool IsName(const std::string& text) {
  if (text.empty() || text.size() > kMaxNameLength) return false;
  for (const char c : text) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

// "1-64 characters from [A-Za-z0-9_-]".
std::string NameRule() {
  return "1-" + std::to_string(kMaxNameLength) + " characters from [A-Za-z0-9_-]";
}

std::string Indexed(const std::string& list, std::size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

// Reads typed values out of YAML nodes, turning every problem into a
// ModelError that says file:line: key: what.
class Reader {
 public:
  Reader(std::string source, std::vector<std::string>* warnings)
      : source_(std::move(source)), warnings_(warnings) {}

  const std::string& source() const { return source_; }

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

  // Whether the optional `key` of `map` is given (present and not null).
  static bool Has(const YAML::Node& map, const std::string& key) {
    const YAML::Node value = map[key];
    return value.IsDefined() && !value.IsNull();
  }

  void WarnUnknownKeys(const YAML::Node& map, const std::set<std::string>& known,
                       const std::string& path) const {
    if (warnings_ == nullptr) return;
    for (const auto& entry : map) {
      const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
      if (known.count(key) == 0) {
        warnings_->push_back(Location(entry.first) + ": " + Join(path, Printable(key)) +
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

  // A list of at most `max` entries; `what` names them in the message.
  YAML::Node Sequence(const YAML::Node& node, const std::string& path, std::size_t max,
                      const std::string& what) const {
    Sequence(node, path);
    if (node.size() > max) {
      Fail(node, path, std::to_string(node.size()) + " " + what + "; at most " +
                           std::to_string(max) + " are allowed");
    }
    return node;
  }

  std::string String(const YAML::Node& node, const std::string& path) const {
    if (!node.IsScalar() || node.Scalar().empty()) {
      Fail(node, path, "must be a non-empty string");
    }
    return node.Scalar();
  }

  // A name: 1 to kMaxNameLength characters from [A-Za-z0-9_-].
  std::string Name(const YAML::Node& node, const std::string& path) const {
    if (!node.IsScalar()) Fail(node, path, "must be a name of " + NameRule());
    const std::string& name = node.Scalar();
    if (!IsName(name)) Fail(node, path, Quote(name) + " must be " + NameRule());
    return name;
  }

  // A finite number in [-kMaxMagnitude, kMaxMagnitude]; `unit` is named in
  // the message ("m", "rad", ...; "" for none).
  double Number(const YAML::Node& node, const std::string& path, const char* unit) const {
    if (!node.IsScalar()) Fail(node, path, "must be a number");
    double value = 0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      Fail(node, path, "must be a number, got " + Quote(node.Scalar()));
    }
    if (!std::isfinite(value)) Fail(node, path, "must be a finite number");
    if (!(std::abs(value) <= kMaxMagnitude)) {
      const std::string unit_text = *unit == '\0' ? "" : std::string(" (") + unit + ")";
      Fail(node, path, Quote(node.Scalar()) + " must lie in [" + FormatG(-kMaxMagnitude) + ", " +
                           FormatG(kMaxMagnitude) + "]" + unit_text);
    }
    return value;
  }

  // Three numbers; `units` names each component's unit.
  Eigen::Vector3d Vector3(const YAML::Node& node, const std::string& path,
                          const std::array<const char*, 3>& units) const {
    if (!node.IsSequence() || node.size() != 3) {
      Fail(node, path, "must be a list of 3 numbers");
    }
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = Number(node[i], Indexed(path, i), units[i]);
    return v;
  }

  Eigen::Vector3d Vector3(const YAML::Node& node, const std::string& path,
                          const char* unit) const {
    return Vector3(node, path, {unit, unit, unit});
  }

  // A unit vector from a non-zero 3-vector. Scaled by its largest component
  // first, so neither huge nor tiny components overflow or underflow.
  Eigen::Vector3d Axis(const YAML::Node& node, const std::string& path) const {
    const Eigen::Vector3d v = Vector3(node, path, "unitless");
    const double scale = v.cwiseAbs().maxCoeff();
    if (!(scale > 0)) Fail(node, path, "must not be the zero vector");
    const Eigen::Vector3d scaled = v / scale;
    const double norm = scaled.norm();  // in [1, sqrt(3)]
    if (!(scale * norm >= kMinAxisNorm)) Fail(node, path, "must not be the zero vector");
    return scaled / norm;
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

// Union-find over body indices, to find bodies no joint ties to a base.
// Iterative, with union by size: no recursion however long the chain.
class Components {
 public:
  explicit Components(int n) : parent_(n), size_(n, 1) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int Find(int i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];  // path halving
      i = parent_[i];
    }
    return i;
  }
  void Unite(int a, int b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<int> parent_;
  std::vector<int> size_;
};

// Turns a YAML tree into a Model, one section at a time.
class Parser {
 public:
  Parser(const std::string& source, std::vector<std::string>* warnings)
      : r_(source, warnings) {
    model_.source = source;
  }

  Model Parse(const YAML::Node& root) {
    if (!root.IsDefined() || root.IsNull()) r_.Fail(root, "", "empty model file");
    if (!root.IsMap()) r_.Fail(root, "", "the top level must be a mapping of keys");
    r_.WarnUnknownKeys(root, {"name", "description", "bodies", "mobile_bases", "joints",
                              "end_effector"},
                       "");
    ParseHeader(root);
    const YAML::Node bodies = r_.Sequence(r_.Require(root, "bodies", ""), "bodies",
                                          static_cast<std::size_t>(kMaxBodies), "bodies");
    ParseBodies(bodies);
    // `mobile_bases` may be omitted or [] when joints are actuated (checked below).
    if (Reader::Has(root, "mobile_bases")) ParseBases(root["mobile_bases"], bodies.size());
    ParseJoints(r_.Sequence(r_.Require(root, "joints", ""), "joints",
                            static_cast<std::size_t>(kMaxJoints), "joints"));
    if (model_.num_bases() + model_.num_actuated_joints() == 0) {
      r_.Fail(Reader::Has(root, "mobile_bases") ? root["mobile_bases"] : root, "mobile_bases",
              "a model needs at least one actuator: a mobile base or a joint with actuated: true");
    }
    ParseEndEffector(r_.Map(r_.Require(root, "end_effector", ""), "end_effector"));
    CheckConnected(bodies);
    return std::move(model_);
  }

 private:
  struct NamedBody {
    int index;
    YAML::Node node;  // where it was declared, for messages
  };

  void ParseHeader(const YAML::Node& root) {
    model_.name = r_.Name(r_.Require(root, "name", ""), "name");
    if (!Reader::Has(root, "description")) return;
    const YAML::Node description = root["description"];
    if (!description.IsScalar()) r_.Fail(description, "description", "must be a string");
    if (description.Scalar().size() > kMaxDescriptionLength) {
      r_.Fail(description, "description",
              "must be at most " + std::to_string(kMaxDescriptionLength) + " bytes, got " +
                  std::to_string(description.Scalar().size()));
    }
    model_.description = description.Scalar();
  }

  // Declares the body `model_.bodies.size()` under the name at `node`.
  std::string AddBodyName(const YAML::Node& node, const std::string& path) {
    const std::string name = r_.Name(node, path);
    if (name == "world") r_.Fail(node, path, "'world' is reserved for the ground");
    const auto it = body_names_.find(name);
    if (it != body_names_.end()) {
      r_.Fail(node, path,
              "duplicate name '" + name + "' (first defined at " +
                  r_.Location(it->second.node) + ")");
    }
    body_names_.emplace(name, NamedBody{model_.num_bodies(), node});
    return name;
  }

  // The body named at `node`, or kWorld for `world`.
  int BodyOrWorldAt(const YAML::Node& node, const std::string& path) const {
    return r_.String(node, path) == "world" ? kWorld : BodyAt(node, path);
  }

  std::string NameOf(int body) const { return body == kWorld ? "world" : model_.bodies[body].name; }

  // The index of the body named at `node`, which must exist.
  int BodyAt(const YAML::Node& node, const std::string& path) const {
    const std::string name = r_.String(node, path);
    const auto it = body_names_.find(name);
    if (it == body_names_.end()) r_.Fail(node, path, "unknown body " + Quote(name));
    return it->second.index;
  }

  // Bodies of the passive chain.
  void ParseBodies(const YAML::Node& bodies) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const std::string path = Indexed("bodies", i);
      const YAML::Node node = r_.Map(bodies[i], path);
      r_.WarnUnknownKeys(node, {"name", "position", "rpy"}, path);
      Body body;
      body.name = AddBodyName(r_.Require(node, "name", path), path + ".name");
      body.p_WB_home = r_.Vector3(r_.Require(node, "position", path), path + ".position", "m");
      if (Reader::Has(node, "rpy")) {
        body.R_WB_home = RotationFromRpy(r_.Vector3(node["rpy"], path + ".rpy", "rad"));
      }
      model_.bodies.push_back(body);
    }
  }

  // Mobile bases: bodies too, appended after the chain's bodies.
  void ParseBases(const YAML::Node& bases_node, std::size_t num_bodies) {
    const YAML::Node bases = r_.Sequence(bases_node, "mobile_bases");
    if (num_bodies + bases.size() > static_cast<std::size_t>(kMaxBodies)) {
      r_.Fail(bases, "mobile_bases",
              std::to_string(num_bodies) + " bodies and " + std::to_string(bases.size()) +
                  " mobile bases; at most " + std::to_string(kMaxBodies) +
                  " together are allowed");
    }
    for (std::size_t k = 0; k < bases.size(); ++k) {
      const MobileBase base = ParseBase(bases[k], Indexed("mobile_bases", k));
      Body body;
      body.name = base.name;
      body.base_index = model_.num_bases();
      body.p_WB_home = Eigen::Vector3d(base.home_pose.x(), base.home_pose.y(), 0.0);
      body.R_WB_home = RotationZ(base.home_pose.z());
      model_.bodies.push_back(body);
      model_.mobile_bases.push_back(base);
    }
  }

  MobileBase ParseBase(const YAML::Node& at, const std::string& path) {
    const YAML::Node node = r_.Map(at, path);
    r_.WarnUnknownKeys(node, {"name", "type", "actuation", "pose", "wheels"}, path);
    MobileBase base;
    base.name = AddBodyName(r_.Require(node, "name", path), path + ".name");
    base.body = model_.num_bodies();
    if (Reader::Has(node, "type")) {
      const std::string type = r_.String(node["type"], path + ".type");
      if (type == "differential") {
        base.type = BaseType::kDifferential;
      } else if (type != "omni") {
        r_.Fail(node["type"], path + ".type",
                "unknown base type " + Quote(type) + " (known: omni, differential)");
      }
    }
    // A differential base's x, y and theta are all controls: complete, and
    // `actuation` may be omitted.
    const bool differential = base.type == BaseType::kDifferential;
    const bool given = !differential || Reader::Has(node, "actuation");
    const YAML::Node actuation_node = given ? r_.Require(node, "actuation", path) : node;
    const std::string actuation = given ? r_.String(actuation_node, path + ".actuation") : "complete";
    if (actuation == "complete") {
      base.actuation = Actuation::kComplete;
    } else if (actuation == "reduced" && !differential) {
      base.actuation = Actuation::kReduced;
    } else {
      r_.Fail(actuation_node, path + ".actuation",
              "unknown actuation " + Quote(actuation) +
                  (differential ? " for a differential base (known: complete)" : " (known: complete, reduced)"));
    }
    base.home_pose = r_.Vector3(r_.Require(node, "pose", path), path + ".pose", {"m", "m", "rad"});
    if (Reader::Has(node, "wheels")) {
      if (differential) {
        base.differential = ParseDifferentialWheels(node["wheels"], path + ".wheels");
      } else {
        base.wheels = ParseWheels(node["wheels"], path + ".wheels");
      }
    }
    return base;
  }

  DifferentialWheels ParseDifferentialWheels(const YAML::Node& node, const std::string& path) const {
    const YAML::Node map = r_.Map(node, path);
    r_.WarnUnknownKeys(map, {"track", "radius"}, path);
    DifferentialWheels wheels;
    wheels.track = r_.Number(r_.Require(map, "track", path), path + ".track", "m");
    wheels.radius = r_.Number(r_.Require(map, "radius", path), path + ".radius", "m");
    if (!(wheels.track > 0)) r_.Fail(map["track"], path + ".track", "must be positive (m)");
    if (!(wheels.radius > 0)) r_.Fail(map["radius"], path + ".radius", "must be positive (m)");
    return wheels;
  }

  std::vector<Wheel> ParseWheels(const YAML::Node& node, const std::string& path) const {
    const YAML::Node wheels =
        r_.Sequence(node, path, static_cast<std::size_t>(kMaxWheels), "wheels");
    std::vector<Wheel> result;
    for (std::size_t i = 0; i < wheels.size(); ++i) {
      const std::string wpath = Indexed(path, i);
      const YAML::Node w = r_.Map(wheels[i], wpath);
      r_.WarnUnknownKeys(w, {"angle", "distance", "radius", "mounting", "roller"}, wpath);
      Wheel wheel;
      wheel.angle = r_.Number(r_.Require(w, "angle", wpath), wpath + ".angle", "rad");
      wheel.distance = r_.Number(r_.Require(w, "distance", wpath), wpath + ".distance", "m");
      wheel.radius = r_.Number(r_.Require(w, "radius", wpath), wpath + ".radius", "m");
      if (w["mounting"].IsDefined()) {
        wheel.mounting = r_.Number(w["mounting"], wpath + ".mounting", "rad");
      }
      if (w["roller"].IsDefined()) wheel.roller = r_.Number(w["roller"], wpath + ".roller", "rad");
      result.push_back(wheel);
    }
    try {
      OmniWheelKinematics check(result);
    } catch (const std::invalid_argument& e) {
      r_.Fail(wheels, path, e.what());
    }
    return result;
  }

  // Joints of the passive chain.
  void ParseJoints(const YAML::Node& joints) {
    components_ = Components(model_.num_bodies());
    std::map<std::string, std::pair<YAML::Node, std::size_t>> names;  // given names
    std::vector<bool> named(joints.size(), false);
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const std::string path = Indexed("joints", j);
      const YAML::Node node = r_.Map(joints[j], path);
      if (Reader::Has(node, "name")) {
        const std::string name = r_.Name(node["name"], path + ".name");
        const auto it = names.find(name);
        if (it != names.end()) {
          r_.Fail(node["name"], path + ".name",
                  "duplicate joint name '" + name + "' (first defined at " +
                      r_.Location(it->second.first) + ")");
        }
        names.emplace(name, std::make_pair(node["name"], j));
        named[j] = true;
      }
      model_.joints.push_back(ParseJoint(node, path));
      model_.joints.back().name =
          named[j] ? node["name"].Scalar() : "joint" + std::to_string(j);
    }
    // Controls: three per base, then one per actuated joint in file order.
    int control = kBaseControlSize * model_.num_bases();
    for (Joint& joint : model_.joints) {
      if (joint.actuated) joint.control = control++;
    }
    // A joint without a name is called joint<i>; no other joint may take that.
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const auto it = named[j] ? names.end() : names.find("joint" + std::to_string(j));
      if (it != names.end()) {
        r_.Fail(it->second.first, Indexed("joints", it->second.second) + ".name",
                "duplicate joint name '" + it->first + "': it is the default name of the "
                "unnamed " + Indexed("joints", j));
      }
    }
  }

  Joint ParseJoint(const YAML::Node& node, const std::string& path) {
    r_.WarnUnknownKeys(node, {"type", "between", "point", "axis", "axes", "name", "actuated", "limits"}, path);
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
              "unknown joint type " + Quote(type) +
                  " (known: revolute, spherical, universal, prismatic, fixed)");
    }
    joint.type = type_it->second;

    const YAML::Node between = r_.Require(node, "between", path);
    if (!between.IsSequence() || between.size() != 2) {
      r_.Fail(between, path + ".between", "must be a list of 2 body names");
    }
    joint.body_a = BodyOrWorldAt(between[0], path + ".between[0]");
    joint.body_b = BodyOrWorldAt(between[1], path + ".between[1]");
    if (joint.body_a == joint.body_b) {
      r_.Fail(between, path + ".between",
              "names the same body '" + NameOf(joint.body_a) + "' twice");
    }
    ParseJointGeometry(node, path, &joint);
    ParseActuationAndLimits(node, path, &joint);
    if (joint.body_a == kWorld || joint.body_b == kWorld) {
      grounded_bodies_.push_back(joint.body_a == kWorld ? joint.body_b : joint.body_a);
    } else {
      components_.Unite(joint.body_a, joint.body_b);
    }
    return joint;
  }

  // `actuated` and `limits` (revolute and prismatic joints only).
  void ParseActuationAndLimits(const YAML::Node& node, const std::string& path, Joint* joint) const {
    const bool can = joint->has_coordinate();
    if (Reader::Has(node, "actuated")) {
      const YAML::Node flag = node["actuated"];
      bool value = false;
      if (!flag.IsScalar() || !YAML::convert<bool>::decode(flag, value)) {
        r_.Fail(flag, path + ".actuated", "must be true or false");
      }
      if (value && !can) {
        r_.Fail(flag, path + ".actuated", "only revolute and prismatic joints can be actuated");
      }
      joint->actuated = value;
    }
    if (Reader::Has(node, "limits")) {
      const YAML::Node limits = node["limits"];
      if (!can) r_.Fail(limits, path + ".limits", "only revolute and prismatic joints have limits");
      if (!limits.IsSequence() || limits.size() != 2) {
        r_.Fail(limits, path + ".limits", "must be a list of 2 numbers [lo, hi]");
      }
      const char* unit = joint->type == JointType::kRevolute ? "rad" : "m";
      joint->lower = r_.Number(limits[0], path + ".limits[0]", unit);
      joint->upper = r_.Number(limits[1], path + ".limits[1]", unit);
      if (!(joint->lower <= 0 && 0 <= joint->upper)) {
        r_.Fail(limits, path + ".limits",
                "must satisfy lo <= 0 <= hi (home, q = 0, is inside), got [" + FormatG(joint->lower) + ", " +
                    FormatG(joint->upper) + "]");
      }
      joint->limited = true;
    }
  }

  // The joint's point and axes, from world coordinates at home into each
  // body's frame.
  void ParseJointGeometry(const YAML::Node& node, const std::string& path, Joint* joint) const {
    static const Body kGround;  // world: identity pose
    const Body& A = joint->body_a == kWorld ? kGround : model_.bodies[joint->body_a];
    const Body& B = joint->body_b == kWorld ? kGround : model_.bodies[joint->body_b];
    const Eigen::Vector3d p_W = r_.Vector3(r_.Require(node, "point", path), path + ".point", "m");
    joint->p_A = A.R_WB_home.transpose() * (p_W - A.p_WB_home);
    joint->p_B = B.R_WB_home.transpose() * (p_W - B.p_WB_home);

    const JointType type = joint->type;
    if (type == JointType::kRevolute || type == JointType::kPrismatic) {
      const Eigen::Vector3d a_W = r_.Axis(r_.Require(node, "axis", path), path + ".axis");
      joint->a_A = A.R_WB_home.transpose() * a_W;
      joint->a_B = B.R_WB_home.transpose() * a_W;
      // Reference directions for q: any unit vector perpendicular to the axis.
      const Eigen::Vector3d helper =
          std::abs(a_W.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
      const Eigen::Vector3d e1_W = (helper - helper.dot(a_W) * a_W).normalized();
      joint->e1_A = A.R_WB_home.transpose() * e1_W;
      joint->e2_A = A.R_WB_home.transpose() * a_W.cross(e1_W);
      joint->w_B = B.R_WB_home.transpose() * e1_W;
    }
    if (type == JointType::kUniversal) {
      const YAML::Node axes = r_.Require(node, "axes", path);
      if (!axes.IsSequence() || axes.size() != 2) {
        r_.Fail(axes, path + ".axes", "must be a list of 2 axes");
      }
      const Eigen::Vector3d a_W = r_.Axis(axes[0], path + ".axes[0]");
      const Eigen::Vector3d b_W = r_.Axis(axes[1], path + ".axes[1]");
      const double cosine = a_W.dot(b_W);
      if (std::abs(cosine) > kPerpendicularTolerance) {
        r_.Fail(axes, path + ".axes",
                "the two axes must be perpendicular at home (cosine " + FormatG(cosine) + ")");
      }
      // Within the tolerance, make them exactly perpendicular (b moves in the
      // plane of a and b), so the model is assembled at home by construction.
      const Eigen::Vector3d b_W_exact = (b_W - cosine * a_W).normalized();
      joint->a_A = A.R_WB_home.transpose() * a_W;
      joint->b_B = B.R_WB_home.transpose() * b_W_exact;
    }
    if (type == JointType::kFixed || type == JointType::kPrismatic) {
      joint->d1_A = A.R_WB_home.transpose() * Eigen::Vector3d::UnitX();
      joint->d1_B = B.R_WB_home.transpose() * Eigen::Vector3d::UnitX();
      joint->d2_A = A.R_WB_home.transpose() * Eigen::Vector3d::UnitY();
      joint->d2_B = B.R_WB_home.transpose() * Eigen::Vector3d::UnitY();
    }
  }

  void ParseEndEffector(const YAML::Node& ee) {
    r_.WarnUnknownKeys(ee, {"body", "point", "controlled"}, "end_effector");
    EndEffector& out = model_.end_effector;
    const YAML::Node body = r_.Require(ee, "body", "end_effector");
    if (r_.String(body, "end_effector.body") == "world") {
      r_.Fail(body, "end_effector.body", "the end-effector must be on a body, not on 'world'");
    }
    out.body = BodyAt(body, "end_effector.body");
    const Body& frame = model_.bodies[out.body];
    out.p_W_home =
        r_.Vector3(r_.Require(ee, "point", "end_effector"), "end_effector.point", "m");
    out.p_B = frame.R_WB_home.transpose() * (out.p_W_home - frame.p_WB_home);
    const YAML::Node controlled =
        r_.Sequence(r_.Require(ee, "controlled", "end_effector"), "end_effector.controlled");
    if (controlled.size() == 0) {
      r_.Fail(controlled, "end_effector.controlled", "must name at least one component");
    }
    for (std::size_t c = 0; c < controlled.size(); ++c) {
      const std::string path = Indexed("end_effector.controlled", c);
      const std::string component = r_.String(controlled[c], path);
      int index = -1;
      for (int k = 0; k < 6; ++k) {
        if (component == kEndEffectorComponentNames[k]) index = k;
      }
      if (index < 0) {
        r_.Fail(controlled[c], path,
                "unknown component " + Quote(component) + " (known: x y z roll pitch yaw)");
      }
      if (out.controlled[index]) {
        r_.Fail(controlled[c], path, "component '" + component + "' listed twice");
      }
      out.controlled[index] = true;
    }
  }

  // Every body must hang, through joints, from some mobile base or `world`.
  void CheckConnected(const YAML::Node& bodies) {
    std::set<int> grounded;
    for (const MobileBase& base : model_.mobile_bases) {
      grounded.insert(components_.Find(base.body));
    }
    for (int body : grounded_bodies_) grounded.insert(components_.Find(body));
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (grounded.count(components_.Find(static_cast<int>(i))) == 0) {
        r_.Fail(bodies[i], Indexed("bodies", i),
                "body '" + model_.bodies[i].name +
                    "' is not connected through joints to any mobile base or to world");
      }
    }
  }

  const Reader r_;
  Model model_;
  std::unordered_map<std::string, NamedBody> body_names_;  // bodies and bases
  Components components_{0};
  std::vector<int> grounded_bodies_;  // bodies jointed to `world`
};

// Rejects flow collections nested deeper than kMaxFlowNesting, counting every
// bracket outside comments (brackets inside quoted strings count too, which
// only matters for text no model file contains).
void CheckFlowNesting(const std::string& text, const std::string& source) {
  int depth = 0;
  int line = 1;
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      comment = false;
    } else if (comment) {
      continue;
    } else if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' ||
                            text[i - 1] == '\n')) {
      comment = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxFlowNesting) {
        throw ModelError(source + ":" + std::to_string(line) + ": not valid YAML: nested more than " +
                         std::to_string(kMaxFlowNesting) + " levels deep");
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

std::string WithLine(const std::string& source, const YAML::Mark& mark) {
  return mark.line >= 0 ? source + ":" + std::to_string(mark.line + 1) : source;
}

std::string MiB(std::size_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

// Closes a file descriptor on every path out.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

namespace internal {

bool ReadRegularFile(const std::string& path, std::size_t max_bytes, const char* noun,
                     std::string* text, std::string* error) {
  const std::string cannot_open = path + ": cannot open the " + noun;
  // Look before opening: opening a FIFO blocks, reading a device never ends.
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) {
    *error = cannot_open + " (no such file)";
    return false;
  }
  if (ec) {
    *error = cannot_open + " (" + ec.message() + ")";
    return false;
  }
  if (status.type() != std::filesystem::file_type::regular) {
    const bool directory = status.type() == std::filesystem::file_type::directory;
    *error = path + ": not a regular file" + (directory ? " (a directory)" : "");
    return false;
  }
  // O_NONBLOCK and the fstat below: the path may have been swapped since.
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK));
  if (fd.get() < 0) {
    *error = cannot_open + " (" + std::strerror(errno) + ")";
    return false;
  }
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0 || !S_ISREG(info.st_mode)) {
    *error = path + ": not a regular file";
    return false;
  }
  const std::string too_large = path + ": larger than " + MiB(max_bytes) + " (the limit for a " +
                                noun + ")";
  if (info.st_size > 0 && static_cast<std::uintmax_t>(info.st_size) > max_bytes) {
    *error = too_large;
    return false;
  }
  text->clear();
  char buffer[65536];
  for (;;) {
    const ssize_t got = ::read(fd.get(), buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      *error = path + ": cannot read the " + noun + " (" + std::strerror(errno) + ")";
      return false;
    }
    if (got == 0) break;
    if (text->size() + static_cast<std::size_t>(got) > max_bytes) {
      *error = too_large;  // it grew, or st_size was not its size
      return false;
    }
    text->append(buffer, static_cast<std::size_t>(got));
  }
  return true;
}

}  // namespace internal

Model LoadModelFromString(const std::string& text, const std::string& source_name,
                          std::vector<std::string>* warnings) {
  if (text.size() > kMaxModelFileBytes) {
    throw ModelError(source_name + ": larger than " + MiB(kMaxModelFileBytes) +
                     " (the limit for a model file)");
  }
  CheckFlowNesting(text, source_name);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw ModelError(WithLine(source_name, e.mark) + ": not valid YAML: nested too deeply (" +
                     std::to_string(e.depth()) + " levels)");
  } catch (const YAML::ParserException& e) {
    throw ModelError(WithLine(source_name, e.mark) + ": not valid YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw ModelError(WithLine(source_name, e.mark) + ": cannot read the YAML: " + e.msg);
  }
  try {
    return Parser(source_name, warnings).Parse(root);
  } catch (const YAML::Exception& e) {  // a conversion we did not foresee
    throw ModelError(WithLine(source_name, e.mark) + ": " + e.msg);
  }
}

Model LoadModel(const std::string& path, std::vector<std::string>* warnings) {
  std::string text;
  std::string error;
  if (!internal::ReadRegularFile(path, kMaxModelFileBytes, "model file", &text, &error)) {
    throw ModelError(error);
  }
  return LoadModelFromString(text, path, warnings);
}

}  // namespace ccma
