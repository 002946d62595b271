// The `ccma` tool as shared/cli.md fixes it: exit codes, stdout/stderr, keys.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <vector>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/tool_run.h"

namespace cli_test {

struct ToolRun {
  int status;
  std::string out, err;
};

std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

ToolRun Ccma(const std::string& args) {
  const std::string dir = ccma::testing::TestDir();
  // Unique per process: CTest runs these tests in parallel.
  const std::string tag = std::to_string(getpid());
  const std::string out = dir + "/ccma_out_" + tag + ".txt", err = dir + "/ccma_err_" + tag + ".txt";
  const std::string cmd = std::string(CCMA_TOOL_PATH) + " " + args + " >" + out + " 2>" + err;
  const int raw = std::system(cmd.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, Slurp(out), Slurp(err)};
}

std::string Model(const std::string& name) {
  return std::string("--model=") + CCMA_MODELS_DIR + "/" + name + ".yaml";
}

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = ccma::testing::TestDir() + "/" + std::to_string(getpid()) + "_" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(Cli, CheckPrintsTheContractKeys) {
  const ToolRun r = Ccma("check " + Model("4dof_reduced"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["model"], "4dof_reduced");
  EXPECT_EQ(j["bodies"], 10);
  EXPECT_EQ(j["mobile_bases"], 3);
  EXPECT_EQ(j["joints"], 9);
  EXPECT_EQ(j["state_size"], 60);
  EXPECT_EQ(j["controls"], 9);
  EXPECT_EQ(j["effective_controls"], 6);
  EXPECT_EQ(j["constraints"], 81);
  EXPECT_EQ(j["rigid_with_controls_fixed"], true);
  EXPECT_EQ(j["end_effector_dof"], 4);
  EXPECT_EQ(j["assembled_at_home"], true);
}

// `check` names the bodies and joints each free motion moves (JSON and stderr). Leg 2
// of 4dof_reduced without its joint to ee hangs from its base: its post
// spins carrying its link, and the link swings alone.
TEST(Cli, CheckNamesTheBodiesOfEachFreeMotion) {
  std::string text = Slurp(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  const size_t at = text.find("  - {type: revolute, between: [link2, ee]");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find('\n', at) + 1 - at);
  const ToolRun r = Ccma("check --model=" + WriteFile("loose_leg.yaml", text));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["rigid_with_controls_fixed"], false);
  EXPECT_EQ(j["dof_with_controls_fixed"], 2);
  // The post's joint (joint6, base2-post2) turns carrying the link; the link's (joint7) turns alone.
  EXPECT_EQ(j["free_motions"], nlohmann::json::parse(R"([{"bodies": ["post2", "link2"], "joints": ["joint6"]},
                                                         {"bodies": ["link2"], "joints": ["joint7"]}])"));
  EXPECT_NE(r.err.find("ccma check: warning: not rigid with its controls fixed: 2 free motion(s) remain"),
            std::string::npos) << r.err;
  // Neither motion moves the end-effector, which the other legs hold: idle.
  EXPECT_NE(r.err.find("): motion 1 moves post2, link2 (joints joint6); motion 2 moves link2 (joints joint7); none "
                       "moves the end-effector (idle motions, docs/numerics.md)"),
            std::string::npos) << r.err;
  // A rigid mechanism: the field is there, empty.
  const ToolRun rigid = Ccma("check " + Model("4dof_reduced"));
  ASSERT_EQ(rigid.status, 0) << rigid.err;
  EXPECT_EQ(nlohmann::json::parse(rigid.out)["free_motions"], nlohmann::json::array());
}

TEST(Cli, SimulatePrintsTheContractKeys) {
  const ToolRun r = Ccma("simulate " + Model("6dof_six_agents"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"model", "converged", "assembled", "residual_energy", "iterations",
                          "solve_time_ms", "controls", "end_effector"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["controls"].size(), 18u);
  EXPECT_EQ(j["assembled"], true);
  EXPECT_NEAR(j["end_effector"]["position"][2].get<double>(), 0.6, 1e-12);
  EXPECT_EQ(j["end_effector"]["rotation"].size(), 3u);
  EXPECT_EQ(j["end_effector"]["rpy"].size(), 3u);
}

TEST(Cli, SimulateMovesTheEndEffectorWithTheBases) {
  // Every base 5 cm along +y: the mechanism translates rigidly.
  const ToolRun r = Ccma("simulate " + Model("4dof_complete") +
                     " --controls=0,0.633012702,1.570796327,-0.504903811,-0.241506351,"
                     "-2.617993878,0.619801759,-0.307842712,-0.523598776");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["assembled"], true);
  EXPECT_LT(j["residual_energy"].get<double>(), 1e-20);
  EXPECT_NEAR(j["end_effector"]["position"][1].get<double>(), 0.05, 1e-10);
}

TEST(Cli, UnreachableControlsAreReportedNotForced) {
  const ToolRun r = Ccma("simulate " + Model("4dof_reduced") +
                     " --controls=0.02,0.583012702,1.570796327,-0.504903811,-0.291506351,"
                     "-2.617993878,0.504903811,-0.291506351,-0.523598776");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["assembled"], false);
  EXPECT_GT(j["residual_energy"].get<double>(), 1e-8);
}

