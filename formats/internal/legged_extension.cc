#include "formats/internal/legged_extension.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/internal/export_geometry.h"
#include "formats/model_loader.h"

namespace ccma {
namespace internal {
namespace {

// "lo hi" for a limited range.
std::string LeggedRangeText(const ControlRange& range) { return Number(range.lower) + " " + Number(range.upper); }

// Exactly `count` decimal numbers separated by white space, each finite and
// within kMaxMagnitude; at most count + 1 words are looked at.
std::vector<double> LeggedNumbers(const std::string& text, std::size_t count, const std::string& where) {
  std::istringstream words(text);
  std::vector<double> values;
  bool clean = true;
  for (std::string word; clean && values.size() <= count && words >> word;) {
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    // Decimal only: strtod also reads hex floats (0x1p-1), inf and nan.
    const bool decimal = word.find_first_not_of("0123456789+-.eE") == std::string::npos;
    clean = decimal && end != word.c_str() && *end == '\0' && errno != ERANGE && std::isfinite(value) &&
            std::abs(value) <= kMaxMagnitude;
    values.push_back(value);
  }
  if (!clean || values.size() != count) {
    throw ModelError(where + ": expected " + std::to_string(count) + " finite number" + (count > 1 ? "s" : "") +
                     " within 1e4, got " + Quote(text));
  }
  return values;
}

ControlRange LeggedRange(const std::string& text, double home, const char* unit, const std::string& where) {
  const std::vector<double> v = LeggedNumbers(text, 2, where);
  if (!(v[0] <= home && home <= v[1])) {
    throw ModelError(where + ": must contain the home value " + FormatG(home) + " " + unit + ", got [" +
                     FormatG(v[0]) + ", " + FormatG(v[1]) + "]");
  }
  ControlRange range;
  range.limited = true;
  range.lower = v[0];
  range.upper = v[1];
  return range;
}

}  // namespace

std::string LeggedAttributes(const LeggedBody& body) {
  std::string out = " body_height=\"" + Number(body.height) + "\"";
  if (body.height_limits.limited) out += " height_limits=\"" + LeggedRangeText(body.height_limits) + "\"";
  if (body.roll_limits.limited) out += " roll_limits=\"" + LeggedRangeText(body.roll_limits) + "\"";
  if (body.pitch_limits.limited) out += " pitch_limits=\"" + LeggedRangeText(body.pitch_limits) + "\"";
  if (body.footprint.minCoeff() > 0) {
    out += " footprint=\"" + Number(body.footprint.x()) + " " + Number(body.footprint.y()) + "\"";
  }
  return out;
}

LeggedBody ParseLeggedAttributes(const std::vector<std::pair<std::string, std::string>>& attributes,
                                 const std::string& where) {
  static const std::set<std::string> kKnown = {"body_height", "height_limits", "roll_limits", "pitch_limits",
                                               "footprint"};
  std::map<std::string, std::string> given;
  for (const auto& [name, value] : attributes) {
    if (kKnown.count(name) == 0) {
      throw ModelError(where + ": unknown attribute " + Quote(name) +
                       " (known: body_height, height_limits, roll_limits, pitch_limits, footprint)");
    }
    if (!given.emplace(name, value).second) throw ModelError(where + ": attribute " + Quote(name) + " given twice");
  }
  if (given.count("body_height") == 0) throw ModelError(where + ": body_height is required (m, above the floor)");
  LeggedBody body;
  body.height = LeggedNumbers(given["body_height"], 1, where + ": body_height")[0];
  if (!(body.height > 0)) {
    throw ModelError(where + ": body_height: must be > 0 m (above the floor), got " + FormatG(body.height));
  }
  if (given.count("height_limits")) {
    body.height_limits = LeggedRange(given["height_limits"], body.height, "m", where + ": height_limits");
  }
  if (given.count("roll_limits")) body.roll_limits = LeggedRange(given["roll_limits"], 0.0, "rad", where + ": roll_limits");
  if (given.count("pitch_limits")) {
    body.pitch_limits = LeggedRange(given["pitch_limits"], 0.0, "rad", where + ": pitch_limits");
  }
  if (given.count("footprint")) {
    const std::vector<double> sides = LeggedNumbers(given["footprint"], 2, where + ": footprint");
    if (!(sides[0] > 0 && sides[1] > 0)) {
      throw ModelError(where + ": footprint: both sides must be > 0 m, got " + Quote(given["footprint"]));
    }
    body.footprint = Eigen::Vector2d(sides[0], sides[1]);
  }
  return body;
}

}  // namespace internal
}  // namespace ccma
