// The bytes of one `ccma workspace --store` tile file (apps/workspace_store.h
// keeps them in DIR/tile_<k>.bin): a finished tile (WorkspaceTileResult)
// encoded, and decoded back with every claim checked, since a store may
// come from someone else (a folder shared on a cluster).
//
// Layout (little-endian as written by this machine): the magic "CCMAWT02";
// the map's fingerprint (u64, WorkspaceMapFingerprint: a tile copied from
// another map's store, or left in a store whose store.json was deleted, is
// told apart from this map's, even with a valid checksum); the samples (a
// u64 count, then each sample); the carried rows (a u64 count, then that
// many i64); the carried samples (count and samples as before); a u64
// FNV-1a checksum of everything before it, the fingerprint included. A sample is its
// target position and rpy (each a u64 count 3 and 3 doubles), the flags
// reachable, converged, assembled (one byte each, 0 or 1), the controls (u64
// count, doubles), residual_energy, error, sigma_min, rcond,
// max_limit_violation (doubles), limited_by (u64 length, bytes), wave, start,
// tile, steps (i64), warning (u64 length, bytes) and the state (u64 count,
// 7 doubles per body).
#ifndef CCMA_APPS_WORKSPACE_TILE_FILE_H_
#define CCMA_APPS_WORKSPACE_TILE_FILE_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "analyses/workspace.h"
#include "apps/fnv1a.h"
#include "ccma/model.h"

namespace ccma::cli {

// Longest limited_by or warning text a tile sample may hold (those ccma
// writes are a few hundred bytes).
constexpr std::uint64_t kMaxTileTextBytes = 64 * 1024;
// Text bytes per sample (limited_by and warning together, on average over
// the tile) that the size cap of a tile file allows for.
constexpr std::uint64_t kTileTextBytesPerSample = 4096;

// What a tile file of one map may hold.
struct WorkspaceTileLimits {
  int tile = 0;               // the tile's number: its samples' `tile`
  long long samples = 0;      // its sample count, exactly; also the most carried samples
  long long map_samples = 0;  // the map's sample count: rows and starts are below it
  int tiles = 0;              // the map's tile count: every sample's `tile` is below it
  std::uint64_t map = 0;      // the map's fingerprint: a tile of another map holds another
  std::size_t max_bytes = 0;  // the largest file such a tile can be (see below)
};

// The limits of tile `tile` of the map whose fingerprint is `map` (of
// `model`, cut into `tiles`). max_bytes is the encoded size of samples + carried samples (at most one carried
// sample per sample: each starts from one) of `model`'s size, with
// kTileTextBytesPerSample of text each, plus the carried rows and framing.
WorkspaceTileLimits WorkspaceTileLimitsFor(const Model& model, const std::vector<WorkspaceTile>& tiles, int tile,
                                           std::uint64_t map);

// The fingerprint of the map named by `key_text` (the text its store's
// key hashes: the model file and every option that defines the map).
inline std::uint64_t WorkspaceMapFingerprint(const std::string& key_text) { return Fnv1a(key_text); }

// The file's bytes for a finished tile of the map whose fingerprint is `map`.
std::string EncodeWorkspaceTile(const WorkspaceTileResult& result, std::uint64_t map);

// The tile in `bytes`, or nullopt and `why` (a short reason, no file name)
// when they are not a whole tile of `model` within `limits`: wrong magic or
// checksum, a whole tile of another map (a fingerprint other than
// limits.map: then `other_map`, when given, is set), a count that is not
// the tile's or does not fit the bytes that remain (checked before anything
// is allocated), a vector of another size
// than the model's, a flag other than 0 or 1, reachable without converged
// and assembled, a target that is not finite, controls or state that are
// not finite in a reachable or assembled sample, measures that are not
// finite in a reachable one, a wave, start, tile or step count out of
// range, carried rows not ascending within the map, text longer than
// kMaxTileTextBytes, or bytes left over.
std::optional<WorkspaceTileResult> DecodeWorkspaceTile(const std::string& bytes, const Model& model,
                                                       const WorkspaceTileLimits& limits, std::string* why,
                                                       bool* other_map = nullptr);

}  // namespace ccma::cli

#endif  // CCMA_APPS_WORKSPACE_TILE_FILE_H_
