// `ccma workspace --store=DIR`: the finished tiles of a map kept in a
// directory as they complete, so that a run stopped by Ctrl-C (or a crash)
// resumes where it stopped: a tile found there is not computed again, and
// the map is identical to one computed in one go.
//
// DIR/store.json   {"ccma_workspace_store": 1, "key": "<hex>", "tiles": N}
// DIR/tile_<k>.bin one finished tile (analyses/workspace.h
//                  WorkspaceTileResult), written to a temporary name and
//                  renamed, so a file is whole or absent; it ends with a
//                  64-bit FNV-1a checksum of everything before it.
// The key hashes the model file's text and every option that defines the
// map; a store of another map is refused (UsageError naming DIR). A tile
// file that is truncated, damaged or of another shape is ignored (one line
// on stderr) and the tile computed again.
#ifndef CCMA_APPS_WORKSPACE_STORE_H_
#define CCMA_APPS_WORKSPACE_STORE_H_

#include <mutex>
#include <string>

#include "analyses/workspace.h"
#include "ccma/model.h"

namespace ccma::cli {

class WorkspaceStore final : public WorkspaceTileCache {
 public:
  // Opens or creates DIR for the map of (model_text, key_text); `tiles` the
  // map's tile count. Throws UsageError when DIR holds another map or
  // cannot be created.
  WorkspaceStore(const std::string& dir, const Model& model, const std::string& key_text, int tiles);

  bool Load(int tile, WorkspaceTileResult* out) override;
  void Save(int tile, const WorkspaceTileResult& result) override;

  int loaded() const { return loaded_; }  // tiles read back (not computed)

 private:
  std::string TilePath(int tile) const;
  const std::string dir_;
  const Model& model_;
  int loaded_ = 0;
  std::mutex mutex_;
};

}  // namespace ccma::cli

#endif  // CCMA_APPS_WORKSPACE_STORE_H_
