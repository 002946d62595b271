// A joint's `actuated` (its coordinate becomes a control) and `limits`
// (bounds on its coordinate): revolute and prismatic joints only.
#include <string>

#include "ccma/internal/format.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

void ModelParser::ParseActuationAndLimits(const YAML::Node& node, const std::string& path, Joint* joint) const {
  const bool can = joint->has_coordinate();
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

}  // namespace internal
}  // namespace ccma
