// `ccma dynamics` as a user runs it (cli.md): the closed form of an arm on a
// motor through the CLI, statics' numbers at rest, and bad input (exit 2,
// nothing on stdout, file, line and column named, no --out file).
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
namespace dynamics_cli_test {

using testing::RunTool;
using testing::ToolRun;

constexpr char kArm[] =
    "name: arm\nbodies:\n  - {name: arm, position: [0.2, 0, 0], mass: 2.5, com: [0.4, 0, 0],"
    " inertia: [0.02, 0.03, 0.025, 0.004, -0.003, 0.002]}\n"
    "joints:\n  - {name: hinge, type: revolute, actuated: true, between: [world, arm], point: [0, 0, 0], "
    "axis: [0, -1, 0]}\nend_effector: {body: arm, point: [0.5, 0, 0], controlled: [x, z]}\n";

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = testing::ScratchPath("dynamics_cli", name);
  std::ofstream(path) << text;
  return path;
}

// Rows theta(t) = theta0 + w t (a natural spline is exact on a line): the
// arm's torque is m g l cos(theta) + 0 (theta'' = 0), at every row.
std::string LinearArmPath(double theta0, double w, int rows, double dt) {
  std::ostringstream csv;
  csv.precision(17);
  csv << "# an arm turning at a constant rate\ntime_s,u_hinge_rad,x_m,y_m,z_m\n";
  for (int r = 0; r < rows; ++r) {
    const double t = r * dt, q = theta0 + w * t;
    csv << t << "," << q << "," << 0.5 * std::cos(q) << ",0," << 0.5 * std::sin(q) << "\n";
  }
  return csv.str();
}

