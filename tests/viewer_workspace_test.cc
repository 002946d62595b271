// `ccma view --workspace`: a `ccma workspace` map read into the viewer's
// point cloud (viewer/workspace_cloud.h), the scene's "workspace" object,
// the CLI's JSON, and hostile maps refused with file, line and column. The
// page draws the cloud in a real browser (CTest: viewer_browser_workspace_*).
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "formats/model_loader.h"
#include "tests/tool_run.h"
#include "viewer/scene.h"
#include "viewer/workspace_cloud.h"

namespace ccma::viewer {
namespace viewer_workspace_test {

namespace fs = std::filesystem;
using ccma::testing::RunTool;
using ccma::testing::ModelPath;
using ccma::testing::ToolRun;

std::string Scratch(const std::string& name) { return ccma::testing::ScratchPath("viewer_workspace", name); }

// A 3 x 3 map of 4dof_reduced over x and z written by the tool: z = 0.9 m
// is above the legs' reach (0.85 m), so its three rows are unreachable.
std::string ToolMap() {
  static const std::string csv = [] {
    const std::string path = Scratch("map.csv");
    const ToolRun r = RunTool({"workspace", "--model=" + ModelPath("4dof_reduced"), "--x=-0.2:0.2", "--z=0.5:0.9",
                               "--resolution=3", "--out=" + path});
    EXPECT_EQ(r.status, 0) << r.err;
    return path;
  }();
  return csv;
}

// The CSV's rows as name -> text maps (the tool's own output, read plainly).
std::vector<std::map<std::string, std::string>> Rows(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    if (header.empty()) {
      header = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size(); ++i) row[header[i]] = cells.at(i);
    rows.push_back(row);
  }
  return rows;
}

TEST(WorkspaceCloud, ToolMapGivesOnePointPerRow) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  const WorkspaceCloud cloud = CloudFromWorkspaceCsv(model, ToolMap());
  const auto rows = Rows(ToolMap());
  ASSERT_EQ(cloud.points.size(), 9u);
  ASSERT_EQ(rows.size(), 9u);
  EXPECT_EQ(cloud.components, (std::vector<std::string>{"x", "y", "z", "yaw"}));
  EXPECT_EQ(cloud.source, "map.csv");
  EXPECT_EQ(cloud.reachable_count, 6);
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(cloud.points[i].x(), std::stod(rows[i].at("x")));
    EXPECT_EQ(cloud.points[i].y(), std::stod(rows[i].at("y")));  // y not sampled: its home value, as written
    EXPECT_EQ(cloud.points[i].z(), std::stod(rows[i].at("z")));
    const bool reachable = cloud.points[i].z() < 0.85;
    EXPECT_EQ(cloud.reachable[i], reachable ? 1 : 0) << i;
    if (reachable) {
      EXPECT_EQ(cloud.sigma_min[i], std::stod(rows[i].at("sigma_min")));
      EXPECT_GT(cloud.sigma_min[i], 0);
    } else {
      EXPECT_EQ(cloud.sigma_min[i], 0);
    }
  }
}

TEST(WorkspaceCloud, ComponentsTheModelDoesNotControlComeFromHome) {
  // planar_3rpr controls x, y and yaw: z is the end-effector's at home, and
  // rows differing only in yaw give one point twice.
  const Model model = LoadModel(ModelPath("planar_3rpr"));
  ASSERT_FALSE(model.end_effector.controlled[2]);
  const std::string csv = Scratch("planar.csv");
  std::ofstream(csv) << "# a comment line\nx,y,yaw,reachable,sigma_min,limited_by\n"
                     << "0.01,0.02,0,1,0.3,\n0.01,0.02,0.1,1,0.25,\n0.5,0.5,0,0,,joint1;joint2\n";
  const WorkspaceCloud cloud = CloudFromWorkspaceCsv(model, csv);
  ASSERT_EQ(cloud.points.size(), 3u);
  EXPECT_EQ(cloud.components, (std::vector<std::string>{"x", "y", "yaw"}));
  for (const Eigen::Vector3d& p : cloud.points) EXPECT_EQ(p.z(), model.end_effector.p_W_home.z());
  EXPECT_EQ(cloud.points[0], cloud.points[1]);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3d(0.01, 0.02, model.end_effector.p_W_home.z()));
  EXPECT_EQ(cloud.reachable, (std::vector<char>{1, 1, 0}));
  EXPECT_EQ(cloud.sigma_min, (std::vector<double>{0.3, 0.25, 0}));  // empty for the unreachable row: 0
}