TEST(Cli, ControlPrintsTheContractKeysAndReachesTheTarget) {
  const ToolRun r = Ccma("control " + Model("6dof_asymmetric") + " --target=0.02,0.01,0.61,0.01,-0.02,0.03");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"model", "converged", "assembled", "steps", "iterations", "objective",
                          "residual_energy", "solve_time_ms", "target", "controls", "end_effector"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["converged"], true);
  // 24.5 mm needs 3 steps of 10 mm; the rotation of |(0.01, -0.02, 0.03)| ~ 0.0374 rad
  // needs 8 of 0.005 rad: the larger count wins.
  EXPECT_EQ(j["steps"], 8);
  EXPECT_NEAR(j["end_effector"]["position"][0].get<double>(), 0.02, 1e-9);
  EXPECT_NEAR(j["end_effector"]["rpy"][2].get<double>(), 0.03, 1e-9);
  EXPECT_LT(j["residual_energy"].get<double>(), 1e-20);
}

TEST(Cli, ControlReportsAnUnreachableTarget) {
  const ToolRun r = Ccma("control " + Model("4dof_reduced") + " --target=0,0,1.5,0,0,0");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["converged"], false);
  EXPECT_TRUE(j.contains("warning"));
  EXPECT_NE(r.err.find("warning"), std::string::npos);
}

TEST(Cli, TrajectoryWritesOneRowPerStep) {
  const std::string out = ccma::testing::TestDir() + "/" + std::to_string(getpid()) + "_traj.csv";
  const ToolRun r = Ccma("trajectory " + Model("4dof_complete") + " --waypoints=" + CCMA_MODELS_DIR +
                         "/paths/4dof_combined.csv --out=" + out);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["converged"], true);
  EXPECT_LT(j["max_residual_energy"].get<double>(), 1e-16);
  std::ifstream csv(out);
  std::string line;
  int rows = -1;  // header
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, j["steps"].get<int>());
}

TEST(Cli, GenerateWritesAModelThatChecks) {
  const std::string out = ccma::testing::TestDir() + "/" + std::to_string(getpid()) + "_gen.yaml";
  ASSERT_EQ(Ccma("generate --agents=12 --out=" + out).status, 0);
  const ToolRun r = Ccma("check --model=" + out);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["mobile_bases"], 12);
  EXPECT_EQ(j["state_size"], 6 * (1 + 3 * 12));
  EXPECT_EQ(j["rigid_with_controls_fixed"], true);
  EXPECT_EQ(j["end_effector_dof"], 6);
}

