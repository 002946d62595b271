// libFuzzer target for `ccma workspace --store` tile files
// (apps/workspace_tile_file.h, issue 34).
//
// The bytes are decoded as each tile of a small fixed map of
// models/4dof_reduced.yaml (4 tiles of 2 x 2 samples: `ccma workspace
// --x=-0.2:0.2 --z=0.5:0.9 --resolution=4 --tile_size=2`, the map the seeds in
// fuzz/corpus_workspace_tile/ come from). A decode either refuses with a
// reason or returns a tile that keeps every limit and encodes back to the
// same bytes; anything else (an exception, a crash, a sanitizer report, an
// allocation beyond the input's size) aborts. Each input is also tried with
// its FNV-1a checksum appended, so that mutations reach the checks behind
// the checksum (the unsealed_* seeds are tiles without their checksum), and
// as a tile of the map whose fingerprint its header holds as well as of the
// seeds' map (Fnv1a("fuzz map")), so that a mutated fingerprint does not
// stop every mutation at the first check.
// The model is found at $CCMA_FUZZ_MODEL, else CCMA_SOURCE_DIR/models/...,
// else models/4dof_reduced.yaml under the working directory.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "apps/workspace_tile_file.h"
#include "formats/model_loader.h"

namespace {

std::string ModelPath() {
  if (const char* path = std::getenv("CCMA_FUZZ_MODEL")) return path;
#ifdef CCMA_SOURCE_DIR
  return CCMA_SOURCE_DIR "/models/4dof_reduced.yaml";
#else
  return "models/4dof_reduced.yaml";
#endif
}

const ccma::Model& FuzzModel() {
  static const ccma::Model model = ccma::LoadModel(ModelPath());
  return model;
}

// The map's tiles: only their row counts matter to the decoder.
std::vector<ccma::WorkspaceTile> FuzzTiles() {
  std::vector<ccma::WorkspaceTile> tiles(4);
  for (int t = 0; t < 4; ++t) tiles[static_cast<std::size_t>(t)].rows = {4 * t, 4 * t + 1, 4 * t + 2, 4 * t + 3};
  return tiles;
}

void Fail(const char* what) {
  std::fprintf(stderr, "workspace_tile_fuzzer: %s\n", what);
  std::abort();
}

// What an accepted tile must keep (the decoder's contract).
void CheckAccepted(const std::string& bytes, const ccma::WorkspaceTileResult& tile,
                   const ccma::cli::WorkspaceTileLimits& limits) {
  if (static_cast<long long>(tile.samples.size()) != limits.samples) Fail("accepted a tile of another size");
  if (tile.carried.size() != tile.carried_rows.size() || static_cast<long long>(tile.carried.size()) > limits.samples) {
    Fail("accepted carried samples without rows, or too many");
  }
  for (const auto* samples : {&tile.samples, &tile.carried}) {
    for (const ccma::WorkspaceSample& s : *samples) {
      if (s.reachable && (!s.controls.allFinite() || !std::isfinite(s.error))) Fail("accepted a non-finite reached sample");
      if (s.tile < 0 || s.tile >= limits.tiles || s.start < -1 || s.start >= limits.map_samples) Fail("index out of range");
    }
  }
  if (ccma::cli::EncodeWorkspaceTile(tile, limits.map) != bytes) Fail("an accepted tile does not encode back to its bytes");
}

// Decodes `bytes` as each tile of the map whose fingerprint is `map`.
void DecodeAsEveryTile(const std::string& bytes, std::uint64_t map) {
  static const std::vector<ccma::WorkspaceTile> tiles = FuzzTiles();
  for (int t = 0; t < static_cast<int>(tiles.size()); ++t) {
    const ccma::cli::WorkspaceTileLimits limits = ccma::cli::WorkspaceTileLimitsFor(FuzzModel(), tiles, t, map);
    std::string why;
    bool other_map = false;
    const auto tile = ccma::cli::DecodeWorkspaceTile(bytes, FuzzModel(), limits, &why, &other_map);
    if (tile) {
      if (other_map) Fail("accepted a tile of another map");
      CheckAccepted(bytes, *tile, limits);
    } else if (why.empty()) {
      Fail("refused without a reason");
    }
  }
}

// Decodes `bytes` as a tile of the seeds' map and of the map in its header.
void DecodeAsEveryMap(const std::string& bytes) {
  static const std::uint64_t seeds_map = ccma::cli::WorkspaceMapFingerprint("fuzz map");
  DecodeAsEveryTile(bytes, seeds_map);
  std::uint64_t header_map = 0;
  if (bytes.size() >= 16) std::memcpy(&header_map, bytes.data() + 8, sizeof header_map);
  if (header_map != seeds_map) DecodeAsEveryTile(bytes, header_map);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    DecodeAsEveryMap(bytes);
    // The same bytes with their checksum appended: a mutation gets past the
    // checksum to the checks behind it (a forger can compute FNV-1a too).
    std::string sealed = bytes;
    const std::uint64_t sum = ccma::cli::Fnv1a(bytes);
    sealed.append(reinterpret_cast<const char*>(&sum), sizeof sum);
    DecodeAsEveryMap(sealed);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workspace_tile_fuzzer: unexpected exception: %s\n", e.what());
    std::abort();
  }
  return 0;
}