TEST(WorkspaceCloud, SceneCarriesTheCloudAndItsScale) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  const WorkspaceCloud cloud = CloudFromWorkspaceCsv(model, ToolMap());
  SceneSummary summary;
  const std::string text = BuildScene(model, {}, "workspace", &summary, &cloud);
  EXPECT_EQ(text.find("null"), std::string::npos);
  EXPECT_EQ(text.find("NaN"), std::string::npos);
  const nlohmann::json scene = nlohmann::json::parse(text);
  EXPECT_EQ(summary.workspace_points, 9);
  EXPECT_EQ(summary.workspace_reachable, 6);
  EXPECT_EQ(summary.frames, 1);
  EXPECT_EQ(scene["source"], "workspace");
  const nlohmann::json& ws = scene["workspace"];
  ASSERT_EQ(ws["points"].size(), 9u);
  ASSERT_EQ(ws["reachable"].size(), 9u);
  ASSERT_EQ(ws["sigma_min"].size(), 9u);
  EXPECT_EQ(ws["source"], "map.csv");
  EXPECT_EQ(ws["components"], nlohmann::json({"x", "y", "z", "yaw"}));
  for (size_t i = 0; i < 9; ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(ws["points"][i][k].get<double>(), cloud.points[i][k], 5e-8);
    EXPECT_EQ(ws["reachable"][i].get<int>(), cloud.reachable[i]);
    EXPECT_NEAR(ws["sigma_min"][i].get<double>(), cloud.sigma_min[i], 5e-8);
  }
  // Without the cloud: no "workspace", and a scale no larger (the cloud's box counts).
  const nlohmann::json bare = nlohmann::json::parse(BuildScene(model, {}, "model", nullptr));
  EXPECT_FALSE(bare.contains("workspace"));
  EXPECT_GE(scene["scale"].get<double>(), bare["scale"].get<double>());

  // A cloud far out widens the scale to cover it.
  WorkspaceCloud far = cloud;
  far.points[0] = Eigen::Vector3d(5, 0, 0.6);
  const nlohmann::json wide = nlohmann::json::parse(BuildScene(model, {}, "workspace", nullptr, &far));
  EXPECT_GT(wide["scale"].get<double>(), 2.0);
}

struct BadMap {
  std::string what;
  std::string text;
  std::string expected;  // in the message, after the file name
};

std::vector<BadMap> BadMaps() {
  const std::string header = "x,y,z,yaw,reachable,sigma_min,limited_by\n";
  const std::string good = "0,0,0.6,0,1,0.5,\n";
  return {
      {"not a number", header + good + "0,zero,0.6,0,1,0.5,\n", ":3: column 'y': not a number: 'zero'"},
      {"nan", header + good + "0,0,nan,0,1,0.5,\n", ":3: column 'z': not a finite number: 'nan'"},
      {"inf", header + "# note\n" + good + "0,0,0.6,0,1,inf,\n", ":4: column 'sigma_min': not a finite number"},
      {"huge", header + good + "1e300,0,0.6,0,1,0.5,\n", ":3: column 'x': '1e300' is outside"},
      {"reachable 2", header + good + "0,0,0.6,0,2,0.5,\n", ":3: column 'reachable': not 0 or 1"},
      {"reachable empty", header + "0,0,0.6,0,,0.5,\n", ":2: column 'reachable': not 0 or 1"},
      {"empty pose cell", header + good + "0,,0.6,0,1,0.5,\n", ":3: column 'y': empty"},
      {"negative sigma", header + "0,0,0.6,0,1,-0.1,\n", ":2: column 'sigma_min': a reachable row needs a number >= 0"},
      {"empty sigma", header + "0,0,0.6,0,1,,\n", ":2: column 'sigma_min': a reachable row needs a number >= 0"},
      {"one cell too many", header + good + "0,0,0.6,0,1,0.5,,7\n", ":3: 8 cells, the header has 7"},
      {"one cell too few", header + "0,0,0.6,0,1\n", ":2: 5 cells, the header has 7"},
      {"no sigma_min", "x,y,z,yaw,reachable\n0,0,0.6,0,1\n", ": no column 'sigma_min' in the header"},
      {"no reachable", "x,y,z,yaw,sigma_min\n0,0,0.6,0,1\n", ": no column 'reachable' in the header"},
      {"another model", "x,y,z,reachable,sigma_min\n0,0,0.6,1,0.5\n", ": no column 'yaw' in the header"},
      {"a component not controlled", "x,y,z,roll,yaw,reachable,sigma_min\n0,0,0.6,0,0,1,0.5\n",
       ": column 'roll': 4dof_reduced does not control it"},
      {"no rows", header, ": no rows"},
      {"empty file", "", ": no header line"},
  };
}

