// `ccma replay` (and bench's plots) as a user runs them: hostile output
// folders, failures that must be reported, inputs that must be refused
// quickly, and the plots of the paper's model and of 48 agents.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/tool_run.h"

namespace replay_cli_test {

namespace fs = std::filesystem;

struct ToolRun {
  int status;  // exit status; -1 if killed (e.g. by the timeout)
  std::string out, err;
  double seconds;
};

std::string Slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(ccma::testing::TestDir()) / ("replay_cli_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs the tool with `args` (no shell: arguments go through unchanged) in
// the working directory `cwd`; kills it after `timeout_s` seconds.
ToolRun Ccma(const std::vector<std::string>& args, const fs::path& cwd, double timeout_s = 120) {
  const fs::path out = cwd / "stdout.txt", err = cwd / "stderr.txt";
  std::vector<std::string> argv_strings = {CCMA_TOOL_PATH};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_strings) argv.push_back(a.data());
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (o < 0 || e < 0 || chdir(cwd.c_str()) != 0) _exit(127);
    dup2(o, 1);
    dup2(e, 2);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int raw = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &raw, WNOHANG);
    if (done == pid) break;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > timeout_s) {
      kill(pid, SIGKILL);
      waitpid(pid, &raw, 0);
      ADD_FAILURE() << "ccma did not finish within " << timeout_s << " s";
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, Slurp(out), Slurp(err), seconds};
}

std::string Models() { return CCMA_MODELS_DIR; }
std::string Model(const std::string& name) { return "--model=" + Models() + "/" + name + ".yaml"; }
std::string Path(const std::string& name) { return "--waypoints=" + Models() + "/paths/" + name + ".csv"; }

bool HaveGnuplot() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path != nullptr ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && access((dir + "/gnuplot").c_str(), X_OK) == 0) return true;
  }
  return false;
}

int CountLines(const std::string& text, const std::string& prefix) {
  int n = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
  return n;
}

// The attack of a single quote in --out: gnuplot's script used to name the
// folder between single quotes, so this made gnuplot run `touch PWNED`.
const char kOddName[] = "odd'.system('touch PWNED').'";

TEST(ReplayCli, AQuoteInOutRunsNoCommandAndThePlotsGoIntoThatFolder) {
  const fs::path cwd = FreshDir("odd_out");
  const fs::path out = cwd / kOddName;
  const ToolRun r = Ccma({"replay", Model("4dof_reduced"), Path("4dof_combined"), "--out=" + out.string(),
                          "--noise=none"},
                         cwd);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(cwd / "PWNED"));
  EXPECT_FALSE(fs::exists(out / "PWNED"));
  EXPECT_TRUE(fs::exists(out / "end_effector.csv"));
  EXPECT_TRUE(fs::exists(out / "rmse.md"));
  const auto j = nlohmann::json::parse(r.out);
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot is not installed: plots not checked";
  EXPECT_EQ(j["plots"].size(), 4u) << r.err;
  for (const char* f : {"end_effector.png", "end_effector.svg", "bases_xy.png", "bases_xy.svg"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
}

TEST(ReplayCli, AQuoteInBenchOutRunsNoCommand) {
  const fs::path cwd = FreshDir("odd_bench");
  const fs::path out = cwd / kOddName;
  const ToolRun r = Ccma({"bench", Model("4dof_reduced"), "--steps=2", "--out=" + out.string()}, cwd);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(cwd / "PWNED"));
  EXPECT_FALSE(fs::exists(out / "PWNED"));
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot is not installed: plots not checked";
  EXPECT_TRUE(fs::exists(out / "convergence_lm.png")) << r.err;
  EXPECT_TRUE(fs::exists(out / "convergence_bfgs.svg")) << r.err;
}

