// `velocity_limit` (model_format.md, "Inertia"): how fast `ccma retime` may
// drive an actuated joint (V [rad/s or m/s]) or a mobile base ([V, W]: speed
// over the floor [m/s] and turn rate [rad/s]; a legged base adds its height,
// roll and pitch rates: [V, W, Vz, Wr, Wp]).
#include <string>

#include "ccma/internal/format.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

void ModelParser::ParseJointVelocityLimit(const YAML::Node& node, const std::string& path, Joint* joint) const {
  if (!YamlReader::Has(node, "velocity_limit")) return;
  const std::string at = path + ".velocity_limit";
  if (!joint->actuated) {
    r_.Fail(node["velocity_limit"], at, "only an actuated joint (actuated: true) has a velocity limit");
  }
  const char* unit = joint->type == JointType::kRevolute ? "rad/s" : "m/s";
  const double limit = r_.Number(node["velocity_limit"], at, unit);
  if (!(limit > 0)) r_.Fail(node["velocity_limit"], at, "must be positive (" + std::string(unit) + "), got " + FormatG(limit));
  joint->velocity_limit = limit;
}

std::vector<double> ModelParser::ParseBaseVelocityLimit(const YAML::Node& node, const std::string& path,
                                                        BaseType type) const {
  if (!YamlReader::Has(node, "velocity_limit")) return {};
  const std::string at = path + ".velocity_limit";
  const bool legged = type == BaseType::kLegged;
  const std::size_t count = legged ? 5 : 2;
  const YAML::Node values = r_.Sequence(node["velocity_limit"], at);
  if (values.size() != count) {
    r_.Fail(node["velocity_limit"], at,
            legged ? "must be [V, W, Vz, Wr, Wp] (m/s, rad/s, m/s, rad/s, rad/s) for a legged base"
                   : "must be [V, W] (speed over the floor in m/s, turn rate in rad/s)");
  }
  static const char* const kUnits[] = {"m/s", "rad/s", "m/s", "rad/s", "rad/s"};
  std::vector<double> out;
  for (std::size_t i = 0; i < count; ++i) {
    const double v = r_.Number(values[i], Indexed(at, i), kUnits[i]);
    if (!(v > 0)) r_.Fail(values[i], Indexed(at, i), std::string("must be positive (") + kUnits[i] + "), got " + FormatG(v));
    out.push_back(v);
  }
  return out;
}

}  // namespace internal
}  // namespace ccma
