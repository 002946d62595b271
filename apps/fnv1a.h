// FNV-1a (64 bits): the checksum that ends a `ccma workspace --store` tile
// file (apps/workspace_tile_file.h) and the hash in a store's key
// (apps/workspace_store_manifest.h). Not a defence against a forger (a store
// is checked value by value instead), only against damage.
#ifndef CCMA_APPS_FNV1A_H_
#define CCMA_APPS_FNV1A_H_

#include <cstdint>
#include <string>

namespace ccma::cli {

inline std::uint64_t Fnv1a(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace ccma::cli

#endif  // CCMA_APPS_FNV1A_H_