TEST(Cli, BenchPrintsTheStudyAndWritesItsFiles) {
  const std::string dir = ccma::testing::TestDir() + "/" + std::to_string(getpid()) + "_bench";
  const ToolRun r = Ccma("bench " + Model("4dof_reduced") + " --steps=2 --out=" + dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["model"], "4dof_reduced");
  EXPECT_EQ(j["steps"], 2);
  for (const char* loop : {"lm", "bfgs"}) {
    EXPECT_GT(j["control_ms"][loop]["median"].get<double>(), 0) << loop;
    EXPECT_TRUE(j["control_ms"][loop].contains("p95"));
    EXPECT_TRUE(j["control_ms"][loop].contains("median_iterations"));
  }
  EXPECT_GT(j["forward_us"]["median"].get<double>(), 0);
  EXPECT_GE(j["forward_us"]["p95"].get<double>(), j["forward_us"]["median"].get<double>());
  // Times are reported, not compared: which is faster is measured in
  // benchmarks (benchmarks/RESULTS.md), not asserted on a loaded machine.
  EXPECT_GT(j["finite_difference_ms"]["median"].get<double>(), 0);
  EXPECT_GT(j["jacobian_us"]["autodiff"].get<double>(), 0);
  EXPECT_GT(j["jacobian_us"]["analytic"].get<double>(), 0);
  for (const char* key : {"cpu", "cores", "build_type"}) EXPECT_TRUE(j["machine"].contains(key)) << key;
  EXPECT_TRUE(std::ifstream(dir + "/4dof_reduced_steps.csv").good());
  EXPECT_TRUE(std::ifstream(dir + "/4dof_reduced_convergence_bfgs.dat").good());
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
    for (const char* f : {"/convergence_lm.png", "/convergence_lm.svg", "/convergence_bfgs.png", "/convergence_bfgs.svg"}) {
      EXPECT_TRUE(std::ifstream(dir + f).good()) << f;
    }
  } else {
    EXPECT_NE(r.err.find("gnuplot not found"), std::string::npos) << r.err;
  }
}

TEST(Cli, ReplayWritesSimulationLabelledOutputs) {
  const std::string dir = ccma::testing::TestDir() + "/" + std::to_string(getpid()) + "_replay";
  const ToolRun r = Ccma("replay " + Model("4dof_complete") + " --waypoints=" + CCMA_MODELS_DIR +
                         "/paths/4dof_combined.csv --out=" + dir + " --noise=none");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["simulation"], true);
  EXPECT_LT(j["rmse"]["x_mm"].get<double>(), 1.0);
  EXPECT_LT(j["rmse"]["yaw_rad"].get<double>(), 1e-3);
  EXPECT_EQ(j["paper_hardware_rmse"].size(), 3u);
  EXPECT_EQ(j["noise"]["mocap_position_sigma_m"], 0.0);
  std::ifstream ee(dir + "/end_effector.csv");
  std::string first;
  std::getline(ee, first);
  EXPECT_NE(first.find("SIMULATION"), std::string::npos);
  EXPECT_NE(r.err.find("paper, reduced scheme, sequential"), std::string::npos);
}

struct BadCall {
  std::string what, args;
};
void PrintTo(const BadCall& b, std::ostream* os) { *os << b.what; }

class BadUsage : public ::testing::TestWithParam<BadCall> {};

TEST_P(BadUsage, ExitsTwoWithAMessageAndNothingOnStdout) {
  const ToolRun r = Ccma(GetParam().args);
  EXPECT_EQ(r.status, 2) << GetParam().what << "\nstderr: " << r.err;
  EXPECT_EQ(r.out, "") << GetParam().what;
  EXPECT_FALSE(r.err.empty()) << GetParam().what;
  EXPECT_EQ(r.err.find("terminate"), std::string::npos) << r.err;  // no crash text
}

const std::string kTwoBases = Model("4dof_reduced");

