// `ccma retime` as a user runs it (cli.md): the output is the input with new
// times only, `ccma dynamics` on it stays within every limit, a path beyond
// its limits at rest writes nothing, bad input is exit 2; `velocity_limit`
// in the model format.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/tool_run.h"

namespace ccma {
namespace retime_cli_test {

using testing::RunTool;
using testing::ToolRun;

std::string Arm(const std::string& limits) {
  return "name: arm\nbodies:\n  - {name: arm, position: [0.2, 0, 0], mass: 2.5, com: [0.4, 0, 0],"
         " inertia: [0.02, 0.03, 0.025, 0.004, -0.003, 0.002]}\n"
         "joints:\n  - {name: hinge, type: revolute, actuated: true, between: [world, arm], point: [0, 0, 0], "
         "axis: [0, -1, 0]" + limits + "}\nend_effector: {body: arm, point: [0.5, 0, 0], controlled: [x, z]}\n";
}

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = testing::ScratchPath("retime_cli", name);
  std::ofstream(path) << text;
  return path;
}

// A comment, the header with time_s second, then rows whose cells are
// written in more than one way (17 digits, "-0"): the output must keep
// every byte but the times.
std::string SweepCsv(int rows) {
  std::ostringstream csv;
  csv.precision(17);
  csv << "# swing the arm up\nu_hinge_rad,time_s,x_m,y_m,z_m\n";
  for (int r = 0; r < rows; ++r) {
    const double q = -0.5 + 1.5 * r / (rows - 1);
    csv << q << "," << 2.0 * r << "," << 0.5 * std::cos(q) << (r % 2 ? ",-0," : ",0,") << 0.5 * std::sin(q) << "\n";
  }
  return csv.str();
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<std::string> Cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
  return out;
}

TEST(RetimeCli, OutputIsTheInputWithNewTimesAndDynamicsFindsItWithinLimits) {
  const std::string model = Write("arm.yaml", Arm(", effort_limits: [-30, 30], velocity_limit: 4"));
  const std::string input_text = SweepCsv(41);
  const std::string input = Write("sweep.csv", input_text);
  const std::string out = testing::ScratchPath("retime_cli", "fast.csv");
  const ToolRun r = RunTool({"retime", "--model=" + model, "--trajectory=" + input, "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["feasible"].get<bool>());
  EXPECT_EQ(j["rows"].get<int>(), 41);
  EXPECT_EQ(j["original_duration_s"].get<double>(), 80.0);
  EXPECT_LE(j["duration_s"].get<double>(), j["uniform_duration_s"].get<double>());
  EXPECT_GT(j["duration_s"].get<double>(), 1.5 / 4);
  ASSERT_FALSE(j["limiting"].empty());
  double shares = 0;
  for (const nlohmann::json& l : j["limiting"]) shares += l["share"].get<double>();
  EXPECT_LE(shares, 1 + 1e-12);
  EXPECT_GT(shares, 0.9);

  const std::vector<std::string> before = Lines(input_text), after = Lines(testing::Slurp(out));
  ASSERT_EQ(before.size(), after.size());
  EXPECT_EQ(before[0], after[0]);
  EXPECT_EQ(before[1], after[1]);
  double previous = -1;
  for (size_t i = 2; i < before.size(); ++i) {
    std::vector<std::string> a = Cells(before[i]), b = Cells(after[i]);
    ASSERT_EQ(a.size(), b.size());
    const double t = std::stod(b[1]);
    EXPECT_GT(t, previous);
    previous = t;
    a[1] = b[1] = "";
    EXPECT_EQ(a, b) << i;
  }
  EXPECT_NEAR(previous, j["duration_s"].get<double>(), 1e-12);

  const ToolRun check = RunTool({"dynamics", "--model=" + model, "--trajectory=" + out});
  ASSERT_EQ(check.status, 0) << check.err;
  EXPECT_TRUE(nlohmann::json::parse(check.out)["within_limits"].get<bool>());
}

TEST(RetimeCli, APathBeyondItsLimitsAtRestWritesNothing) {
  const std::string model = Write("weak.yaml", Arm(", effort_limits: [-5, 5]"));
  const std::string input = Write("sweep.csv", SweepCsv(11));
  const std::string out = testing::ScratchPath("retime_cli", "never.csv");
  std::filesystem::remove(out);
  const ToolRun r = RunTool({"retime", "--model=" + model, "--trajectory=" + input, "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["feasible"].get<bool>());
  EXPECT_EQ(j["infeasible"]["row"].get<int>(), 0);
  EXPECT_EQ(j["infeasible"]["line"].get<int>(), 3);
  EXPECT_EQ(j["infeasible"]["control"].get<std::string>(), "hinge");
  EXPECT_FALSE(j.contains("duration_s"));
  EXPECT_NE(r.err.find("infeasible at rest"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

void ExpectBadInput(const std::vector<std::string>& args, const std::string& message) {
  const ToolRun r = RunTool(args);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
}

TEST(RetimeCli, BadInputIsNamed) {
  const std::string input = Write("sweep.csv", SweepCsv(11));
  const std::string out = testing::ScratchPath("retime_cli", "bad_out.csv");
  std::filesystem::remove(out);
  const std::string free_arm = Write("free.yaml", Arm(""));
  ExpectBadInput({"retime", "--model=" + free_arm, "--trajectory=" + input, "--out=" + out}, "no effort_limits");
  const std::string limited = Write("limited.yaml", Arm(", effort_limits: [-30, 30]"));
  ExpectBadInput({"retime", "--model=" + limited, "--trajectory=" + input}, "--out");
  const std::string backwards = Write("backwards.csv", "time_s,u_hinge_rad\n0,0.1\n2,0.2\n1,0.3\n");
  ExpectBadInput({"retime", "--model=" + limited, "--trajectory=" + backwards, "--out=" + out},
                 "backwards.csv:4: column 'time_s'");
  EXPECT_FALSE(std::filesystem::exists(out));
  // velocity_limit: positive, on an actuated joint, [V, W] on a base.
  for (const auto& [limits, message] : std::vector<std::pair<std::string, std::string>>{
           {", velocity_limit: 0", "joints[0].velocity_limit: must be positive"},
           {", velocity_limit: -2", "must be positive"},
           {", velocity_limit: .nan", "velocity_limit"},
           {", velocity_limit: [1, 2]", "velocity_limit"}}) {
    const std::string bad = Write("bad_velocity.yaml", Arm(limits));
    ExpectBadInput({"check", "--model=" + bad}, message);
  }
}

}  // namespace retime_cli_test
}  // namespace ccma
