// Running the `ccma` tool from a test: an argument vector (no shell), stdout
// and stderr captured through files, killed after a timeout. CCMA_TOOL_PATH
// is defined by tests/CMakeLists.txt.
#ifndef CCMA_TESTS_TOOL_RUN_H_
#define CCMA_TESTS_TOOL_RUN_H_

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace ccma::testing {

// How much longer the sanitized builds may take (scripts/sanitize.sh): a
// test's bound on how long a refusal takes is multiplied by it.
#ifdef CCMA_TEST_TIME_FACTOR
constexpr double kTestTimeFactor = CCMA_TEST_TIME_FACTOR;
#else
constexpr double kTestTimeFactor = 1;
#endif

struct ToolRun {
  int status = -1;  // exit status, or -1 if killed
  std::string out, err;
  double seconds = 0;
  long peak_rss_kb = 0;  // the child's largest resident set [KiB] (wait4's ru_maxrss)
};

inline std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Starts the tool with `args` and returns at once with its pid: stdout and
// stderr to the files `out` and `err` (created, truncated), killed by
// SIGALRM after `timeout_s` (a hang ends), `in_child` run in the child just
// before the tool starts (a resource limit, say). The caller waits for it.
inline pid_t SpawnTool(const std::vector<std::string>& args, int timeout_s, const std::string& out = "/dev/null",
                       const std::string& err = "/dev/null", void (*in_child)() = nullptr) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (in_child != nullptr) in_child();
    const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    dup2(o, 1);
    dup2(e, 2);
    alarm(static_cast<unsigned>(timeout_s));  // SIGALRM ends a hang
    std::vector<char*> argv = {const_cast<char*>(CCMA_TOOL_PATH)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(CCMA_TOOL_PATH, argv.data());
    _exit(127);
  }
  return pid;
}

// `in_child` as for SpawnTool (e.g. an RLIMIT_AS, so that a run which would
// allocate more fails with bad_alloc instead of taking the machine's memory).
inline ToolRun RunTool(const std::vector<std::string>& args, int timeout_s = 120, void (*in_child)() = nullptr) {
  const std::string dir = ::testing::TempDir();
  const std::string tag = std::to_string(getpid());
  const std::string out = dir + "/tool_out_" + tag, err = dir + "/tool_err_" + tag;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = SpawnTool(args, timeout_s, out, err, in_child);
  int raw = 0;
  struct rusage usage {};
  wait4(pid, &raw, 0, &usage);
  ToolRun r;
  r.peak_rss_kb = usage.ru_maxrss;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = Slurp(out);
  r.err = Slurp(err);
  return r;
}

// A bundled model file's path (models/NAME.yaml).
inline std::string ModelPath(const std::string& name) { return std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"; }

// This test process's own scratch folder, TempDir()/ccma_test_PID (created):
// ctest runs every test in a process of its own, two at a time, so files in
// TempDir() itself (path.csv, rows.csv) would be written by two tests at once.
inline std::string TestDir() {
  const std::string dir = ::testing::TempDir() + "/ccma_test_" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  return dir;
}

// A path in this test process's own scratch folder TempDir()/PREFIX_PID (created).
inline std::string ScratchPath(const std::string& prefix, const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/" + prefix + "_" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  return dir + "/" + name;
}

}  // namespace ccma::testing

#endif  // CCMA_TESTS_TOOL_RUN_H_