std::vector<std::vector<double>> ReadRows(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(cell.empty() ? NAN : std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

TEST(DynamicsCli, ArmAtConstantRateIsItsClosedForm) {
  const std::string model = Write("arm.yaml", kArm);
  const std::string path = Write("arm_path.csv", LinearArmPath(-0.4, 1.3, 11, 0.1));
  const std::string out = testing::ScratchPath("dynamics_cli", "arm_dynamics.csv");
  const ToolRun r = RunTool({"dynamics", "--model=" + model, "--trajectory=" + path, "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["rows"], 11);
  EXPECT_TRUE(j["assembled"].get<bool>());
  EXPECT_EQ(j["actuators"][0]["name"], "hinge");
  const std::vector<std::vector<double>> rows = ReadRows(out);
  ASSERT_EQ(rows.size(), 11u);
  const double m = 2.5, l = 0.4, I = 0.03 + m * l * l;
  for (int k = 0; k < 11; ++k) {
    const double q = -0.4 + 1.3 * 0.1 * k;
    // time_s, u_hinge_Nm, kinetic_J, potential_J, power_W
    EXPECT_NEAR(rows[k][1], m * 9.81 * l * std::cos(q), 1e-9) << k;
    EXPECT_NEAR(rows[k][2], 0.5 * I * 1.3 * 1.3, 1e-12) << k;
    EXPECT_NEAR(rows[k][4], rows[k][1] * 1.3, 1e-9) << k;
  }
  // The peak is the largest |torque|: at the row nearest theta = 0.
  EXPECT_NEAR(j["actuators"][0]["peak_effort"].get<double>(), m * 9.81 * l * std::cos(-0.01), 1e-9);
}

// Rates are judged against velocity_limit: the arm turns at 1.3 rad/s.
TEST(DynamicsCli, RatesAreJudgedAgainstTheVelocityLimit) {
  const std::string path = Write("arm_path.csv", LinearArmPath(-0.4, 1.3, 11, 0.1));
  for (const double limit : {1.0, 1.5}) {
    std::string text = kArm;
    text.replace(text.find("axis: [0, -1, 0]}"), 17, "axis: [0, -1, 0], velocity_limit: " + std::to_string(limit) + "}");
    const std::string model = Write("arm_rate.yaml", text);
    const ToolRun r = RunTool({"dynamics", "--model=" + model, "--trajectory=" + path});
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    const nlohmann::json& hinge = j["actuators"][0];
    EXPECT_NEAR(hinge["peak_rate"].get<double>(), 1.3, 1e-12);
    EXPECT_EQ(hinge["rate_limit"].get<double>(), limit);
    EXPECT_TRUE(hinge["limit"].is_null());
    EXPECT_EQ(hinge["within_limits"].get<bool>(), limit > 1.3) << limit;
    EXPECT_EQ(j["within_limits"].get<bool>(), limit > 1.3) << limit;
    EXPECT_EQ(j["limiting"].size(), limit > 1.3 ? 0u : 1u) << limit;
    EXPECT_EQ(r.err.find("rate limits") != std::string::npos, limit < 1.3) << r.err;
  }
  // Without a velocity_limit there is nothing to judge the rate against.
  const ToolRun r = RunTool({"dynamics", "--model=" + Write("arm.yaml", kArm), "--trajectory=" + path});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(nlohmann::json::parse(r.out)["actuators"][0]["rate_limit"].is_null());
}

TEST(DynamicsCli, AtRestIsCcmaStatics) {
  const std::string model = Write("arm.yaml", kArm);
  const std::string path = Write("rest.csv", "time_s,u_hinge_rad\n0,0.7\n1,0.7\n2,0.7\n");
  const std::string out = testing::ScratchPath("dynamics_cli", "rest_dynamics.csv");
  const ToolRun r = RunTool({"dynamics", "--model=" + model, "--trajectory=" + path, "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  const ToolRun statics = RunTool({"statics", "--model=" + model, "--controls=0.7"});
  ASSERT_EQ(statics.status, 0) << statics.err;
  const double expected = nlohmann::json::parse(statics.out)["actuators"][0]["effort"].get<double>();
  for (const std::vector<double>& row : ReadRows(out)) EXPECT_EQ(row[1], expected);
  EXPECT_EQ(nlohmann::json::parse(r.out)["energy_J"].get<double>(), 0.0);
}

void ExpectBadInput(const std::string& csv_text, const std::string& message, const std::string& model_text = kArm) {
  const std::string model = Write("model.yaml", model_text);
  const std::string path = Write("bad.csv", csv_text);
  const std::string out = testing::ScratchPath("dynamics_cli", "never.csv");
  std::filesystem::remove(out);
  const ToolRun r = RunTool({"dynamics", "--model=" + model, "--trajectory=" + path, "--out=" + out});
  EXPECT_EQ(r.status, 2) << csv_text << r.err;
  EXPECT_EQ(r.out, "") << csv_text;
  EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << csv_text;
}

TEST(DynamicsCli, BadInputIsNamed) {
  ExpectBadInput("time_s,u_hinge_rad\n0,0.1\n1,nan\n", "bad.csv:3: column 'u_hinge_rad'");
  ExpectBadInput("time_s,u_hinge_rad\n0,0.1\n1,\n", "bad.csv:3: column 'u_hinge_rad': empty");
  ExpectBadInput("time_s,u_hinge_rad\n0,0.1\n2,0.2\n1,0.3\n", "bad.csv:4: column 'time_s': 1 is not after");
  ExpectBadInput("time_s,u_hinge_rad\n0,0.1\n0,0.2\n", "bad.csv:3: column 'time_s'");
  ExpectBadInput("time_s,u_elbow_rad\n0,0.1\n1,0.2\n", "u_hinge_rad");
  ExpectBadInput("time_s,u_hinge_rad\n0,0.1\n", "at least two");
  // Another model's path: its reached points are not where this arm's end-effector is.
  ExpectBadInput("time_s,u_hinge_rad,x_m,y_m,z_m\n0,0.1,0.3,0,0.03\n1,0.2,0.3,0,0.06\n",
                 "bad.csv:2: columns x_m, y_m, z_m");
  // A non-physical inertia: izz above ixx + iyy.
  std::string bad_model = kArm;
  bad_model.replace(bad_model.find("0.025"), 5, "0.095");
  ExpectBadInput("time_s,u_hinge_rad\n0,0.1\n1,0.2\n", "inertia", bad_model);
}

}  // namespace dynamics_cli_test
}  // namespace ccma