TEST(WorkspaceCloud, BadMapsNameFileLineAndColumn) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  for (const BadMap& bad : BadMaps()) {
    const std::string csv = Scratch("bad.csv");
    std::ofstream(csv) << bad.text;
    try {
      CloudFromWorkspaceCsv(model, csv);
      ADD_FAILURE() << "accepted: " << bad.what;
    } catch (const ViewInputError& e) {
      EXPECT_NE(std::string(e.what()).find(csv + bad.expected), std::string::npos) << bad.what << ": " << e.what();
    }
  }
  EXPECT_THROW(CloudFromWorkspaceCsv(model, Scratch("no_such.csv")), ViewInputError);
  EXPECT_THROW(CloudFromWorkspaceCsv(model, ccma::testing::TestDir()), ViewInputError);  // a directory
}

TEST(WorkspaceCloud, MoreRowsThanAnyMapAreRefused) {
  const Model model = LoadModel(ModelPath("4dof_reduced"));
  const std::string csv = Scratch("huge.csv");
  {
    std::ofstream out(csv);
    out << "x,y,z,yaw,reachable,sigma_min\n";
    for (long i = 0; i <= kMaxWorkspaceRows; ++i) out << "0,0,0.6,0,1,0.5\n";
  }
  try {
    CloudFromWorkspaceCsv(model, csv);
    ADD_FAILURE() << "accepted more than " << kMaxWorkspaceRows << " rows";
  } catch (const ViewInputError& e) {
    EXPECT_NE(std::string(e.what()).find(csv + ":1000002: more than 1000000 rows"), std::string::npos) << e.what();
  }
  fs::remove(csv);
}

TEST(ViewWorkspaceCli, WritesThePageAndCountsThePoints) {
  const std::string out = Scratch("cloud.html");
  const ToolRun r = RunTool({"view", "--model=" + ModelPath("4dof_reduced"), "--workspace=" + ToolMap(), "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["source"], "workspace");
  EXPECT_EQ(j["frames"], 1);
  EXPECT_EQ(j["workspace_points"], 9);
  EXPECT_EQ(j["workspace_reachable"], 6);
  EXPECT_EQ(j["bytes"].get<size_t>(), fs::file_size(out));
  // Without --workspace the keys are absent.
  const ToolRun plain = RunTool({"view", "--model=" + ModelPath("4dof_reduced"), "--out=" + Scratch("plain.html")});
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_FALSE(nlohmann::json::parse(plain.out).contains("workspace_points"));
}

TEST(ViewWorkspaceCli, BadInputExitsTwoWithNothingOnStdout) {
  const std::string out = Scratch("bad.html");
  const std::string model = "--model=" + ModelPath("4dof_reduced");
  const std::string bad = Scratch("bad_map.csv");
  std::ofstream(bad) << "x,y,z,yaw,reachable,sigma_min\n0,0,0.6,0,1,0.5\n0,0,0.6,0,yes,0.5\n";
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  for (const Case& c : std::vector<Case>{
           {{"view", model, "--workspace=" + bad, "--out=" + out}, bad + ":3: column 'reachable': not a number: 'yes'"},
           {{"view", model, "--workspace=" + Scratch("missing.csv"), "--out=" + out}, "missing.csv"},
           {{"view", model, "--workspace=" + ToolMap(), "--trajectory=" + ToolMap(), "--out=" + out},
            "--workspace goes alone"},
           {{"view", model, "--workspace=" + ToolMap(), "--replay=/tmp", "--out=" + out}, "--workspace goes alone"},
       }) {
    const ToolRun r = RunTool(c.args);
    EXPECT_EQ(r.status, 2) << c.args[2] << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace ccma::viewer