INSTANTIATE_TEST_SUITE_P(
    Cases, BadUsage,
    ::testing::Values(
        BadCall{"no arguments", ""}, BadCall{"unknown command", "assemble " + kTwoBases},
        BadCall{"missing model", "check"}, BadCall{"empty model", "check --model="},
        BadCall{"unknown flag", "check " + kTwoBases + " --verbose=1"},
        BadCall{"flag without value", "simulate --model"},
        BadCall{"positional argument", "check models/4dof_reduced.yaml"},
        BadCall{"flag given twice", "check " + kTwoBases + " " + kTwoBases},
        BadCall{"missing file", "check --model=/nonexistent.yaml"},
        BadCall{"directory as model", std::string("simulate --model=") + CCMA_MODELS_DIR},
        BadCall{"too few controls", "simulate " + kTwoBases + " --controls=1,2,3"},
        BadCall{"not a number", "simulate " + kTwoBases + " --controls=0,0,0,0,0,0,0,0,abc"},
        BadCall{"nan control", "simulate " + kTwoBases + " --controls=0,0,0,0,0,0,0,0,nan"},
        BadCall{"inf control", "simulate " + kTwoBases + " --controls=0,0,0,0,0,0,0,0,inf"},
        BadCall{"trailing comma", "simulate " + kTwoBases + " --controls=0,0,0,0,0,0,0,0,0,"},
        BadCall{"empty controls value", "simulate " + kTwoBases + " --controls="},
        BadCall{"single dash flag", "check -model=x.yaml"},
        BadCall{"controls overflow", "simulate " + kTwoBases + " --controls=1e999,0,0,0,0,0,0,0,0"},
        BadCall{"empty entry", "simulate " + kTwoBases + " --controls=0,0,0,,0,0,0,0,0"},
        BadCall{"check takes no controls", "check " + kTwoBases + " --controls=1"},
        BadCall{"control without target", "control " + kTwoBases},
        BadCall{"target of five values", "control " + kTwoBases + " --target=0,0,0.6,0,0"},
        BadCall{"unknown method", "control " + kTwoBases + " --target=0,0,0.6,0,0,0 --method=newton"},
        BadCall{"negative step", "control " + kTwoBases + " --target=0,0,0.6,0,0,0 --max_step_m=-1"},
        BadCall{"lambda out of range", "control " + kTwoBases + " --target=0,0,0.6,0,0,0 --lambda=1"},
        BadCall{"step not a number", "control " + kTwoBases + " --target=0,0,0.6,0,0,0 --max_step_rad=x"},
        BadCall{"trajectory without out", "trajectory " + kTwoBases + " --waypoints=" +
                                              std::string(CCMA_MODELS_DIR) + "/paths/4dof_combined.csv"},
        BadCall{"missing waypoint file", "trajectory " + kTwoBases + " --waypoints=/nonexistent.csv --out=/tmp/x.csv"},
        BadCall{"generate two agents", "generate --agents=2 --out=/tmp/x.yaml"},
        BadCall{"generate non-integer agents", "generate --agents=3.5 --out=/tmp/x.yaml"},
        BadCall{"generate without out", "generate --agents=6"},
        BadCall{"bench without a mode", "bench"},
        BadCall{"bench with two modes", "bench --all " + kTwoBases},
        BadCall{"bench negative steps", "bench " + kTwoBases + " --steps=-3"},
        BadCall{"bench unreadable models dir", "bench --all --models_dir=/nonexistent"},
        BadCall{"replay unknown noise", "replay " + kTwoBases + " --waypoints=" + std::string(CCMA_MODELS_DIR) +
                                            "/paths/4dof_combined.csv --out=/tmp/r --noise=loud"},
        BadCall{"replay negative gain", "replay " + kTwoBases + " --waypoints=" + std::string(CCMA_MODELS_DIR) +
                                            "/paths/4dof_combined.csv --out=/tmp/r --kp=-1"},
        BadCall{"replay without waypoints", "replay " + kTwoBases + " --out=/tmp/r"},
        BadCall{"model as waypoints", "trajectory " + kTwoBases + " --waypoints=" +
                                          std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml --out=/tmp/x.csv"}),
    [](const auto& info) {
      std::string n = info.param.what;
      for (char& c : n) if (!isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

TEST(Cli, MalformedModelsExitTwoNamingFileAndLine) {
  const std::string path = WriteFile("broken.yaml", R"(name: broken
bodies: []
mobile_bases:
  - {name: b, actuation: sideways, pose: [0, 0, 0]}
joints: []
end_effector: {body: b, point: [0, 0, 0], controlled: [x]}
)");
  for (const std::string command : {"check", "simulate"}) {
    const ToolRun r = Ccma(command + " --model=" + path);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find("broken.yaml:4"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("actuation"), std::string::npos) << r.err;
  }
}

TEST(Cli, BinaryGarbageIsABadModel) {
  const std::string path = WriteFile("garbage.yaml", std::string("\x01\x02\xff\xfe{{{[[[", 10));
  const ToolRun r = Ccma("check --model=" + path);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("garbage.yaml"), std::string::npos) << r.err;
}

// `ccma --help`: one line per command, "  ccma NAME  what it does", every
// command of the tool exactly once, each a real command.
TEST(Cli, GlobalHelpHasOneLinePerCommand) {
  const ToolRun r = Ccma("--help");
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> listed;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  ccma ", 0) != 0) continue;
    std::istringstream words(line.substr(7));
    std::string name, first_word;
    words >> name >> first_word;
    EXPECT_FALSE(first_word.empty()) << "no description: " << line;
    EXPECT_LE(line.size(), 100u) << line;
    listed.push_back(name);
  }
  EXPECT_EQ(listed, (std::vector<std::string>{"check", "simulate", "control", "trajectory", "plan", "statics", "dynamics", "retime", "generate", "import",
                                              "export", "bench", "replay", "view", "workspace", "design"}))
      << r.out;
  for (const std::string& name : listed) {
    const ToolRun help = Ccma(name + " --help");
    EXPECT_EQ(help.status, 0) << name;
    EXPECT_EQ(help.out.rfind("usage: ccma " + name, 0), 0u) << name;
  }
  const size_t check = r.out.find("\n  ccma check ");
  ASSERT_NE(check, std::string::npos);
  EXPECT_NE(r.out.substr(check, r.out.find('\n', check + 1) - check).find("validate a model"), std::string::npos);
}

TEST(Cli, HelpGoesToStdout) {
  const ToolRun global = Ccma("--help");
  EXPECT_EQ(global.status, 0);
  for (const char* command : {"check", "simulate", "control", "trajectory", "generate", "bench", "replay"}) {
    EXPECT_NE(global.out.find(std::string("ccma ") + command), std::string::npos) << command;
  }
  for (const std::string args : {"check --help", "simulate --model=x.yaml -h"}) {
    const ToolRun r = Ccma(args);
    EXPECT_EQ(r.status, 0) << args;
    EXPECT_EQ(r.err, "") << args;
    EXPECT_NE(r.out.find("usage: ccma " + args.substr(0, args.find(' '))), std::string::npos) << args;
  }
}

// Each sub-command's --help is its own: its synopsis, and exactly its flags,
// each with a unit in brackets.
TEST(Cli, EachCommandHasItsOwnHelpWithUnits) {
  const std::map<std::string, std::vector<std::string>> flags = {
      {"check", {"model", "obstacles"}},
      {"simulate", {"model", "controls", "from", "obstacles", "loaded", "wrench", "max_minutes"}},
      {"control", {"model", "target", "controls", "obstacles", "compensate", "wrench", "max_minutes",
                   "singularity_weight", "singularity_threshold", "pivot_weight",
                   "pivot_threshold", "secondary", "secondary_weight", "clearance_m", "method", "max_step_m",
                   "max_step_rad", "lambda"}},
      {"statics", {"model", "controls", "wrench", "mocap_noise_m", "mocap_noise_rad", "obstacles"}},
      {"dynamics", {"model", "trajectory", "out", "wrench"}},
      {"retime", {"model", "trajectory", "out"}},
      {"plan", {"model", "waypoints", "out", "controls", "obstacles", "plan_iterations", "plan_time_s", "path_weight",
                "smoothness_weight", "travel_weight", "max_step_m", "max_step_rad", "lambda"}},
      {"trajectory", {"model", "waypoints", "out", "controls", "obstacles", "compensate", "wrench", "max_minutes",
                      "singularity_weight",
                      "singularity_threshold",
                      "pivot_weight", "pivot_threshold", "secondary", "secondary_weight", "clearance_m", "method",
                      "max_step_m", "max_step_rad", "lambda"}},
      {"generate", {"agents", "kind", "out"}},
      {"import", {"from", "closures", "actuated", "end_effector", "controlled", "collision_radius", "keyframe", "strict",
                  "out"}},
      {"bench", {"model", "all", "models_dir", "scaling", "steps", "seed", "out", "max_minutes"}},
      {"replay", {"model", "waypoints", "out", "noise", "seed", "mocap_noise_m", "mocap_noise_rad",
                  "latency_s", "slip", "kp", "ki", "controller_hz", "max_wheel_speed", "gait_hz", "gait_bob_m",
                  "gait_sway_rad", "obstacles", "max_minutes", "method", "max_step_m",
                  "max_step_rad", "lambda"}},
      {"view", {"model", "trajectory", "dynamics", "replay", "workspace", "controls", "meshes", "mesh_root", "color_by",
                "deflection", "wrench", "out", "obstacles"}},
      {"workspace", {"model", "out", "x", "y", "z", "roll", "pitch", "yaw", "resolution", "samples", "seed",
                     "threads", "tile_size", "plot", "obstacles", "store", "max_minutes", "method", "max_step_m",
                     "max_step_rad", "lambda"}},
      {"design", {"model", "targets", "out", "vary", "vary_length", "max_change", "min_length", "min_singular_value",
                  "target_tolerance", "design_iterations", "objective", "mocap_noise_m", "mocap_noise_rad",
                  "max_minutes", "method", "max_step_m", "max_step_rad", "lambda"}},
      {"export", {"model", "format", "out"}}};
  for (const auto& [command, expected] : flags) {
    const ToolRun r = Ccma(command + " --help");
    ASSERT_EQ(r.status, 0) << command;
    EXPECT_EQ(r.out.rfind("usage: ccma " + command, 0), 0u) << r.out;
    std::vector<std::string> listed;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("  --", 0) != 0) continue;
      listed.push_back(line.substr(4, line.find('=') == std::string::npos ? std::string::npos : line.find('=') - 4));
      std::string description;
      std::getline(lines, description);
      EXPECT_NE(description.find('['), std::string::npos) << command << " --" << listed.back() << ": no unit";
    }
    EXPECT_EQ(listed, expected) << command;
  }
}

// A flag several commands share is described for the command whose help
// lists it: no description speaks for another command ("simulate: ..." in
// import's help) or names a flag this command does not take (--noise, which
// only replay has, in statics' help).
TEST(Cli, FlagDescriptionsSpeakForTheirOwnCommand) {
  const ToolRun global = Ccma("--help");
  std::vector<std::string> commands;
  std::istringstream global_lines(global.out);
  for (std::string line; std::getline(global_lines, line);) {
    if (line.rfind("  ccma ", 0) == 0) commands.push_back(line.substr(7, line.find(' ', 7) - 7));
  }
  ASSERT_GE(commands.size(), 14u) << global.out;
  std::map<std::string, std::map<std::string, std::string>> described;  // command -> flag -> description
  for (const std::string& command : commands) {
    const ToolRun r = Ccma(command + " --help");
    ASSERT_EQ(r.status, 0) << command;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("  --", 0) != 0) continue;
      std::string description;
      std::getline(lines, description);
      described[command][line.substr(4, line.find('=') == std::string::npos ? std::string::npos : line.find('=') - 4)] =
          description;
    }
  }
  for (const auto& [command, flags] : described) {
    for (const auto& [flag, description] : flags) {
      const std::string text = description.substr(description.find_first_not_of(' '));
      for (const std::string& other : commands) {
        const bool speaks_for = text.rfind(other + ":", 0) == 0 || text.rfind(other + " --", 0) == 0;
        EXPECT_FALSE(speaks_for && other != command) << "ccma " << command << " --help: --" << flag << ": " << text;
      }
      for (size_t p = text.find("--"); p != std::string::npos; p = text.find("--", p + 2)) {
        size_t end = p + 2;
        while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_')) ++end;
        const std::string named = text.substr(p + 2, end - p - 2);
        EXPECT_TRUE(named.empty() || flags.count(named) == 1)
            << "ccma " << command << " --help: --" << flag << " names --" << named << ", which ccma " << command
            << " does not take: " << text;
      }
    }
  }
  // The shared --from: a JSON result for simulate, the robot file for import.
  EXPECT_NE(described["simulate"]["from"].find("JSON"), std::string::npos) << described["simulate"]["from"];
  EXPECT_EQ(described["simulate"]["from"].find("URDF"), std::string::npos) << described["simulate"]["from"];
  EXPECT_NE(described["import"]["from"].find("URDF"), std::string::npos) << described["import"]["from"];
  EXPECT_EQ(described["import"]["from"].find("JSON"), std::string::npos) << described["import"]["from"];
}

TEST(Cli, VersionPrintsOneLine) {
  const ToolRun r = Ccma("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("ccma 0.1.0 (", 0), 0u) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1);
}

}  // namespace
