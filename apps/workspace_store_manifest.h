// DIR/store.json of a `ccma workspace --store=DIR` store: the name of the
// map whose tiles the folder holds, {"ccma_workspace_store": 1, "key":
// "<hex>", "tiles": N}. The key hashes the model file's text and every
// option that defines the map (apps/workspace_command.cc StoreKey).
#ifndef CCMA_APPS_WORKSPACE_STORE_MANIFEST_H_
#define CCMA_APPS_WORKSPACE_STORE_MANIFEST_H_

#include <cstddef>
#include <string>

namespace ccma::cli {

// Largest store.json read (the ones ccma writes are under 100 bytes).
constexpr std::size_t kMaxStoreManifestBytes = 4096;

// The text of store.json for the map named by `key_text`, cut into `tiles`.
std::string StoreManifestText(const std::string& key_text, int tiles);

enum class ManifestMatch {
  kSame,       // the same map: its tiles may be read back
  kOtherMap,   // a manifest of another map
  kMalformed,  // not a manifest: not JSON, a key given twice, other keys or types, another version
};

// Compares `text` (a store.json read back) with `want` (StoreManifestText).
// For kMalformed, `why` says what is wrong (values from `text` quoted).
ManifestMatch CheckStoreManifest(const std::string& text, const std::string& want, std::string* why);

}  // namespace ccma::cli

#endif  // CCMA_APPS_WORKSPACE_STORE_MANIFEST_H_