// 1 s of motion-capture and radio latency: the PI loops oscillate and the
// bases tear the chain apart (the cheapest torn case; 20 s is outside the
// documented range of latencies, see TooLongLatencyIsRefused).
TEST(ReplayCli, ATornChainIsReportedOnStderrInTheTableAndInJson) {
  const fs::path cwd = FreshDir("torn");
  const ToolRun r = Ccma({"replay", Model("4dof_reduced"), Path("4dof_sequential"), "--out=" + (cwd / "r").string(),
                          "--latency_s=1"},
                         cwd);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["torn"], true);
  EXPECT_EQ(j["trustworthy"], false);
  EXPECT_GT(j["torn_samples"].get<int>(), 0);
  EXPECT_GT(j["max_residual_energy"].get<double>(), j["torn_residual_energy"].get<double>());
  EXPECT_TRUE(j["first_torn_time_s"].is_number());
  EXPECT_NE(j["warning"].get<std::string>().find("chain torn"), std::string::npos);
  EXPECT_EQ(CountLines(r.err, "ccma replay: warning: chain torn"), 1) << r.err;
  EXPECT_EQ(CountLines(r.err, "ccma replay: warning:"), 1) << r.err;  // converged: no other warning
  EXPECT_NE(r.err.find("worst E = "), std::string::npos);
  EXPECT_EQ(CountLines(r.err, "WARNING: NOT TRUSTWORTHY"), 1) << r.err;
  EXPECT_EQ(Slurp(cwd / "r" / "rmse.md").rfind("WARNING: NOT TRUSTWORTHY", 0), 0u);
  EXPECT_NE(Slurp(cwd / "r" / "end_effector.csv").find(",1\n"), std::string::npos);  // torn rows
}

TEST(ReplayCli, AnUnreachableWaypointIsReported) {
  const fs::path cwd = FreshDir("unreachable");
  std::ofstream(cwd / "path.csv") << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n2,0,0,0.65,0,0,0\n"
                                     "4,0,0,1.5,0,0,0\n";
  const ToolRun r = Ccma({"replay", Model("4dof_reduced"), "--waypoints=" + (cwd / "path.csv").string(),
                          "--out=" + (cwd / "r").string()},
                         cwd);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["converged"], false);
  EXPECT_EQ(j["trustworthy"], false);
  EXPECT_TRUE(j["failed_step_time_s"].is_number());
  EXPECT_GT(j["failed_step_time_s"].get<double>(), 2.0);
  EXPECT_NE(j["warning"].get<std::string>().find("not converged"), std::string::npos);
  EXPECT_EQ(CountLines(r.err, "ccma replay: warning: not converged"), 1) << r.err;
  EXPECT_NE(r.err.find("waypoint 2"), std::string::npos) << r.err;  // the library's message
  EXPECT_EQ(Slurp(cwd / "r" / "rmse.md").rfind("WARNING: NOT TRUSTWORTHY", 0), 0u);
}

struct Refused {
  std::string what;
  std::vector<std::string> args;
  std::string message;  // expected in stderr
};
void PrintTo(const Refused& r, std::ostream* os) { *os << r.what; }

class ReplayRefuses : public ::testing::TestWithParam<Refused> {};

