// `ccma workspace --store=DIR` against a store someone else prepared (issue
// 34): links planted at the names it writes, tiles that claim too much, are
// not files or hold values the map cannot use, and manifests that are not
// manifests. A bad tile is computed again (one line on stderr naming it, the
// same map as without a store); a bad manifest is refused with exit 2. And
// Ctrl-C: what the store keeps and the command that resumes, on stderr.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analyses/workspace.h"
#include "apps/workspace_store.h"
#include "apps/workspace_store_manifest.h"
#include "apps/workspace_tile_file.h"
#include "formats/model_loader.h"
#include "tests/tool_run.h"

namespace ccma {
namespace workspace_store_test {

namespace fs = std::filesystem;
using cli::DecodeWorkspaceTile;
using cli::EncodeWorkspaceTile;

// 16 samples in 4 tiles of 2 x 2 (the map of fuzz/workspace_tile_fuzzer.cc).
const std::vector<std::string> kMap = {"--x=-0.2:0.2", "--z=0.5:0.9", "--resolution=4", "--tile_size=2"};

WorkspaceOptions MapOptions(const Model& model) {
  WorkspaceOptions options;
  options.ranges = {{0, -0.2, 0.2}, {2, 0.5, 0.9}};
  options.resolution = 4;
  options.tile_size = 2;
  std::string why;
  EXPECT_TRUE(options.IsValid(model, &why)) << why;
  return options;
}

const Model& TheModel() {
  static const Model model = LoadModel(testing::ModelPath("4dof_reduced"));
  return model;
}

// A fresh, empty folder for one test.
std::string FreshDir(const std::string& name) {
  const std::string dir = testing::ScratchPath("store", name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Like testing::RunTool, with the child's address space capped at 2 GiB, so
// that a run which would allocate tens of GB fails (bad_alloc) instead of
// taking the machine's memory, and an alarm that ends a hang.
testing::ToolRun RunBounded(const std::vector<std::string>& args, int timeout_s = 120) {
  const std::string out = testing::ScratchPath("store", "bounded_out"), err = testing::ScratchPath("store", "bounded_err");
  const pid_t pid = testing::SpawnTool(args, timeout_s, out, err, [] {
#ifndef __SANITIZE_ADDRESS__  // AddressSanitizer's shadow memory alone needs terabytes of address space
    const rlimit limit{std::uint64_t{2} << 30, std::uint64_t{2} << 30};
    setrlimit(RLIMIT_AS, &limit);
#endif
  });
  int raw = 0;
  waitpid(pid, &raw, 0);
  testing::ToolRun r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = testing::Slurp(out);
  r.err = testing::Slurp(err);
  return r;
}

std::vector<std::string> MapArgs(const std::string& out, const std::string& store) {
  std::vector<std::string> args = {"workspace", "--model=" + testing::ModelPath("4dof_reduced"), "--out=" + out};
  args.insert(args.end(), kMap.begin(), kMap.end());
  if (!store.empty()) args.push_back("--store=" + store);
  return args;
}

// The map's CSV computed in one go, without a store.
const std::string& ReferenceCsv() {
  static const std::string csv = [] {
    const std::string out = testing::ScratchPath("store", "reference.csv");
    const testing::ToolRun run = testing::RunTool(MapArgs(out, ""));
    EXPECT_EQ(run.status, 0) << run.err;
    return testing::Slurp(out);
  }();
  return csv;
}

// The map fingerprint a tile file's header holds (after the 8-byte magic).
std::uint64_t MapOf(const std::string& bytes) {
  std::uint64_t map = 0;
  if (bytes.size() >= 16) std::memcpy(&map, bytes.data() + 8, sizeof map);
  return map;
}

// A store of the map with all its tiles, in a fresh folder.
std::string FilledStore(const std::string& name) {
  const std::string dir = FreshDir(name);
  const testing::ToolRun run = testing::RunTool(MapArgs(dir + "/map.csv", dir + "/store"));
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["tiles"], 4);
  return dir;
}

// Runs the map again on the store in `dir` after tile_<bad>.bin was spoiled:
// the tile is computed again with one line naming it (and one more when the
// entry cannot be replaced), the others read back, and the map is the one
// computed in one go.
void ExpectRecomputed(const std::string& dir, int bad, bool bounded = false, bool replaceable = true) {
  const std::vector<std::string> args = MapArgs(dir + "/again.csv", dir + "/store");
  const testing::ToolRun run = bounded ? RunBounded(args) : testing::RunTool(args, 60);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["tiles_from_store"], 3);
  const std::string name = "tile_" + std::to_string(bad) + ".bin' is damaged";
  EXPECT_NE(run.err.find(name), std::string::npos) << run.err;
  const std::string more = replaceable ? "" : "could not write '" + dir + "/store/tile_" + std::to_string(bad) + ".bin'";
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), replaceable ? 1 : 2) << run.err;
  EXPECT_NE(run.err.find(more), std::string::npos) << run.err;
  EXPECT_EQ(testing::Slurp(dir + "/again.csv"), ReferenceCsv());
}

