// Hostile input and loud failures, as a user or an attacker meets them through
// the `ccma` tool: every finding of the hardening issue reproduced and shown
// fixed (exit 2 with a message and nothing on stdout; warnings on stderr; no
// null or NaN printed; output files that never replace links or devices).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/tool_run.h"

namespace hostile_cli_test {

namespace fs = std::filesystem;

struct ToolRun {
  int status = -1;  // exit status, or -1 if killed
  std::string out, err;
  double seconds = 0;
};

std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs the tool with an argument vector (no shell), killed after `timeout_s`.
ToolRun Ccma(const std::vector<std::string>& args, int timeout_s = 60) {
  const std::string dir = ccma::testing::TestDir();
  const std::string tag = std::to_string(getpid());
  const std::string out = dir + "/hostile_out_" + tag, err = dir + "/hostile_err_" + tag;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
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
  int raw = 0;
  waitpid(pid, &raw, 0);
  ToolRun r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = Slurp(out);
  r.err = Slurp(err);
  return r;
}

std::string ModelFlag(const std::string& name) {
  return std::string("--model=") + CCMA_MODELS_DIR + "/" + name + ".yaml";
}

std::string Scratch(const std::string& name) {
  const std::string dir = ccma::testing::TestDir() + "/hostile_" + std::to_string(getpid());
  fs::create_directories(dir);
  return dir + "/" + name;
}

// Bad input: exit 2, a message on stderr that mentions `what`, nothing on stdout.
void ExpectRefused(const ToolRun& r, const std::string& what) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
}

