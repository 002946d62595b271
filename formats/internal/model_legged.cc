// A legged base's body: `body_height` (required), `body_limits` and
// `footprint` (docs/model_format.md, "Legged agents").
#include <string>

#include "ccma/internal/format.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {

LeggedBody ModelParser::ParseLeggedBody(const YAML::Node& node, const std::string& path) const {
  LeggedBody body;
  body.height = r_.Number(r_.Require(node, "body_height", path), path + ".body_height", "m");
  if (!(body.height > 0)) {
    r_.Fail(node["body_height"], path + ".body_height", "must be > 0 m (above the floor), got " + FormatG(body.height));
  }
  if (YamlReader::Has(node, "body_limits")) {
    const std::string at = path + ".body_limits";
    const YAML::Node limits = r_.Map(node["body_limits"], at);
    r_.CheckKeys(limits, {"height", "roll", "pitch"}, at);
    body.height_limits = ParseBodyLimit(limits, at, "height", body.height, "m");
    body.roll_limits = ParseBodyLimit(limits, at, "roll", 0.0, "rad");
    body.pitch_limits = ParseBodyLimit(limits, at, "pitch", 0.0, "rad");
  }
  if (YamlReader::Has(node, "footprint")) {
    const YAML::Node footprint = node["footprint"];
    if (!footprint.IsSequence() || footprint.size() != 2) {
      r_.Fail(footprint, path + ".footprint", "must be a list of 2 numbers [length, width] (m)");
    }
    for (int i = 0; i < 2; ++i) {
      body.footprint[i] = r_.Number(footprint[i], path + ".footprint[" + std::to_string(i) + "]", "m");
      if (!(body.footprint[i] > 0)) {
        r_.Fail(footprint[i], path + ".footprint[" + std::to_string(i) + "]",
                "must be > 0 m, got " + FormatG(body.footprint[i]));
      }
    }
  }
  return body;
}

// One entry of `body_limits`: [lo, hi] around the home value (the home
// height, zero roll and pitch), or unbounded when absent.
ControlRange ModelParser::ParseBodyLimit(const YAML::Node& limits, const std::string& path, const char* key,
                                         double home, const char* unit) const {
  ControlRange range;
  if (!YamlReader::Has(limits, key)) return range;
  const YAML::Node pair = limits[key];
  const std::string at = path + "." + key;
  if (!pair.IsSequence() || pair.size() != 2) r_.Fail(pair, at, "must be a list of 2 numbers [lo, hi]");
  range.lower = r_.Number(pair[0], at + "[0]", unit);
  range.upper = r_.Number(pair[1], at + "[1]", unit);
  if (!(range.lower <= home && home <= range.upper)) {
    r_.Fail(pair, at,
            "must contain the home value " + FormatG(home) + " " + unit + ", got [" + FormatG(range.lower) + ", " +
                FormatG(range.upper) + "]");
  }
  range.limited = true;
  return range;
}

}  // namespace internal
}  // namespace ccma
