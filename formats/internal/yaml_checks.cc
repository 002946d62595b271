#include "formats/internal/yaml_checks.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "formats/internal/magnitude_checks.h"
#include "formats/model_loader.h"

namespace ccma {
namespace internal {
namespace {

// Axes shorter than this are "the zero vector".
constexpr double kMinAxisNorm = 1e-12;

// The edit distance between `a` and `b` (optimal string alignment: a swap of
// two neighbouring characters counts 1, as in "tpye"), or more than `limit`
// whenever it exceeds `limit`: lengths that differ by more cost nothing.
std::size_t EditDistance(const std::string& a, const std::string& b, std::size_t limit) {
  const std::size_t n = a.size(), m = b.size();
  if ((n > m ? n - m : m - n) > limit) return limit + 1;
  // d[i][j]: distance between the first i characters of a and j of b.
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

// "'a'", "'a' or 'b'", "'a', 'b' or 'c'".
std::string Alternatives(const std::vector<std::string>& keys) {
  std::string out;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i > 0) out += i + 1 == keys.size() ? " or " : ", ";
    out += "'" + keys[i] + "'";
  }
  return out;
}

}  // namespace

bool IsName(const std::string& text) {
  if (text.empty() || text.size() > kMaxNameLength) return false;
  for (const char c : text) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

std::string NameRule() {
  return "1-" + std::to_string(kMaxNameLength) + " characters from [A-Za-z0-9_-]";
}

std::string Indexed(const std::string& list, std::size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

std::vector<std::string> ClosestKeys(const std::string& key, const std::set<std::string>& known) {
  std::vector<std::string> closest;
  std::size_t best = 0;
  for (const std::string& candidate : known) {
    // Short keys are one edit from many words ("note" is two from "name").
    const std::size_t limit = std::min(key.size(), candidate.size()) <= 4 ? 1 : 2;
    const std::size_t distance = EditDistance(key, candidate, limit);
    if (distance > limit || (!closest.empty() && distance > best)) continue;
    if (closest.empty() || distance < best) closest.clear();
    best = distance;
    closest.push_back(candidate);
  }
  return closest;
}

void YamlReader::Fail(const YAML::Node& at, const std::string& key, const std::string& what) const {
  std::ostringstream os;
  os << source_;
  if (at.IsDefined() && at.Mark().line >= 0) os << ":" << at.Mark().line + 1;
  os << ": " << (key.empty() ? "" : key + ": ") << what;
  throw ModelError(os.str());
}

YAML::Node YamlReader::Require(const YAML::Node& map, const std::string& key,
                               const std::string& path) const {
  const YAML::Node value = map[key];
  if (!value.IsDefined() || value.IsNull()) Fail(map, Join(path, key), "missing required key");
  return value;
}

bool YamlReader::Has(const YAML::Node& map, const std::string& key) {
  const YAML::Node value = map[key];
  return value.IsDefined() && !value.IsNull();
}

void YamlReader::CheckKeys(const YAML::Node& map, const std::set<std::string>& known,
                           const std::string& path) const {
  for (const auto& entry : map) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
    if (known.count(key) != 0) continue;
    // A non-scalar key ("? [a, b]") is no misspelling of a name.
    const std::vector<std::string> closest =
        entry.first.IsScalar() ? ClosestKeys(key, known) : std::vector<std::string>{};
    if (!closest.empty()) {
      Fail(entry.first, path, "unknown key " + Quote(key) + " (did you mean " + Alternatives(closest) + "?)");
    }
    if (warnings_ != nullptr) {
      warnings_->push_back(Location(entry.first) + ": " + Join(path, Printable(key)) +
                           ": unknown key, ignored");
    }
  }
}

YAML::Node YamlReader::Map(const YAML::Node& node, const std::string& path) const {
  if (!node.IsMap()) Fail(node, path, "must be a mapping");
  return node;
}

YAML::Node YamlReader::Sequence(const YAML::Node& node, const std::string& path) const {
  if (!node.IsSequence()) Fail(node, path, "must be a list");
  return node;
}

YAML::Node YamlReader::Sequence(const YAML::Node& node, const std::string& path, std::size_t max,
                                const std::string& what) const {
  Sequence(node, path);
  if (node.size() > max) {
    Fail(node, path, std::to_string(node.size()) + " " + what + "; at most " + std::to_string(max) +
                         " are allowed");
  }
  return node;
}

std::string YamlReader::String(const YAML::Node& node, const std::string& path) const {
  if (!node.IsScalar() || node.Scalar().empty()) Fail(node, path, "must be a non-empty string");
  return node.Scalar();
}

std::string YamlReader::Name(const YAML::Node& node, const std::string& path) const {
  if (!node.IsScalar()) Fail(node, path, "must be a name of " + NameRule());
  const std::string& name = node.Scalar();
  if (!IsName(name)) Fail(node, path, Quote(name) + " must be " + NameRule());
  return name;
}

double YamlReader::Number(const YAML::Node& node, const std::string& path, const char* unit) const {
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
  if (magnitudes_ != nullptr) magnitudes_->See(value, unit, node.Mark().line, path);
  return value;
}

Eigen::Vector3d YamlReader::Vector3(const YAML::Node& node, const std::string& path,
                                    const std::array<const char*, 3>& units) const {
  if (!node.IsSequence() || node.size() != 3) Fail(node, path, "must be a list of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = Number(node[i], Indexed(path, i), units[i]);
  return v;
}

// Scaled by its largest component first, so neither huge nor tiny components
// overflow or underflow.
Eigen::Vector3d YamlReader::Axis(const YAML::Node& node, const std::string& path) const {
  const Eigen::Vector3d v = Vector3(node, path, "unitless");
  const double scale = v.cwiseAbs().maxCoeff();
  if (!(scale > 0)) Fail(node, path, "must not be the zero vector");
  const Eigen::Vector3d scaled = v / scale;
  const double norm = scaled.norm();  // in [1, sqrt(3)]
  if (!(scale * norm >= kMinAxisNorm)) Fail(node, path, "must not be the zero vector");
  return scaled / norm;
}

std::string YamlReader::Location(const YAML::Node& node) const {
  std::string where = source_;
  if (node.Mark().line >= 0) where += ":" + std::to_string(node.Mark().line + 1);
  return where;
}

std::string YamlReader::Join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

}  // namespace internal
}  // namespace ccma
