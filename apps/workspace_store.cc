#include "apps/workspace_store.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "apps/cli.h"
#include "apps/output_file.h"
#include "apps/workspace_store_manifest.h"
#include "apps/workspace_tile_file.h"
#include "formats/model_loader.h"

namespace ccma::cli {
namespace {

// Why the entry at `path` is not a store file ccma could have written
// ("" when it is a regular file of at most `max_bytes`); `absent` is set
// when there is no entry. Looks with lstat: a link is never followed, a
// FIFO never opened, a folder never read.
std::string NotAStoreFile(const std::string& path, std::size_t max_bytes, bool* absent) {
  struct stat info;
  *absent = false;
  if (::lstat(path.c_str(), &info) != 0) {
    *absent = errno == ENOENT;
    return std::strerror(errno);
  }
  if (S_ISLNK(info.st_mode)) return "a symbolic link; ccma writes regular files";
  if (S_ISDIR(info.st_mode)) return "a directory";
  if (!S_ISREG(info.st_mode)) return "not a regular file";
  if (static_cast<std::uintmax_t>(info.st_size) > max_bytes) {
    return std::to_string(info.st_size) + " bytes, more than the " + std::to_string(max_bytes) + " it can take";
  }
  return "";
}

// Writes `bytes` to `path` as OutputFile does, replacing whatever entry is
// there. Throws UsageError or std::runtime_error when it cannot.
void WriteStoreFile(const std::string& path, const std::string& bytes) {
  OutputFile out(path, "store", ExistingName::kReplace);
  out.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.Commit();  // checks every write, fsyncs, then renames into place
}

// The manifest at `path` read back and compared with `want`; throws
// UsageError unless it names the same map.
void CheckManifestFile(const std::string& dir, const std::string& path, const std::string& want) {
  const std::string fix = ": delete the folder '" + dir + "' to start again, or use a new one";
  bool absent = false;
  std::string why = NotAStoreFile(path, kMaxStoreManifestBytes, &absent), text;
  if (why.empty() && !internal::ReadRegularFile(path, kMaxStoreManifestBytes, "store manifest", &text, &why)) {
    throw UsageError("--store: " + why + fix);
  }
  if (why.empty() && CheckStoreManifest(text, want, &why) == ManifestMatch::kOtherMap) {
    throw UsageError("--store: '" + dir + "' holds another map (other model, ranges or options): use a new "
                     "directory, or delete this one to start again");
  }
  if (!why.empty()) throw UsageError("--store: '" + path + "' is not a workspace store manifest (" + why + ")" + fix);
}

}  // namespace

WorkspaceStore::WorkspaceStore(const std::string& dir, const Model& model, const std::string& key_text,
                               const std::vector<WorkspaceTile>& tiles)
    : dir_(dir), model_(model), tiles_(tiles), map_(WorkspaceMapFingerprint(key_text)) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (!fs::is_directory(dir_, ec)) throw UsageError("--store: cannot create the directory '" + dir_ + "'");
  const std::string want = StoreManifestText(key_text, static_cast<int>(tiles_.size()));
  const std::string manifest = dir_ + "/store.json";
  struct stat info;
  if (::lstat(manifest.c_str(), &info) != 0 && errno == ENOENT) {
    try {
      WriteStoreFile(manifest, want);
    } catch (const std::exception&) {
      throw UsageError("--store: cannot write '" + manifest + "'");
    }
  }
  // Read back even after writing it: another run may have written its own.
  CheckManifestFile(dir_, manifest, want);
}

std::string WorkspaceStore::TilePath(int tile) const { return dir_ + "/tile_" + std::to_string(tile) + ".bin"; }

void WorkspaceStore::Warn(const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::cerr << "ccma workspace: --store: " << line << "\n";
}

bool WorkspaceStore::Load(int tile, WorkspaceTileResult* out) {
  if (tile < 0 || tile >= static_cast<int>(tiles_.size())) return false;
  const std::string path = TilePath(tile);
  const WorkspaceTileLimits limits = WorkspaceTileLimitsFor(model_, tiles_, tile, map_);
  bool absent = false;
  std::string why = NotAStoreFile(path, limits.max_bytes, &absent), bytes;
  if (absent) return false;  // not computed yet
  std::optional<WorkspaceTileResult> kept;
  bool other_map = false;
  if (why.empty() && internal::ReadRegularFile(path, limits.max_bytes, "tile file", &bytes, &why)) {
    kept = DecodeWorkspaceTile(bytes, model_, limits, &why, &other_map);
  }
  if (!kept) {
    Warn("'" + path + (other_map ? "' is " + why : "' is damaged (" + why + ")") + "; computing the tile again");
    std::lock_guard<std::mutex> lock(mutex_);
    damaged_.insert(tile);
    return false;
  }
  *out = std::move(*kept);
  std::lock_guard<std::mutex> lock(mutex_);
  ++loaded_;
  return true;
}

void WorkspaceStore::Save(int tile, const WorkspaceTileResult& result) {
  const std::string path = TilePath(tile);
  const std::string bytes = EncodeWorkspaceTile(result, map_);
  std::lock_guard<std::mutex> lock(save_mutex_);
  if (frozen_) return;
  try {
    WriteStoreFile(path, bytes);
    std::lock_guard<std::mutex> lock(mutex_);
    damaged_.erase(tile);
  } catch (const std::exception&) {
    Warn("could not write '" + path + "' (the map goes on without it)");
  }
}

int WorkspaceStore::Freeze() {
  std::lock_guard<std::mutex> save_lock(save_mutex_);
  frozen_ = true;
  std::lock_guard<std::mutex> lock(mutex_);
  int kept = 0;
  for (int tile = 0; tile < tiles(); ++tile) {
    struct stat info;
    const bool file = ::lstat(TilePath(tile).c_str(), &info) == 0 && S_ISREG(info.st_mode);
    kept += file && damaged_.count(tile) == 0 ? 1 : 0;
  }
  return kept;
}

}  // namespace ccma::cli