// ---------------------------------------------------------------- writes ---

TEST(WorkspaceStoreWrites, LinksPlantedAtEveryNameAreReplacedNotFollowed) {
  const std::string dir = FreshDir("links"), store = dir + "/store", victim = dir + "/victim.txt";
  WriteBytes(victim, "precious\n");
  fs::create_directories(store);
  // The fixed temporary names of earlier versions, and the tiles' own names.
  fs::create_symlink(victim, store + "/store.json.tmp");
  for (int k = 0; k < 4; ++k) {
    fs::create_symlink(victim, store + "/tile_" + std::to_string(k) + ".bin.tmp");
    fs::create_symlink(victim, store + "/tile_" + std::to_string(k) + ".bin");
  }
  const testing::ToolRun run = testing::RunTool(MapArgs(dir + "/map.csv", store));
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(testing::Slurp(victim), "precious\n");
  EXPECT_EQ(testing::Slurp(dir + "/map.csv"), ReferenceCsv());
  for (int k = 0; k < 4; ++k) {
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(store + "/tile_" + std::to_string(k) + ".bin"))) << k;
  }
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(store + "/store.json")));
  const testing::ToolRun again = testing::RunTool(MapArgs(dir + "/again.csv", store));
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(nlohmann::json::parse(again.out)["tiles_from_store"], 4);
  EXPECT_TRUE(again.err.empty()) << again.err;
}

// Two stores on one folder saving the same tiles at once (two runs sharing a
// store on a cluster): every write succeeds, nothing is said.
TEST(WorkspaceStoreWrites, ConcurrentWritersOfOneTileWarnNothing) {
  const Model& model = TheModel();
  const std::vector<WorkspaceTile> tiles = WorkspaceTiles(model, MapOptions(model));
  int home = 0;  // the tile that depends on none
  while (!tiles[static_cast<size_t>(home)].depends_on.empty()) ++home;
  const WorkspaceTileResult tile = EvaluateWorkspaceTile(model, MapOptions(model), home, {});
  const std::string dir = FreshDir("concurrent") + "/store";
  cli::WorkspaceStore a(dir, model, "key", tiles), b(dir, model, "key", tiles);
  const std::uint64_t map = cli::WorkspaceMapFingerprint("key");
  ::testing::internal::CaptureStderr();
  auto writer = [&tile, home](cli::WorkspaceStore* store) {
    for (int i = 0; i < 200; ++i) store->Save(home, tile);
  };
  std::thread first(writer, &a), second(writer, &b);
  first.join();
  second.join();
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  WorkspaceTileResult back;
  EXPECT_TRUE(a.Load(home, &back));
  EXPECT_EQ(EncodeWorkspaceTile(back, map), EncodeWorkspaceTile(tile, map));
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {  // no temporaries left
    const std::string name = e.path().filename().string();
    EXPECT_TRUE(name == "store.json" || name == "tile_" + std::to_string(home) + ".bin") << name;
  }
}

