// Masses and loads (model_format.md, "Masses and loads"): `mass` and `com`
// on bodies and bases, `payload` under end_effector, `gravity`,
// `effort_limits` on actuated joints and `push_limit` on bases.
#include <string>

#include "ccma/internal/format.h"
#include "ccma/mass_properties.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

// `mass` [kg] and `com` (world at home, default the body's origin) of `node`.
MassProperties ModelParser::ParseMassProperties(const YAML::Node& node, const std::string& path,
                                                const Body& body) const {
  MassProperties out;
  if (YamlReader::Has(node, "mass")) {
    out.mass = r_.Number(node["mass"], path + ".mass", "kg");
    if (!(out.mass >= 0)) r_.Fail(node["mass"], path + ".mass", "must not be negative (kg), got " + FormatG(out.mass));
  }
  if (YamlReader::Has(node, "com")) {
    const Eigen::Vector3d com_W = r_.Vector3(node["com"], path + ".com", "m");
    out.com_B = body.R_WB_home.transpose() * (com_W - body.p_WB_home);
  }
  if (YamlReader::Has(node, "inertia")) {
    const std::string at = path + ".inertia";
    const YAML::Node six = r_.Sequence(node["inertia"], at);
    if (six.size() != 6) r_.Fail(node["inertia"], at, "must be [ixx, iyy, izz, ixy, ixz, iyz] (kg*m^2)");
    double v[6];
    for (std::size_t i = 0; i < 6; ++i) v[i] = r_.Number(six[i], Indexed(at, i), "kg*m^2");
    Eigen::Matrix3d I_W;
    I_W << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
    std::string why;
    if (!IsPhysicalInertia(I_W, &why)) r_.Fail(node["inertia"], at, why);
    out.inertia_B = body.R_WB_home.transpose() * I_W * body.R_WB_home;  // the file's world axes at home
  }
  return out;
}

void ModelParser::ParseEffortLimits(const YAML::Node& node, const std::string& path, Joint* joint) const {
  if (!YamlReader::Has(node, "effort_limits")) return;
  const YAML::Node limits = node["effort_limits"];
  const std::string at = path + ".effort_limits";
  if (!joint->actuated) r_.Fail(limits, at, "only an actuated joint (actuated: true) has effort limits");
  if (!limits.IsSequence() || limits.size() != 2) r_.Fail(limits, at, "must be [lower, upper] (N*m or N)");
  const char* unit = joint->type == JointType::kRevolute ? "N*m" : "N";
  joint->effort.given = true;
  joint->effort.lower = r_.Number(limits[0], Indexed(at, 0), unit);
  joint->effort.upper = r_.Number(limits[1], Indexed(at, 1), unit);
  if (!(joint->effort.lower <= joint->effort.upper)) {
    r_.Fail(limits, at, "lower (" + FormatG(joint->effort.lower) + ") must not exceed upper (" +
                            FormatG(joint->effort.upper) + ")");
  }
}

double ModelParser::ParsePushLimit(const YAML::Node& node, const std::string& path) const {
  if (!YamlReader::Has(node, "push_limit")) return 0.0;
  const double limit = r_.Number(node["push_limit"], path + ".push_limit", "N");
  if (!(limit > 0)) r_.Fail(node["push_limit"], path + ".push_limit", "must be positive (N), got " + FormatG(limit));
  return limit;
}

void ModelParser::ParseLoads(const YAML::Node& root, const YAML::Node& end_effector) {
  if (YamlReader::Has(root, "gravity")) model_.gravity = r_.Vector3(root["gravity"], "gravity", "m/s^2");
  if (!YamlReader::Has(end_effector, "payload")) return;
  const YAML::Node payload = r_.Map(end_effector["payload"], "end_effector.payload");
  r_.CheckKeys(payload, {"mass", "com", "inertia"}, "end_effector.payload");
  const Body& body = model_.bodies[static_cast<size_t>(model_.end_effector.body)];
  r_.Require(payload, "mass", "end_effector.payload");
  model_.end_effector.payload = ParseMassProperties(payload, "end_effector.payload", body);
  // Default: the end-effector point.
  if (!YamlReader::Has(payload, "com")) model_.end_effector.payload.com_B = model_.end_effector.p_B;
}

}  // namespace internal
}  // namespace ccma
