#include "apps/workspace_store_manifest.h"

#include <set>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/fnv1a.h"
#include "ccma/internal/format.h"

namespace ccma::cli {
namespace {

constexpr int kVersion = 1;

std::string Hex(std::uint64_t x) {
  std::ostringstream out;
  out << std::hex << x;
  return out.str();
}

// Why `have` is not a manifest of this version, or "" when it is one.
std::string Malformed(const nlohmann::json& have) {
  if (have.is_discarded()) return "not JSON";
  if (!have.is_object()) return "not a JSON object";
  for (const auto& item : have.items()) {
    if (item.key() != "ccma_workspace_store" && item.key() != "key" && item.key() != "tiles") {
      return "an unknown key " + Quote(item.key());
    }
  }
  const auto version = have.find("ccma_workspace_store");
  if (version == have.end() || !version->is_number_integer()) return "no integer \"ccma_workspace_store\"";
  if (*version != kVersion) return "store version " + Quote(version->dump()) + ", not " + std::to_string(kVersion);
  const auto key = have.find("key");
  if (key == have.end() || !key->is_string()) return "no string \"key\"";
  const auto tiles = have.find("tiles");
  if (tiles == have.end() || !tiles->is_number_integer()) return "no integer \"tiles\"";
  return "";
}

// The first key given twice in one object of `text`, with the line of its
// second appearance ("" when none): nlohmann keeps the last value silently.
std::string DuplicateKey(const std::string& text) {
  std::vector<std::set<std::string>> open;  // the keys of each object being parsed
  std::string duplicate;
  const auto callback = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    if (event == Event::object_start) open.emplace_back();
    if (event == Event::object_end && !open.empty()) open.pop_back();
    if (event == Event::key && duplicate.empty() && !open.empty()) {
      const std::string key = parsed.get<std::string>();
      if (!open.back().insert(key).second) duplicate = key;
    }
    return true;
  };
  (void)nlohmann::json::parse(text, callback, false);  // only the callback's findings matter
  if (duplicate.empty()) return "";
  const std::string what = "the key " + Quote(duplicate) + " given twice";
  // The line of its second appearance, written as a plain JSON string.
  const std::string quoted = nlohmann::json(duplicate).dump();
  int line = 1, seen = 0;
  for (std::size_t at = 0; at < text.size(); ++at) {
    if (text[at] == '\n') ++line;
    if (text.compare(at, quoted.size(), quoted) == 0 && ++seen == 2) return "line " + std::to_string(line) + ": " + what;
  }
  return what;
}

}  // namespace

std::string StoreManifestText(const std::string& key_text, int tiles) {
  const nlohmann::json manifest = {{"ccma_workspace_store", kVersion}, {"key", Hex(Fnv1a(key_text))}, {"tiles", tiles}};
  return manifest.dump() + "\n";
}

ManifestMatch CheckStoreManifest(const std::string& text, const std::string& want, std::string* why) {
  // No exceptions: a parse error gives a discarded value, refused by Malformed.
  const nlohmann::json have = nlohmann::json::parse(text, nullptr, false);
  *why = Malformed(have);
  if (why->empty()) *why = DuplicateKey(text);
  if (!why->empty()) return ManifestMatch::kMalformed;
  return have == nlohmann::json::parse(want) ? ManifestMatch::kSame : ManifestMatch::kOtherMap;
}

}  // namespace ccma::cli