// ---------------------------------------------------------------- Ctrl-C ---

// Ctrl-C in the middle of a map: the run ends by SIGINT (a shell's exit
// status 130) with nothing on stdout and no CSV, after one message on stderr
// that names the tiles the store keeps -- exactly the tile files there -- and
// the command line that resumes. That line, run by a shell, finishes the map
// from the store: the same CSV as in one go.
TEST(WorkspaceStoreInterrupt, CtrlCSaysWhatIsKeptAndHowToResume) {
  // 24 x 24 samples in 16 tiles of 6 x 6: long enough to stop half-way.
  const std::vector<std::string> map = {"--x=-0.35:0.35", "--z=0.35:1.0", "--resolution=24", "--tile_size=6"};
  const std::string dir = FreshDir("ctrl_c"), store = dir + "/store";
  std::vector<std::string> args = {"workspace", "--model=" + testing::ModelPath("4dof_reduced")};
  args.insert(args.end(), map.begin(), map.end());
  std::vector<std::string> whole = args;
  whole.push_back("--out=" + dir + "/whole.csv");
  ASSERT_EQ(testing::RunTool(whole).status, 0);
  args.push_back("--out=" + dir + "/map.csv");
  args.push_back("--store=" + store);

  const pid_t pid = fork();
  if (pid == 0) {
    const int o = open((dir + "/out").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int e = open((dir + "/err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    dup2(o, 1);
    dup2(e, 2);
    std::vector<char*> argv = {const_cast<char*>(CCMA_TOOL_PATH)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(CCMA_TOOL_PATH, argv.data());
    _exit(127);
  }
  auto tile_files = [&store] {
    int n = 0;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(store, ec)) {
      n += e.path().filename().string().rfind("tile_", 0) == 0 && e.path().extension() == ".bin";
    }
    return n;
  };
  // Wait for 2 finished tiles (a bound on the wait, not a timing assertion).
  for (int polls = 0; polls < 24000 && tile_files() < 2 && waitpid(pid, nullptr, WNOHANG) == 0; ++polls) usleep(5000);
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int raw = 0;
  ASSERT_EQ(waitpid(pid, &raw, 0), pid);
  const std::string err = testing::Slurp(dir + "/err");
  ASSERT_TRUE(WIFSIGNALED(raw)) << "exit status " << WEXITSTATUS(raw) << "\n" << err;
  EXPECT_EQ(WTERMSIG(raw), SIGINT);  // a shell reports 128 + 2 = 130
  EXPECT_EQ(testing::Slurp(dir + "/out"), "");
  EXPECT_FALSE(fs::exists(dir + "/map.csv"));
  const int kept = tile_files();
  EXPECT_GE(kept, 2);
  EXPECT_LT(kept, 16);
  // (The store's name in quotes is shortened when long; the resume line below names it whole.)
  const std::string said = "ccma workspace: interrupted: " + std::to_string(kept) +
                           " of 16 tiles of the map are finished and kept in the store '";
  EXPECT_EQ(err.rfind(said, 0), 0u) << err;
  std::string command = CCMA_TOOL_PATH;
  for (const std::string& a : args) command += " " + a;
  const std::string resume = "the same command again resumes from them:\n  " + command + "\n";
  ASSERT_NE(err.find(resume), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 2) << err;

  // The printed line, run by a shell.
  const std::string line = err.substr(err.find("\n  ") + 3, command.size());
  const int status = std::system((line + " >" + dir + "/resumed.json 2>" + dir + "/resumed.err").c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << testing::Slurp(dir + "/resumed.err");
  const nlohmann::json summary = nlohmann::json::parse(testing::Slurp(dir + "/resumed.json"));
  EXPECT_EQ(summary["tiles"], 16);
  EXPECT_EQ(summary["tiles_from_store"], kept);
  EXPECT_EQ(testing::Slurp(dir + "/map.csv"), testing::Slurp(dir + "/whole.csv"));
}

// ----------------------------------------------------------------- tiles ---

// A tile file of only a header, a count of 1e8 samples and a valid checksum
// (24 bytes) would have allocated about 22 GB.
TEST(WorkspaceStoreTiles, AHundredMillionSampleClaimIsComputedAgain) {
  const std::string dir = FilledStore("claim");
  std::string bytes = testing::Slurp(dir + "/store/tile_1.bin").substr(0, 16);  // magic and map fingerprint
  const std::uint64_t count = 100000000;
  bytes.append(reinterpret_cast<const char*>(&count), sizeof count);
  const std::uint64_t sum = cli::Fnv1a(bytes);
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  ASSERT_EQ(bytes.size(), 32u);
  WriteBytes(dir + "/store/tile_1.bin", bytes);
  ExpectRecomputed(dir, 1, true);
}

TEST(WorkspaceStoreTiles, ALinkToDevZeroIsComputedAgain) {
  const std::string dir = FilledStore("devzero");
  fs::remove(dir + "/store/tile_2.bin");
  fs::create_symlink("/dev/zero", dir + "/store/tile_2.bin");
  ExpectRecomputed(dir, 2, true);
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir + "/store/tile_2.bin")));  // the link replaced
}

TEST(WorkspaceStoreTiles, AFifoIsComputedAgainWithoutWaiting) {
  const std::string dir = FilledStore("fifo");
  fs::remove(dir + "/store/tile_2.bin");
  ASSERT_EQ(mkfifo((dir + "/store/tile_2.bin").c_str(), 0600), 0);
  ExpectRecomputed(dir, 2);  // a hang is ended by RunTool's alarm: status -1
}

TEST(WorkspaceStoreTiles, ADirectoryIsComputedAgain) {
  const std::string dir = FilledStore("directory");
  fs::remove(dir + "/store/tile_3.bin");
  fs::create_directories(dir + "/store/tile_3.bin/inside");
  ExpectRecomputed(dir, 3, false, false);  // a folder is never removed
}

TEST(WorkspaceStoreTiles, AReachableSampleWithNanControlsIsComputedAgain) {
  const std::string dir = FilledStore("nan");
  const Model& model = TheModel();
  const std::vector<WorkspaceTile> tiles = WorkspaceTiles(model, MapOptions(model));
  for (int k = 0; k < 4; ++k) {
    const std::string path = dir + "/store/tile_" + std::to_string(k) + ".bin", bytes = testing::Slurp(path);
    const std::uint64_t map = MapOf(bytes);
    std::string why;
    std::optional<WorkspaceTileResult> tile =
        DecodeWorkspaceTile(bytes, model, cli::WorkspaceTileLimitsFor(model, tiles, k, map), &why);
    ASSERT_TRUE(tile) << why;
    for (WorkspaceSample& s : tile->samples) {
      if (!s.reachable) continue;
      s.controls[0] = std::nan("");
      WriteBytes(path, EncodeWorkspaceTile(*tile, map));  // a valid checksum
      ExpectRecomputed(dir, k);
      return;
    }
  }
  FAIL() << "no reachable sample in the map";
}

TEST(WorkspaceStoreTiles, ATruncatedTileIsComputedAgain) {
  const std::string dir = FilledStore("truncated");
  const std::string path = dir + "/store/tile_0.bin";
  const std::string bytes = testing::Slurp(path);
  WriteBytes(path, bytes.substr(0, bytes.size() / 2));
  ExpectRecomputed(dir, 0);
}

// issue 49: the tiles of another map -- the same command over z 0.55:0.95
// instead of 0.5:0.9, so the same tile count and sizes, each tile valid with
// its checksum -- copied into this map's store, with its store.json kept and
// without one (a store.json deleted, or tiles copied into a fresh folder):
// every tile is computed again, with one line naming it, and the map is this
// map's, not the other one's.
void ExpectOtherMapsTilesRecomputed(const std::string& name, bool keep_manifest) {
  const std::string dir = FilledStore(name), other = FreshDir(name + "_other");
  std::vector<std::string> args = MapArgs(other + "/map.csv", other + "/store");
  std::replace(args.begin(), args.end(), std::string("--z=0.5:0.9"), std::string("--z=0.55:0.95"));
  ASSERT_EQ(testing::RunTool(args).status, 0);
  ASSERT_NE(testing::Slurp(other + "/map.csv"), ReferenceCsv());
  if (!keep_manifest) fs::remove(dir + "/store/store.json");
  for (int k = 0; k < 4; ++k) {
    const std::string tile = "/store/tile_" + std::to_string(k) + ".bin";
    fs::copy_file(other + tile, dir + tile, fs::copy_options::overwrite_existing);
  }
  const testing::ToolRun run = testing::RunTool(MapArgs(dir + "/again.csv", dir + "/store"), 60);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["tiles_from_store"], 0);
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 4) << run.err;
  for (int k = 0; k < 4; ++k) {
    const std::string line = "ccma workspace: --store: '" + dir + "/store/tile_" + std::to_string(k) +
                             ".bin' is a tile of another map (map ";
    EXPECT_NE(run.err.find(line), std::string::npos) << run.err;
  }
  EXPECT_EQ(testing::Slurp(dir + "/again.csv"), ReferenceCsv());
  // Written again as this map's: the next run reads all four back.
  const testing::ToolRun again = testing::RunTool(MapArgs(dir + "/third.csv", dir + "/store"), 60);
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(nlohmann::json::parse(again.out)["tiles_from_store"], 4);
  EXPECT_TRUE(again.err.empty()) << again.err;
}