TEST_P(ReplayRefuses, ExitsTwoQuicklyWithAMessageAndNothingOnStdout) {
  const fs::path cwd = FreshDir("refused");
  std::ofstream(cwd / "huge.csv") << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n1e308,0,0,0.6,0,0,0\n";
  std::ofstream(cwd / "long.csv") << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n1e6,0,0,0.6,0,0,0\n";
  std::vector<std::string> args = {"replay", Model("4dof_reduced"), "--out=" + (cwd / "r").string()};
  bool has_path = false;
  for (const std::string& a : GetParam().args) {
    args.push_back(a.rfind("@", 0) == 0 ? "--waypoints=" + (cwd / a.substr(1)).string() : a);
    has_path |= a.rfind("@", 0) == 0 || a.rfind("--waypoints", 0) == 0;
  }
  if (!has_path) args.push_back(Path("4dof_combined"));
  const ToolRun r = Ccma(args, cwd, 30);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
  EXPECT_LT(r.seconds, 10);
  EXPECT_FALSE(fs::exists(cwd / "r")) << "refused input must not create the output folder";
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ReplayRefuses,
    ::testing::Values(Refused{"waypoint at 1e308 s", {"@huge.csv"}, "must lie in"},
                      Refused{"waypoint at 1e6 s", {"@long.csv"}, "controller ticks"},
                      Refused{"controller at 1e-300 Hz", {"--controller_hz=1e-300"}, "rate_hz"},
                      Refused{"controller at 1e5 Hz", {"--controller_hz=1e5"}, "[1, 10000] Hz"},
                      Refused{"latency of 20 s", {"--latency_s=20"}, "latency"},
                      Refused{"negative latency", {"--latency_s=-1"}, "latency"},
                      Refused{"negative noise", {"--mocap_noise_m=-5"}, "position_sigma"},
                      Refused{"slip of 1", {"--slip=1"}, "slip"},
                      Refused{"zero wheel speed", {"--max_wheel_speed=0"}, "max_wheel_speed"},
                      Refused{"negative ki", {"--ki=-1"}, "ki_position"}),
    [](const auto& info) {
      std::string n = info.param.what;
      for (char& c : n) if (!isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

TEST(ReplayCli, ZeroNoiseKeepsTheDocumentedAccuracyAndReportsControlledComponentsOnly) {
  const fs::path cwd = FreshDir("zero_noise");
  const ToolRun r = Ccma({"replay", Model("4dof_reduced"), Path("4dof_sequential"),
                          "--out=" + (cwd / "r").string(), "--noise=none"},
                         cwd);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["converged"], true);
  EXPECT_EQ(j["torn"], false);
  EXPECT_EQ(j["trustworthy"], true);
  EXPECT_FALSE(j.contains("warning"));
  EXPECT_EQ(r.err.find("WARNING"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_GT(j["samples"].get<int>(), 1000);
  for (const char* key : {"x_mm", "y_mm", "z_mm"}) EXPECT_LT(j["rmse"][key].get<double>(), 1.0) << key;
  EXPECT_LT(j["rmse"]["yaw_rad"].get<double>(), 1e-3);
  EXPECT_FALSE(j["rmse"].contains("roll_rad"));  // 4dof_reduced does not control roll and pitch
  EXPECT_FALSE(j["rmse"].contains("pitch_rad"));
  EXPECT_EQ(j["paper_hardware_rmse"].size(), 3u);
  EXPECT_NE(r.err.find("| source | y [mm] | z [mm] | x [mm] | yaw [rad] |"), std::string::npos) << r.err;
}

TEST(ReplayCli, FortyEightAgentsReplayWithReadablePlots) {
  const fs::path cwd = FreshDir("agents48");
  std::ofstream(cwd / "g48.yaml").flush();  // generate overwrites (a new name is meant to work too)
  const ToolRun generated = Ccma({"generate", "--agents=48", "--out=" + (cwd / "g48.yaml").string()}, cwd);
  ASSERT_EQ(generated.status, 0) << generated.err;
  std::ofstream(cwd / "path.csv") << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n2,0.01,0,0.6,0,0,0\n";
  const ToolRun r = Ccma({"replay", "--model=" + (cwd / "g48.yaml").string(),
                          "--waypoints=" + (cwd / "path.csv").string(), "--out=" + (cwd / "r").string()},
                         cwd, 60);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_LT(r.seconds, 30);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["converged"], true);
  EXPECT_EQ(j["torn"], false) << j["max_residual_energy"];
  EXPECT_EQ(j["rmse"].size(), 6u);  // all six components are controlled
  EXPECT_FALSE(j.contains("paper_hardware_rmse"));
  EXPECT_EQ(Slurp(cwd / "r" / "rmse.md").find("paper"), std::string::npos);
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot is not installed: plots not checked";
  EXPECT_EQ(j["plots"].size(), 4u) << r.err;
  // One colour per base and no 96-entry key.
  const std::string script = Slurp(cwd / "r" / "replay.gnuplot");
  EXPECT_EQ(script.find("title 'base"), std::string::npos);
  EXPECT_NE(script.find("set size ratio -1"), std::string::npos);
  EXPECT_TRUE(fs::exists(cwd / "r" / "bases_xy.png"));
}

}  // namespace