// A JSON result that never prints null or NaN as a number.
nlohmann::json ParseClean(const ToolRun& r) {
  EXPECT_EQ(r.out.find("null"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  return nlohmann::json::parse(r.out);
}

const std::string kNineZeros = "0,0,0,0,0,0,0,0,0";

TEST(HostileNumbers, HugeControlsAreRefused) {
  for (const std::string big : {"1e9", "1e308", "-3e4"}) {
    ExpectRefused(Ccma({"simulate", ModelFlag("4dof_reduced"), "--controls=" + big + ",0,0,0,0,0,0,0,0"}),
                  "--controls");
    ExpectRefused(Ccma({"control", ModelFlag("4dof_reduced"), "--target=0,0,0.6,0,0,0",
                        "--controls=" + big + ",0,0,0,0,0,0,0,0"}),
                  "--controls");
  }
}

TEST(HostileNumbers, HugeTargetsAreRefused) {
  for (const std::string big : {"1e9", "1e308"}) {
    ExpectRefused(Ccma({"control", ModelFlag("4dof_reduced"), "--target=" + big + ",0,0.6,0,0,0"}), "--target");
  }
}

TEST(HostileNumbers, TinyOrEndlessStepsAreRefused) {
  ExpectRefused(Ccma({"control", ModelFlag("4dof_reduced"), "--target=0.1,0,0.6,0,0,0", "--max_step_m=1e-300"}),
                "max_step_m");
  // Allowed step, but a path of more than 100000 steps: refused up front.
  const ToolRun r = Ccma({"control", ModelFlag("4dof_reduced"), "--target=9000,0,0.6,0,0,0", "--max_step_m=1e-6"});
  ExpectRefused(r, "steps");
  EXPECT_LT(r.seconds, 10 * ccma::testing::kTestTimeFactor);
}

TEST(HostileFiles, DevZeroAsModelIsRefusedAtOnce) {
  const ToolRun r = Ccma({"check", "--model=/dev/zero"}, 20);
  ExpectRefused(r, "not a regular file");
  EXPECT_LT(r.seconds, 5 * ccma::testing::kTestTimeFactor);
}

TEST(HostileFiles, AQuoteInANameIsRefusedBeforeAnythingRuns) {
  std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const std::string from = "name: base0,";
  text.replace(text.find(from), from.size(), "name: \"b0'.system('touch X').'\",");
  const std::string model = Scratch("quoted.yaml");
  std::ofstream(model) << text;
  const ToolRun r = Ccma({"check", "--model=" + model});
  ExpectRefused(r, "must be 1-64 characters from [A-Za-z0-9_-]");
}

// A misspelt key is bad input: exit 2, the unknown key and a suggestion,
// nothing on stdout.
TEST(HostileFiles, AMisspeltKeyIsRefusedWithASuggestion) {
  std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const std::string from = "{type: revolute, between: [post1, link1]";
  text.replace(text.find(from), from.size(), "{type: revolute, betwen: [post1, link1]");
  const std::string model = Scratch("misspelt.yaml");
  std::ofstream(model) << text;
  const ToolRun r = Ccma({"check", "--model=" + model});
  ExpectRefused(r, model + ":23: joints[4]: unknown key 'betwen' (did you mean 'between'?)");
}

// issue 49: yaml-cpp reads a file's first YAML document and ignores the
// rest, malformed or not. A model (or obstacles) file holds one document: a
// second is refused naming the line that starts it, and a malformed one
// naming its own line.
TEST(HostileFiles, YamlDocumentsAfterTheModelAreRefused) {
  const std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  struct Case {
    std::string tail, needle;
  };
  const std::vector<Case> cases = {
      {"---\nname: other\n", ":" + std::to_string(lines + 1) + ": a second YAML document: the file must hold exactly one"},
      {"\n# a comment\n--- \n", ":" + std::to_string(lines + 3) + ": a second YAML document"},
      {"...\nname: other\n", ":" + std::to_string(lines + 2) + ": a second YAML document"},
      {"---\n[unclosed\n", ":" + std::to_string(lines + 3) + ": not valid YAML"},
      {"...\n{a: [\n", ":" + std::to_string(lines + 3) + ": not valid YAML"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string model = Scratch("two_documents_" + std::to_string(i) + ".yaml");
    std::ofstream(model) << text << cases[i].tail;
    ExpectRefused(Ccma({"check", "--model=" + model}), model + cases[i].needle);
  }
  // One document between markers is one document.
  const std::string framed = Scratch("framed.yaml");
  std::ofstream(framed) << "---\n" << text << "...\n";
  const ToolRun ok = Ccma({"check", "--model=" + framed});
  EXPECT_EQ(ok.status, 0) << ok.err;
  const std::string obstacles = Scratch("obstacles.yaml");
  std::ofstream(obstacles) << "obstacles: []\n---\nobstacles: []\n";
  ExpectRefused(Ccma({"check", ModelFlag("4dof_reduced"), "--obstacles=" + obstacles}),
                obstacles + ":2: a second YAML document");
}

// Millimetres and degrees load, with one warning line per kind on stderr;
// stdout is the usual JSON and the exit status 0.
TEST(LoudFailures, ImplausibleMagnitudesWarnOnStderrOnly) {
  std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const std::string from = "pose: [0, 0.583012702, 1.570796327]";
  text.replace(text.find(from), from.size(), "pose: [0, 0.583012702, 90]");
  const std::string model = Scratch("degrees.yaml");
  std::ofstream(model) << text;
  const ToolRun r = Ccma({"check", "--model=" + model});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(ParseClean(r)["model"], "4dof_reduced");
  EXPECT_EQ(r.out.find("degrees"), std::string::npos) << r.out;
  // The loader's one warning line, then check's own note on this
  // over-actuated model (docs/cli.md, "Over-actuated by design").
  const std::string warning = "warning: " + model + ":14: mobile_bases[0].pose[2]: 90 rad is more than a full turn; "
                              "is the angle in degrees? (1 angle above 2 pi)\n";
  EXPECT_EQ(r.err.substr(0, warning.size()), warning);
  EXPECT_EQ(r.err.substr(warning.size()).rfind("ccma check: note: over-actuated by design", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 2) << r.err;
}

TEST(OutputFiles, ASymlinkStaysALinkAndItsTargetGetsTheCsv) {
  const std::string target = Scratch("target.csv"), link = Scratch("link.csv");
  std::ofstream(target) << "old\n";
  fs::remove(link);
  fs::create_symlink(target, link);
  const ToolRun r = Ccma({"trajectory", ModelFlag("4dof_reduced"),
                      std::string("--waypoints=") + CCMA_MODELS_DIR + "/paths/4dof_sequential.csv", "--out=" + link});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(Slurp(target).rfind("time_s,target_x_m,", 0), 0u);
  EXPECT_FALSE(fs::exists(target + ".partial." + std::to_string(getpid())));
}

TEST(OutputFiles, ADeviceIsWrittenInPlaceNeverReplaced) {
  const ToolRun r = Ccma({"trajectory", ModelFlag("4dof_reduced"),
                      std::string("--waypoints=") + CCMA_MODELS_DIR + "/paths/4dof_sequential.csv", "--out=/dev/null"});
  ASSERT_EQ(r.status, 0) << r.err;
  struct stat st {};
  ASSERT_EQ(stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(OutputFiles, ADirectoryIsRefused) {
  const std::string dir = Scratch("a_directory");
  fs::create_directories(dir);
  ExpectRefused(Ccma({"trajectory", ModelFlag("4dof_reduced"),
                      std::string("--waypoints=") + CCMA_MODELS_DIR + "/paths/4dof_sequential.csv", "--out=" + dir}),
                "is a directory");
  ExpectRefused(Ccma({"generate", "--agents=6", "--out=" + dir}), "is a directory");
}

TEST(OutputFiles, TrajectoryHeadersCarryUnits) {
  const std::string csv = Scratch("units.csv");
  ASSERT_EQ(Ccma({"trajectory", ModelFlag("4dof_reduced"),
                  std::string("--waypoints=") + CCMA_MODELS_DIR + "/paths/4dof_combined.csv", "--out=" + csv})
                .status,
            0);
  const std::string header = Slurp(csv).substr(0, Slurp(csv).find('\n'));
  std::stringstream columns(header);
  for (std::string column; std::getline(columns, column, ',');) {
    const bool has_unit = column.size() > 2 &&
                          (column.rfind("_s") == column.size() - 2 || column.rfind("_m") == column.size() - 2 ||
                           column.rfind("_rad") == column.size() - 4 || column.rfind("_m2") == column.size() - 3 ||
                           column.rfind("_ms") == column.size() - 3 || column == "iterations" ||
                           column == "reached" || column == "error_m_or_rad" || column == "limits_violated");
    EXPECT_TRUE(has_unit) << column;
  }
}

TEST(LoudFailures, CheckWarnsWhenTheMechanismIsNotRigid) {
  // Spherical joints at both ends of the legs: every leg spins about itself.
  std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/6dof_six_agents.yaml");
  size_t at = 0;
  int replaced = 0;
  while ((at = text.find("type: revolute", at)) != std::string::npos) {
    const size_t line_end = text.find('\n', at);
    if (text.substr(at, line_end - at).find("axis: [0, 0, 1]") == std::string::npos) {
      text.replace(at, 14, "type: spherical");
      ++replaced;
    }
    at += 14;
  }
  ASSERT_GT(replaced, 0);
  const std::string model = Scratch("floppy.yaml");
  std::ofstream(model) << text;
  const ToolRun r = Ccma({"check", "--model=" + model});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = ParseClean(r);
  EXPECT_EQ(j["rigid_with_controls_fixed"], false);
  EXPECT_NE(r.err.find("ccma check: warning: not rigid with its controls fixed"), std::string::npos) << r.err;
}

TEST(LoudFailures, SimulateWarnsWhenItCannotAssembleWithNumbersInPercentG) {
  // One base of an over-actuated system moved alone: unreachable.
  const ToolRun r = Ccma({"simulate", ModelFlag("4dof_reduced"),
                      "--controls=0.05,0.583012702,1.570796327,-0.504903811,-0.291506351,-2.617993878,0.504903811,"
                      "-0.291506351,-0.523598776"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = ParseClean(r);
  EXPECT_EQ(j["assembled"], false);
  EXPECT_NE(r.err.find("ccma simulate: warning: not assembled: residual energy "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("0.000000"), std::string::npos) << r.err;
}

TEST(LoudFailures, AnUnreachableControlTargetWarnsWithPercentG) {
  const ToolRun r = Ccma({"control", ModelFlag("4dof_reduced"), "--target=0,0,0.95,0,0,0"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = ParseClean(r);
  EXPECT_EQ(j["converged"], false);
  EXPECT_NE(r.err.find("ccma control: warning: path step"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("0.000000"), std::string::npos) << r.err;
}

// 4dof_reduced turned half a turn: the controls that control finds assemble
// on another branch when simulated from home. Control says so, and simulate
// --from reproduces its configuration exactly.
TEST(Branches, ControlWarnsAndSimulateFromReproduces) {
  const ToolRun c = Ccma({"control", ModelFlag("4dof_reduced"), "--target=0,0,0.6,0,0,3.14159"});
  ASSERT_EQ(c.status, 0) << c.err;
  const nlohmann::json control = ParseClean(c);
  EXPECT_EQ(control["converged"], true);
  EXPECT_EQ(control["from_home"]["reproducible"], false);
  EXPECT_GT(control["from_home"]["end_effector_distance_m"].get<double>(), 0.1);
  EXPECT_NE(c.err.find("assemble to another configuration"), std::string::npos) << c.err;

  const std::string saved = Scratch("control.json");
  std::ofstream(saved) << c.out;
  const ToolRun s = Ccma({"simulate", ModelFlag("4dof_reduced"), "--from=" + saved});
  ASSERT_EQ(s.status, 0) << s.err;
  const nlohmann::json simulated = ParseClean(s);
  EXPECT_EQ(simulated["assembled"], true);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(simulated["end_effector"]["position"][i].get<double>(),
                control["end_effector"]["position"][i].get<double>(), 1e-12);
  }
  // From home instead, the same controls report the jump on stderr.
  std::string controls;
  for (const auto& v : control["controls"]) controls += (controls.empty() ? "" : ",") + nlohmann::json(v).dump();
  const ToolRun h = Ccma({"simulate", ModelFlag("4dof_reduced"), "--controls=" + controls});
  ASSERT_EQ(h.status, 0) << h.err;
  EXPECT_NE(h.err.find("ccma simulate: warning:"), std::string::npos) << h.err;
}

TEST(Targets, OnlyTheControlledComponentsMayBeGiven) {
  const ToolRun r = Ccma({"control", ModelFlag("4dof_reduced"), "--target=0.01,-0.01,0.61,0.02"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = ParseClean(r);
  EXPECT_EQ(j["converged"], true);
  EXPECT_NEAR(j["end_effector"]["position"][2].get<double>(), 0.61, 1e-9);
  EXPECT_NEAR(j["end_effector"]["rpy"][2].get<double>(), 0.02, 1e-9);
  ExpectRefused(Ccma({"control", ModelFlag("4dof_reduced"), "--target=0.01,0.61,0.02"}), "x,y,z,yaw");
}

// A --from document nested 100,000 levels deep (200 KB) used to overflow the
// stack when its "model" was printed in the warning; it is refused, naming the file.
TEST(HostileFiles, DeeplyNestedFromIsRefusedWithoutACrash) {
  const std::string path = Scratch("deep.json");
  const int depth = 100000;
  std::ofstream(path) << "{\"model\": " << std::string(depth, '[') << std::string(depth, ']')
                      << ", \"controls\": [0,0,0,0,0,0,0,0,0], \"bodies\": []}";
  ASSERT_GT(fs::file_size(path), 200000u);
  const ToolRun r = Ccma({"simulate", ModelFlag("4dof_reduced"), "--from=" + path});
  ExpectRefused(r, path);
  EXPECT_NE(r.err.find("nested more than 64 levels"), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), 1000u);
  // 64 levels are still read (the model name is then not a string, only its type is shown).
  std::ofstream(path) << "{\"model\": " << std::string(63, '[') << std::string(63, ']') << "}";
  const ToolRun ok = Ccma({"simulate", ModelFlag("4dof_reduced"), "--from=" + path});
  ExpectRefused(ok, path + ": controls: expected 9 numbers");
  EXPECT_NE(ok.err.find("printed for model (a JSON array)"), std::string::npos) << ok.err;
}

// A --from document's model name is quoted, never dumped whole: at most 40
// characters, control characters escaped as \xNN.
TEST(HostileFiles, AFromModelNameIsQuotedShort) {
  const ToolRun home = Ccma({"simulate", ModelFlag("4dof_reduced")});
  ASSERT_EQ(home.status, 0) << home.err;
  nlohmann::json document = nlohmann::json::parse(home.out);
  document["model"] = "evil\x1b[2J" + std::string(100000, 'x');
  const std::string path = Scratch("long_name.json");
  std::ofstream(path) << document.dump();
  const ToolRun r = Ccma({"simulate", ModelFlag("4dof_reduced"), "--from=" + path});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["assembled"], true);
  const std::string expected = "printed for model \"evil\\x1b[2J" + std::string(32, 'x') + "...\", not '4dof_reduced'";
  EXPECT_NE(r.err.find(expected), std::string::npos) << r.err.substr(0, 300);
  EXPECT_LT(r.err.size(), 300u);
}

// issue 49: a flag value holding a terminal escape sequence (ESC ] 0 ; ...
// BEL retitles the terminal) is echoed escaped, in a message that names the
// command like every other: ccma COMMAND: --flag: ...
TEST(HostileFlags, ControlBytesInFlagValuesAreEscapedAndTheCommandNamed) {
  const std::string esc = "\x1b]0;pwned\x07";
  struct Case {
    std::vector<std::string> args;
    std::string starts, shows;
  };
  const std::vector<Case> cases = {
      {{"statics", ModelFlag("4dof_reduced"), "--wrench=1," + esc + ",3,0,0,0"}, "ccma statics: --wrench: ",
       "'\\x1b]0;pwned\\x07' is not a finite number"},
      {{"control", ModelFlag("4dof_reduced"), "--target=0,0," + esc}, "ccma control: --target: ",
       "'\\x1b]0;pwned\\x07' is not a finite number"},
      {{"control", ModelFlag("4dof_reduced"), "--target=0,0,0.6,0,0,0", "--method=" + esc}, "ccma control: --method: ",
       "'\\x1b]0;pwned\\x07' is not lm or bfgs"},
      {{"workspace", ModelFlag("4dof_reduced"), "--out=" + Scratch("w.csv"), "--z=" + esc}, "ccma workspace: --z: ",
       "got '\\x1b]0;pwned\\x07'"},
      {{"generate", "--agents=" + esc, "--out=" + Scratch("g.yaml")}, "ccma generate: bad value ",
       "'\\x1b]0;pwned\\x07'"},
      {{"simulate", ModelFlag("4dof_reduced"), "--" + esc + "=1"}, "ccma simulate: unknown flag ",
       "'--\\x1b]0;pwned\\x07'"},
      {{"simulate", ModelFlag("4dof_reduced"), esc}, "ccma simulate: unexpected argument ", "'\\x1b]0;pwned\\x07'"},
  };
  for (const Case& c : cases) {
    const ToolRun r = Ccma(c.args);
    ExpectRefused(r, c.shows);
    EXPECT_EQ(r.err.rfind(c.starts, 0), 0u) << r.err;
    for (char ch : r.err.substr(0, r.err.size() - 1)) {
      EXPECT_TRUE(static_cast<unsigned char>(ch) >= 0x20 && ch != 0x7f) << "a raw control byte in: " << r.err;
    }
  }
}

// issue 49: integer flags take plain decimal only; gflags alone read 0x10
// as 16 (and let strtol skip leading spaces).
TEST(HostileFlags, IntegerFlagsTakeDecimalDigitsOnly) {
  for (const std::string value : {"0x10", "0X10", " 16", "16 ", "1e1", "+", ""}) {
    const ToolRun r = Ccma({"generate", "--agents=" + value, "--out=" + Scratch("hex.yaml")});
    EXPECT_EQ(r.status, 2) << value << ": " << r.err;
    EXPECT_EQ(r.out, "") << value;
    EXPECT_NE(r.err.find("--agents"), std::string::npos) << r.err;
  }
  ExpectRefused(Ccma({"workspace", ModelFlag("4dof_reduced"), "--out=" + Scratch("w.csv"), "--z=0.5:0.7",
                      "--resolution=0x3"}),
                "bad value '0x3' for --resolution (a decimal integer");
  ExpectRefused(Ccma({"workspace", ModelFlag("4dof_reduced"), "--out=" + Scratch("w.csv"), "--z=0.5:0.7",
                      "--samples=5", "--seed=0x1f"}),
                "bad value '0x1f' for --seed");
  // Leading zeros are decimal, as gflags reads them: 010 agents are 10.
  const ToolRun ten = Ccma({"generate", "--agents=010", "--out=" + Scratch("ten.yaml")});
  ASSERT_EQ(ten.status, 0) << ten.err;
  EXPECT_EQ(nlohmann::json::parse(ten.out)["agents"], 10);
}

}  // namespace
