// Output files under hostile folders (issue: planted links at the temporary
// name, lost modes, leftovers of killed runs, links planted in a --plot
// folder or in the --out folder of bench and replay): the writer of
// apps/output_file.h seen through the `ccma` tool.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/tool_run.h"

namespace ccma {
namespace output_file_test {

namespace fs = std::filesystem;
using testing::Slurp;

// A fresh empty folder for one test.
std::string Folder(const std::string& name) {
  const std::string dir = testing::ScratchPath("output_file", name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs the tool (stdout and stderr to /dev/null) after `plant(pid)` has run
// in this process with the pid the tool will have: the names derived from
// it (the old `NAME.partial.<pid>`) can be planted before the tool starts.
int RunPlanted(const std::vector<std::string>& args, const std::function<void(pid_t)>& plant) {
  int go[2];
  if (pipe(go) != 0) return -2;
  const pid_t pid = fork();
  if (pid == 0) {
    close(go[1]);
    char c;
    if (read(go[0], &c, 1) != 1) _exit(126);
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    alarm(120);
    std::vector<char*> argv = {const_cast<char*>(CCMA_TOOL_PATH)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(CCMA_TOOL_PATH, argv.data());
    _exit(127);
  }
  close(go[0]);
  plant(pid);
  (void)!write(go[1], "x", 1);
  close(go[1]);
  int raw = 0;
  waitpid(pid, &raw, 0);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

mode_t ModeOf(const std::string& path) {
  struct stat info {};
  EXPECT_EQ(lstat(path.c_str(), &info), 0) << path;
  return info.st_mode & 07777;
}

std::vector<std::string> Entries(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string Victim(const std::string& dir) {
  const std::string victim = dir + "/victim";
  std::ofstream(victim) << "secret\n";
  chmod(victim.c_str(), 0600);
  return victim;
}

TEST(OutputFileWriter, ALinkAtTheOldTemporaryNameIsNeverFollowed) {
  const std::string dir = Folder("planted"), out = dir + "/g.yaml", victim = Victim(dir);
  const int status = RunPlanted({"generate", "--agents=6", "--out=" + out}, [&](pid_t pid) {
    fs::create_symlink(victim, out + ".partial." + std::to_string(pid));
  });
  ASSERT_EQ(status, 0);
  EXPECT_EQ(Slurp(victim), "secret\n");
  EXPECT_EQ(ModeOf(victim), 0600u);
  EXPECT_FALSE(fs::is_symlink(out));
  const std::string reference = Folder("planted_reference") + "/g.yaml";
  ASSERT_EQ(testing::RunTool({"generate", "--agents=6", "--out=" + reference}).status, 0);
  EXPECT_EQ(Slurp(out), Slurp(reference));
  for (const std::string& name : Entries(dir)) EXPECT_EQ(name.find("ccma-tmp"), std::string::npos) << name;
  EXPECT_NE(Slurp(out).find("mobile_bases"), std::string::npos);
}

TEST(OutputFileWriter, AReplacedFileKeepsItsModeAndIsComplete) {
  const std::string dir = Folder("mode"), out = dir + "/g.yaml", fresh = dir + "/fresh.yaml";
  std::ofstream(out) << "old\n";
  chmod(out.c_str(), 0600);
  const mode_t old_mask = umask(022);
  ASSERT_EQ(testing::RunTool({"generate", "--agents=6", "--out=" + out}).status, 0);
  ASSERT_EQ(testing::RunTool({"generate", "--agents=6", "--out=" + fresh}).status, 0);
  umask(027);
  const std::string masked = dir + "/masked.yaml";
  ASSERT_EQ(testing::RunTool({"generate", "--agents=6", "--out=" + masked}).status, 0);
  umask(old_mask);
  EXPECT_EQ(ModeOf(out), 0600u);
  EXPECT_EQ(ModeOf(fresh), 0644u);
  EXPECT_EQ(ModeOf(masked), 0640u);
  const std::string text = Slurp(out);
  ASSERT_GT(text.size(), 100u);
  EXPECT_EQ(text, Slurp(fresh));
  EXPECT_EQ(text.back(), '\n');
  // Nothing but the three outputs is left in the folder.
  EXPECT_EQ(Entries(dir), (std::vector<std::string>{"fresh.yaml", "g.yaml", "masked.yaml"}));
}

TEST(OutputFileWriter, StaleTemporariesOfAKilledRunAreRemoved) {
  const std::string dir = Folder("stale"), out = dir + "/g.yaml";
  const std::string stale = dir + "/.g.yaml.ccma-tmp-AbC123", recent = dir + "/.g.yaml.ccma-tmp-XyZ789";
  const std::string other = dir + "/.h.yaml.ccma-tmp-AbC123";
  // An old one whose writer (this test) still runs: a long run writes at its end.
  const std::string running = dir + "/.g.yaml.ccma-tmp-" + std::to_string(getpid()) + "-QwE456";
  const std::string dead = dir + "/.g.yaml.ccma-tmp-999999999-QwE456";  // above any pid_max
  for (const std::string& f : {stale, recent, other, running, dead}) std::ofstream(f) << "half\n";
  const timeval hour_ago[2] = {{time(nullptr) - 3600, 0}, {time(nullptr) - 3600, 0}};
  for (const std::string& f : {stale, other, running, dead}) ASSERT_EQ(utimes(f.c_str(), hour_ago), 0);
  ASSERT_EQ(testing::RunTool({"generate", "--agents=6", "--out=" + out}).status, 0);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(running));
  EXPECT_TRUE(fs::exists(recent));  // may belong to a run still going
  EXPECT_TRUE(fs::exists(other));   // another name's
}

TEST(OutputFileWriter, WorkspacePlotFolderNeverWritesThroughPlantedLinks) {
  const std::string dir = Folder("plot"), victim = Victim(dir), plots = dir + "/maps";
  fs::create_directories(plots);
  for (const char* name : {"workspace_slice.dat", "reachability.png", "sigma_min.png"}) {
    fs::create_symlink(victim, plots + "/" + name);
  }
  const testing::ToolRun r =
      testing::RunTool({"workspace", "--model=" + testing::ModelPath("4dof_reduced"), "--out=" + dir + "/w.csv",
                        "--z=0.5:0.95", "--yaw=-0.2:0.2", "--resolution=3", "--plot=" + plots});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(Slurp(victim), "secret\n");
  EXPECT_FALSE(fs::is_symlink(plots + "/workspace_slice.dat"));
  int lines = 0;
  std::ifstream dat(plots + "/workspace_slice.dat");
  for (std::string line; std::getline(dat, line);) ++lines;
  EXPECT_EQ(lines, 9);
  for (const std::string& name : Entries(plots)) EXPECT_EQ(name.rfind(".ccma-plot-", 0), std::string::npos) << name;
  if (r.out.find("reachability.png") != std::string::npos) {
    EXPECT_FALSE(fs::is_symlink(plots + "/reachability.png"));
    EXPECT_EQ(Slurp(plots + "/reachability.png").substr(1, 3), "PNG");
  }
}

// Plants a link to `victim` at every name of `names` in `dir`.
void PlantLinks(const std::string& dir, const std::string& victim, const std::vector<std::string>& names) {
  fs::create_directories(dir);
  for (const std::string& name : names) fs::create_symlink(victim, dir + "/" + name);
}

// After the run: the victim is untouched, every name is a regular file (the
// link replaced) that begins with `begins[name]` when given, and no scratch
// folder is left.
void ExpectLinksReplaced(const std::string& dir, const std::string& victim, const std::vector<std::string>& names,
                         const std::vector<std::pair<std::string, std::string>>& begins) {
  EXPECT_EQ(Slurp(victim), "secret\n");
  EXPECT_EQ(ModeOf(victim), 0600u);
  for (const std::string& name : names) {
    if (!fs::exists(fs::symlink_status(dir + "/" + name))) continue;  // a plot gnuplot did not draw
    EXPECT_FALSE(fs::is_symlink(dir + "/" + name)) << name;
  }
  for (const auto& [name, start] : begins) {
    ASSERT_FALSE(fs::is_symlink(dir + "/" + name)) << name;
    EXPECT_EQ(Slurp(dir + "/" + name).rfind(start, 0), 0u) << name;
  }
  for (const std::string& name : Entries(dir)) EXPECT_EQ(name.rfind(".ccma-plot-", 0), std::string::npos) << name;
}

TEST(OutputFileWriter, BenchFolderNeverWritesThroughPlantedLinks) {
  const std::string dir = Folder("bench"), victim = Victim(dir), out = dir + "/out";
  const std::vector<std::string> names = {
      "models.md", "4dof_reduced_steps.csv", "4dof_reduced_convergence_lm.dat", "4dof_reduced_convergence_bfgs.dat",
      "convergence_lm.gnuplot", "convergence_bfgs.gnuplot", "convergence_lm.png", "convergence_lm.svg",
      "convergence_bfgs.png", "convergence_bfgs.svg"};
  PlantLinks(out, victim, names);
  const testing::ToolRun r =
      testing::RunTool({"bench", "--model=" + testing::ModelPath("4dof_reduced"), "--steps=1", "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  ExpectLinksReplaced(out, victim, names,
                      {{"models.md", "Machine: "},
                       {"4dof_reduced_steps.csv", "step,method,gradient"},
                       {"4dof_reduced_convergence_lm.dat", "# time_ms objective error"}});
  // The JSON names the files in --out, not in the scratch folder.
  if (r.out.find("convergence_lm.png") != std::string::npos) {
    EXPECT_NE(r.out.find("\"" + out + "/convergence_lm.png\""), std::string::npos) << r.out;
  }
}

TEST(OutputFileWriter, ReplayFolderNeverWritesThroughPlantedLinks) {
  const std::string dir = Folder("replay"), victim = Victim(dir), out = dir + "/out";
  const std::vector<std::string> names = {"end_effector.csv", "bases.csv", "rmse.md", "replay.gnuplot",
                                          "end_effector.png", "end_effector.svg", "bases_xy.png", "bases_xy.svg"};
  PlantLinks(out, victim, names);
  const testing::ToolRun r =
      testing::RunTool({"replay", "--model=" + testing::ModelPath("4dof_reduced"),
                        "--waypoints=" + std::string(CCMA_MODELS_DIR) + "/paths/4dof_sequential.csv", "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  ExpectLinksReplaced(out, victim, names,
                      {{"end_effector.csv", "# SIMULATION (ccma replay)"},
                       {"bases.csv", "# SIMULATION (ccma replay)"},
                       {"rmse.md", ""}});
  EXPECT_NE(r.out.find("\"" + out + "/rmse.md\""), std::string::npos) << r.out;
  EXPECT_GT(Slurp(out + "/rmse.md").size(), 100u);
}

// An --out folder that cannot be written into stops the run before any work.
TEST(OutputFileWriter, ReplayIntoAnUnwritableFolderIsRefused) {
  if (geteuid() == 0) GTEST_SKIP() << "root writes into any folder";
  const std::string dir = Folder("readonly") + "/out";
  fs::create_directories(dir);
  chmod(dir.c_str(), 0500);
  const testing::ToolRun r =
      testing::RunTool({"replay", "--model=" + testing::ModelPath("4dof_reduced"),
                        "--waypoints=" + std::string(CCMA_MODELS_DIR) + "/paths/4dof_sequential.csv", "--out=" + dir});
  chmod(dir.c_str(), 0700);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(r.out.empty());
}

// issue 49: Ctrl-C or SIGTERM in the middle of a long map left the hidden
// temporary output (`.map.csv.ccma-tmp-<pid>-XXXXXX`, 245 MB seen) behind.
// The run still dies by the signal (a shell: 130 or 143), with nothing left
// in the folder: no CSV, no temporary; with a store, no temporary tile.
TEST(OutputFileWriter, ASignalLeavesNoTemporaryBehind) {
  int round = 0;
  for (const int sig : {SIGTERM, SIGINT}) {
    for (const bool store : {false, true}) {
      SCOPED_TRACE(std::string(sig == SIGTERM ? "SIGTERM" : "SIGINT") + (store ? " with a store" : ""));
      const std::string dir = Folder("signal_" + std::to_string(round++));
      // 200 x 200 samples: minutes of work, stopped as soon as its output exists.
      std::vector<std::string> args = {"workspace", "--model=" + testing::ModelPath("4dof_reduced"),
                                       "--out=" + dir + "/map.csv", "--x=-0.35:0.35", "--z=0.35:1.0",
                                       "--resolution=200", "--max_minutes=10080"};  // a week: never refused here
      if (store) args.push_back("--store=" + dir + "/store");
      const pid_t pid = testing::SpawnTool(args, 300);
      auto temporaries = [&dir] {
        int n = 0;
        for (const std::string& name : Entries(dir)) n += name.find(".ccma-tmp-") != std::string::npos;
        return n;
      };
      // With a store, the map has started (a finished tile): the watch that
      // reports what the store keeps takes the signal then.
      auto started = [&dir, store, &temporaries] {
        if (temporaries() != 1) return false;
        if (!store || !fs::is_directory(dir + "/store")) return !store;
        for (const std::string& name : Entries(dir + "/store")) {
          if (name.rfind("tile_", 0) == 0) return true;
        }
        return false;
      };
      // Until then (a bound on the wait, not a timing assertion).
      for (int polls = 0; polls < 12000 && !started() && waitpid(pid, nullptr, WNOHANG) == 0; ++polls) usleep(5000);
      ASSERT_EQ(temporaries(), 1) << "the run wrote no temporary output";
      ASSERT_EQ(kill(pid, sig), 0);
      int raw = 0;
      ASSERT_EQ(waitpid(pid, &raw, 0), pid);
      ASSERT_TRUE(WIFSIGNALED(raw)) << "exit status " << WEXITSTATUS(raw);
      EXPECT_EQ(WTERMSIG(raw), sig);
      EXPECT_EQ(temporaries(), 0) << "a temporary left in " << dir;
      EXPECT_FALSE(fs::exists(dir + "/map.csv"));
      if (store) {
        for (const std::string& name : Entries(dir + "/store")) {
          EXPECT_EQ(name.find("ccma-tmp"), std::string::npos) << name;
        }
      }
    }
  }
}

}  // namespace
}  // namespace ccma