TEST(WorkspaceStoreTiles, AnotherMapsTilesAreComputedAgain) { ExpectOtherMapsTilesRecomputed("other_map", true); }

TEST(WorkspaceStoreTiles, AnotherMapsTilesWithoutStoreJsonAreComputedAgain) {
  ExpectOtherMapsTilesRecomputed("other_map_no_manifest", false);
}

// The fingerprint is inside the checksum: a tile whose fingerprint alone was
// changed is damaged; one encoded for another map is another map's.
TEST(WorkspaceStoreTiles, TheFingerprintIsCoveredByTheChecksum) {
  const Model& model = TheModel();
  const std::vector<WorkspaceTile> tiles = WorkspaceTiles(model, MapOptions(model));
  int home = 0;
  while (!tiles[static_cast<size_t>(home)].depends_on.empty()) ++home;
  const WorkspaceTileResult tile = EvaluateWorkspaceTile(model, MapOptions(model), home, {});
  const std::uint64_t mine = cli::WorkspaceMapFingerprint("mine"), theirs = cli::WorkspaceMapFingerprint("theirs");
  const cli::WorkspaceTileLimits limits = cli::WorkspaceTileLimitsFor(model, tiles, home, mine);
  std::string why;
  bool other_map = true;
  ASSERT_TRUE(DecodeWorkspaceTile(EncodeWorkspaceTile(tile, mine), model, limits, &why, &other_map)) << why;
  EXPECT_FALSE(other_map);
  EXPECT_FALSE(DecodeWorkspaceTile(EncodeWorkspaceTile(tile, theirs), model, limits, &why, &other_map));
  EXPECT_TRUE(other_map);
  EXPECT_EQ(why.rfind("a tile of another map (map ", 0), 0u) << why;
  std::string forged = EncodeWorkspaceTile(tile, theirs);
  std::memcpy(&forged[8], &mine, sizeof mine);  // the fingerprint swapped, the checksum left
  EXPECT_FALSE(DecodeWorkspaceTile(forged, model, limits, &why, &other_map));
  EXPECT_FALSE(other_map);
  EXPECT_EQ(why, "checksum mismatch");
}

