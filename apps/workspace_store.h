// `ccma workspace --store=DIR`: the finished tiles of a map kept in a
// directory as they complete, so that a run stopped by Ctrl-C (or a crash)
// resumes where it stopped: a tile found there is not computed again, and
// the map is identical to one computed in one go.
//
// DIR/store.json   the map's name (apps/workspace_store_manifest.h); a
//                  store of another map is refused, and so is a store.json
//                  that is not a regular file, is larger than
//                  kMaxStoreManifestBytes or is not a manifest (UsageError
//                  naming the file and what is wrong).
// DIR/tile_<k>.bin one finished tile (apps/workspace_tile_file.h), bound to
//                  its map by the map's fingerprint inside it.
// Files are written as OutputFile writes (a fresh temporary name beside
// them made with O_EXCL | O_NOFOLLOW, fsync, rename), replacing whatever
// entry has the name, never writing through a link: a file is whole or
// absent, and several processes may write one store at once.
// A tile is read only when it is a regular file (not a link, FIFO, device
// or folder) of at most the size a tile of this map can take, through the
// bounded reader, and every value is checked (DecodeWorkspaceTile); any
// other tile file -- a tile of another map among them, even when store.json
// is missing or was copied along -- is computed again, with one line on
// stderr naming it.
#ifndef CCMA_APPS_WORKSPACE_STORE_H_
#define CCMA_APPS_WORKSPACE_STORE_H_

#include <cstdint>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "analyses/workspace.h"
#include "ccma/model.h"

namespace ccma::cli {

class WorkspaceStore final : public WorkspaceTileCache {
 public:
  // Opens or creates DIR for the map of (model, key_text) cut into `tiles`
  // (WorkspaceTiles). Throws UsageError when DIR holds another map, its
  // store.json cannot be read or is not a manifest, or DIR cannot be
  // created or written.
  WorkspaceStore(const std::string& dir, const Model& model, const std::string& key_text,
                 const std::vector<WorkspaceTile>& tiles);

  bool Load(int tile, WorkspaceTileResult* out) override;
  void Save(int tile, const WorkspaceTileResult& result) override;

  int loaded() const { return loaded_; }  // tiles read back (not computed)
  int tiles() const { return static_cast<int>(tiles_.size()); }

  // For a run that is about to end (Ctrl-C): waits for a tile being written
  // to be in place, stops writing tiles, and returns how many of this map's
  // tiles the store holds: tile files that are regular files, other than
  // those this run found damaged (and has not written again).
  int Freeze();

 private:
  std::string TilePath(int tile) const;
  void Warn(const std::string& line);  // one line on stderr, whole
  const std::string dir_;
  const Model& model_;
  const std::vector<WorkspaceTile> tiles_;
  const std::uint64_t map_;  // the map's fingerprint, in every tile it writes and reads
  int loaded_ = 0;
  std::set<int> damaged_;  // tiles found damaged and not written since (under mutex_)
  bool frozen_ = false;    // under save_mutex_
  std::mutex mutex_;       // stderr, loaded_ and damaged_
  std::mutex save_mutex_;  // one tile written at a time, so Freeze counts only whole ones
};

}  // namespace ccma::cli

#endif  // CCMA_APPS_WORKSPACE_STORE_H_
