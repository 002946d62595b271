// Validation helpers shared by every section of the model loader: typed reads
// out of YAML nodes (required and optional keys, mappings, lists, names,
// bounded numbers, 3-vectors, axes) that turn every problem into a ModelError
// of the form "file:line: key: what", and the check of a mapping's keys
// (unknown keys, with a suggestion for a misspelt one).
//
// Internal to the library: formats/model_loader.h is the public API.
#ifndef CCMA_FORMATS_INTERNAL_YAML_CHECKS_H_
#define CCMA_FORMATS_INTERNAL_YAML_CHECKS_H_

#include <array>
#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

namespace ccma {
namespace internal {

class MagnitudeChecks;

// Whether `text` is a name: 1 to kMaxNameLength characters from [A-Za-z0-9_-].
bool IsName(const std::string& text);

// "1-64 characters from [A-Za-z0-9_-]", for messages.
std::string NameRule();

// "list[i]".
std::string Indexed(const std::string& list, std::size_t i);

// The entries of `known` closest to `key` by edit distance (insertions,
// deletions, substitutions and swaps of two neighbours count 1 each), if that
// distance is at most 1 (when `key` or the entry has at most 4 characters) or
// 2 (otherwise); several when they tie, in `known`'s order; empty when none
// is that close. A key far longer than every entry costs no more than a
// comparison of lengths.
std::vector<std::string> ClosestKeys(const std::string& key, const std::set<std::string>& known);

// Reads typed values out of YAML nodes, turning every problem into a
// ModelError that says file:line: key: what. `path` arguments are the key
// path of the node for messages ("joints[3].axis", "" for the top level).
class YamlReader {
 public:
  // `warnings` (may be null) receives unknown keys; `magnitudes` (may be
  // null) sees every length ("m") and angle ("rad") that Number() reads.
  YamlReader(std::string source, std::vector<std::string>* warnings, MagnitudeChecks* magnitudes)
      : source_(std::move(source)), warnings_(warnings), magnitudes_(magnitudes) {}

  const std::string& source() const { return source_; }

  // Throws ModelError "source:line: key: what" (the line of `at` when YAML
  // gives one; no "key: " when `key` is empty).
  [[noreturn]] void Fail(const YAML::Node& at, const std::string& key, const std::string& what) const;

  // The value of `key` in `map`, which must be present and not null.
  YAML::Node Require(const YAML::Node& map, const std::string& key, const std::string& path) const;

  // Whether the optional `key` of `map` is given (present and not null).
  static bool Has(const YAML::Node& map, const std::string& key);

  // Checks the keys of `map` against `known`, before any of its values is
  // read: a key within ClosestKeys() distance of a known one is a misspelling
  // and throws "path: unknown key 'betwen' (did you mean 'between'?)" at the
  // key's line; any other unknown key (a key of a newer format, say) is
  // ignored and adds "file:line: path.key: unknown key, ignored" to the
  // warnings.
  void CheckKeys(const YAML::Node& map, const std::set<std::string>& known,
                 const std::string& path) const;

  YAML::Node Map(const YAML::Node& node, const std::string& path) const;
  YAML::Node Sequence(const YAML::Node& node, const std::string& path) const;
  // A list of at most `max` entries; `what` names them in the message.
  YAML::Node Sequence(const YAML::Node& node, const std::string& path, std::size_t max,
                      const std::string& what) const;

  // A non-empty scalar.
  std::string String(const YAML::Node& node, const std::string& path) const;
  // A name: 1 to kMaxNameLength characters from [A-Za-z0-9_-].
  std::string Name(const YAML::Node& node, const std::string& path) const;

  // A finite number in [-kMaxMagnitude, kMaxMagnitude]; `unit` is named in
  // the message ("m", "rad", "unitless"; "" for none). Lengths ("m") and
  // angles ("rad") are also shown to the MagnitudeChecks.
  double Number(const YAML::Node& node, const std::string& path, const char* unit) const;

  // Three numbers; `units` names each component's unit.
  Eigen::Vector3d Vector3(const YAML::Node& node, const std::string& path,
                          const std::array<const char*, 3>& units) const;
  Eigen::Vector3d Vector3(const YAML::Node& node, const std::string& path, const char* unit) const {
    return Vector3(node, path, {unit, unit, unit});
  }

  // A unit vector from a non-zero 3-vector (any length, normalised).
  Eigen::Vector3d Axis(const YAML::Node& node, const std::string& path) const;

  // "source:line" of `node` ("source" when YAML gives no line).
  std::string Location(const YAML::Node& node) const;

  // "path.key", or "key" at the top level.
  static std::string Join(const std::string& path, const std::string& key);

 private:
  std::string source_;
  std::vector<std::string>* warnings_;
  MagnitudeChecks* magnitudes_;
};

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_YAML_CHECKS_H_