// --------------------------------------------------------------- manifest ---

void ExpectManifestRefused(const std::string& dir, const std::string& what) {
  const testing::ToolRun run = testing::RunTool(MapArgs(dir + "/again.csv", dir + "/store"), 60);
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_NE(run.err.find("store.json"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(what), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir + "/again.csv"));
}

TEST(WorkspaceStoreManifest, NotJsonIsRefused) {
  const std::string dir = FilledStore("notjson");
  WriteBytes(dir + "/store/store.json", "this is not JSON\n");
  ExpectManifestRefused(dir, "not JSON");
}

TEST(WorkspaceStoreManifest, TruncatedIsRefused) {
  const std::string dir = FilledStore("cut");
  const std::string text = testing::Slurp(dir + "/store/store.json");
  WriteBytes(dir + "/store/store.json", text.substr(0, text.size() / 2));
  ExpectManifestRefused(dir, "not JSON");
}

TEST(WorkspaceStoreManifest, ALinkOrFifoIsRefused) {
  const std::string dir = FilledStore("manifest_link"), victim = dir + "/victim.json";
  const std::string text = testing::Slurp(dir + "/store/store.json");
  WriteBytes(victim, text);
  fs::remove(dir + "/store/store.json");
  fs::create_symlink(victim, dir + "/store/store.json");
  ExpectManifestRefused(dir, "symbolic link");
  fs::remove(dir + "/store/store.json");
  ASSERT_EQ(mkfifo((dir + "/store/store.json").c_str(), 0600), 0);
  ExpectManifestRefused(dir, "not a regular file");
  EXPECT_EQ(testing::Slurp(victim), text);
}

