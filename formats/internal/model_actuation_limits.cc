// A joint's `q_home` (its coordinate at home), `actuated` (its coordinate
// becomes a control) and `limits` (bounds on its coordinate): revolute and
// prismatic joints only.
#include <cmath>
#include <string>

#include "ccma/internal/format.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

void ModelParser::ParseActuationAndLimits(const YAML::Node& node, const std::string& path, Joint* joint) const {
  const bool can = joint->has_coordinate();
  const char* unit = joint->type == JointType::kRevolute ? "rad" : "m";
  if (YamlReader::Has(node, "q_home")) {
    if (!can) r_.Fail(node["q_home"], path + ".q_home", "only revolute and prismatic joints have a coordinate");
    joint->q_home = r_.Number(node["q_home"], path + ".q_home", unit);
    // Bounded like every control value (a revolute q_home is an angle, any
    // value is allowed; it is reported wrapped into (-pi, pi]).
    if (std::abs(joint->q_home) > 1e4) r_.Fail(node["q_home"], path + ".q_home", "must be within [-1e4, 1e4]");
  }
  if (YamlReader::Has(node, "actuated")) {
    const YAML::Node flag = node["actuated"];
    bool value = false;
    if (!flag.IsScalar() || !YAML::convert<bool>::decode(flag, value)) {
      r_.Fail(flag, path + ".actuated", "must be true or false");
    }
    if (value && !can) r_.Fail(flag, path + ".actuated", "only revolute and prismatic joints can be actuated");
    joint->actuated = value;
  }
  if (YamlReader::Has(node, "limits")) {
    const YAML::Node limits = node["limits"];
    if (!can) r_.Fail(limits, path + ".limits", "only revolute and prismatic joints have limits");
    if (!limits.IsSequence() || limits.size() != 2) {
      r_.Fail(limits, path + ".limits", "must be a list of 2 numbers [lo, hi]");
    }
    joint->lower = r_.Number(limits[0], path + ".limits[0]", unit);
    joint->upper = r_.Number(limits[1], path + ".limits[1]", unit);
    const double home = joint->q_home;
    if (!(joint->lower <= home && home <= joint->upper)) {
      r_.Fail(limits, path + ".limits",
              "must satisfy lo <= q_home <= hi (home, q = " + FormatG(home) + ", is inside), got [" +
                  FormatG(joint->lower) + ", " + FormatG(joint->upper) + "]");
    }
    joint->limited = true;
  }
}

}  // namespace internal
}  // namespace ccma