// issue 49: a key given twice (nlohmann keeps the last value, so a manifest
// naming two maps read as the second) is refused, naming the line.
TEST(WorkspaceStoreManifest, AKeyGivenTwiceIsRefused) {
  const std::string dir = FilledStore("duplicate");
  const nlohmann::json own = nlohmann::json::parse(testing::Slurp(dir + "/store/store.json"));
  const std::string key = own["key"];
  WriteBytes(dir + "/store/store.json", "{\"ccma_workspace_store\": 1,\n \"key\": \"0123\",\n \"key\": \"" + key +
                                            "\",\n \"tiles\": 4}\n");
  ExpectManifestRefused(dir, "(line 3: the key 'key' given twice)");
  const std::string want = cli::StoreManifestText("fuzz", 16);
  std::string why;
  const std::string twice = R"({"ccma_workspace_store": 1, "key": "1", "tiles": 16, "tiles": 16})";
  EXPECT_EQ(cli::CheckStoreManifest(twice, want, &why), cli::ManifestMatch::kMalformed);
  EXPECT_EQ(why, "line 1: the key 'tiles' given twice");
}

TEST(WorkspaceStoreManifest, OtherKeysTypesAndVersionsAreMalformed) {
  const std::string want = cli::StoreManifestText("fuzz", 16);
  std::string why;
  EXPECT_EQ(cli::CheckStoreManifest(want, want, &why), cli::ManifestMatch::kSame);
  EXPECT_EQ(cli::CheckStoreManifest(cli::StoreManifestText("other", 16), want, &why), cli::ManifestMatch::kOtherMap);
  EXPECT_EQ(cli::CheckStoreManifest(cli::StoreManifestText("fuzz", 15), want, &why), cli::ManifestMatch::kOtherMap);
  for (const char* bad : {"", "[]", "null", "{}", R"({"ccma_workspace_store": 2, "key": "1", "tiles": 16})",
                          R"({"ccma_workspace_store": 1, "key": 1, "tiles": 16})",
                          R"({"ccma_workspace_store": 1, "key": "1", "tiles": "16"})",
                          R"({"ccma_workspace_store": 1, "key": "1", "tiles": 16, "more": 0})"}) {
    EXPECT_EQ(cli::CheckStoreManifest(bad, want, &why), cli::ManifestMatch::kMalformed) << bad;
    EXPECT_FALSE(why.empty()) << bad;
  }
}

}  // namespace
}  // namespace ccma
