// Workspace maps (analyses/workspace.h, `ccma workspace`): reachability
// against the closed-form leg solutions, independence of the thread count,
// the sample grid, option bounds, the CSV contract and hostile flags.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ccma/ccma.h"
#include "tests/leg_closed_form.h"
#include "tests/tool_run.h"

namespace ccma {
namespace workspace_test {

std::string ModelFile(const std::string& name) { return std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml"; }

constexpr int kZ = 2, kYaw = 5, kX = 0, kY = 1;

// Closed form: every leg of 4dof_reduced has a base position for the pose
// (LineCircle throws when the end-effector attachment is out of the link's reach).
bool ClosedFormReachable(const Model& model, const PoseTarget& pose, std::vector<Eigen::Vector3d>* bases) {
  const Eigen::Matrix3d R = RotationFromRpy(pose.rpy);
  bases->clear();
  for (const testing::Leg& leg : testing::FindLegs(model)) {
    try {
      bases->push_back(testing::BasePoseForLeg(model, leg, pose.position, R, 0.0));
    } catch (const std::runtime_error&) {
      return false;
    }
  }
  return true;
}

// z in 0.40 .. 1.10 (step 0.1) and yaw in -0.3 .. 0.3: the legs (link
// length L = 0.5 m from the post top at 0.35 m) reach up to z = 0.85 m
// whatever x, y and yaw; grid points stay >= 0.05 m from that edge. Below
// z = 0.35 m the closed form still has solutions, but the links pass
// horizontal on the way there (the bases at their farthest, dG/ds singular:
// the mechanism can move in z with the bases held), which continuation
// does not cross; the grid stays above it.
WorkspaceOptions ZYawGrid() {
  WorkspaceOptions options;
  options.ranges = {{kZ, 0.40, 1.10}, {kYaw, -0.3, 0.3}};
  options.resolution = 8;
  return options;
}

TEST(Workspace, ReachabilityMatchesClosedFormLegSolutions) {
  const Model model = LoadModel(ModelFile("4dof_reduced"));
  WorkspaceOptions options = ZYawGrid();
  options.resolution = 8;
  const WorkspaceResult result = ComputeWorkspace(model, options);
  ASSERT_EQ(result.samples.size(), 64u);
  int reachable = 0, unreachable = 0;
  for (const WorkspaceSample& s : result.samples) {
    std::vector<Eigen::Vector3d> bases;
    const bool expected = ClosedFormReachable(model, s.pose, &bases);
    ASSERT_GT(std::abs(s.pose.position.z() - 0.85), 0.04);  // no sample on the edge
    EXPECT_EQ(s.reachable, expected) << "z " << s.pose.position.z() << " yaw " << s.pose.rpy.z() << ": " << s.warning;
    if (expected) {
      ++reachable;
      EXPECT_LT(s.residual_energy, 1e-20);
      EXPECT_LT(s.error, 1e-9);
      EXPECT_GT(s.sigma_min, 1e-3);
      EXPECT_GT(s.rcond, 0);
      // The controls are the closed-form base positions (same branch as home).
      for (int k = 0; k < model.num_bases(); ++k) {
        EXPECT_NEAR(s.controls[3 * k], bases[static_cast<size_t>(k)].x(), 1e-7) << "base " << k;
        EXPECT_NEAR(s.controls[3 * k + 1], bases[static_cast<size_t>(k)].y(), 1e-7) << "base " << k;
      }
    } else {
      ++unreachable;
      EXPECT_EQ(s.sigma_min, 0);
      EXPECT_FALSE(s.warning.empty());
    }
  }
  EXPECT_EQ(reachable, 5 * 8);    // z = 0.4 .. 0.8
  EXPECT_EQ(unreachable, 3 * 8);  // z = 0.9, 1.0, 1.1
  EXPECT_EQ(result.reachable, reachable);
}

// Every tile evaluated alone (EvaluateWorkspaceTile, what a Dask worker
// runs), in another order than the local threads take them: the order of
// decreasing tile index among the tiles whose dependencies are finished.
std::vector<WorkspaceSample> TileByTile(const Model& model, const WorkspaceOptions& options) {
  const std::vector<WorkspaceTile> tiles = WorkspaceTiles(model, options);
  std::vector<WorkspaceTileResult> results(tiles.size());
  std::vector<bool> finished(tiles.size(), false);
  std::vector<WorkspaceSample> map(static_cast<size_t>(options.SampleCount()));
  for (size_t left = tiles.size(); left > 0; --left) {
    int next = -1;
    for (int t = static_cast<int>(tiles.size()) - 1; t >= 0 && next < 0; --t) {
      bool ready = !finished[static_cast<size_t>(t)];
      for (int d : tiles[static_cast<size_t>(t)].depends_on) ready = ready && finished[static_cast<size_t>(d)];
      if (ready) next = t;
    }
    EXPECT_GE(next, 0);
    if (next < 0) break;
    std::vector<WorkspaceTileResult> inputs;
    for (int d : tiles[static_cast<size_t>(next)].depends_on) inputs.push_back(results[static_cast<size_t>(d)]);
    results[static_cast<size_t>(next)] = EvaluateWorkspaceTile(model, options, next, inputs);
    finished[static_cast<size_t>(next)] = true;
    const WorkspaceTile& tile = tiles[static_cast<size_t>(next)];
    for (size_t k = 0; k < tile.rows.size(); ++k) map[static_cast<size_t>(tile.rows[k])] = results[static_cast<size_t>(next)].samples[k];
  }
  return map;
}

void ExpectSameSamples(const std::vector<WorkspaceSample>& a, const std::vector<WorkspaceSample>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].reachable, b[i].reachable) << i;
    EXPECT_EQ(a[i].start, b[i].start) << i;
    EXPECT_EQ(a[i].wave, b[i].wave) << i;
    EXPECT_EQ(a[i].tile, b[i].tile) << i;
    EXPECT_EQ(a[i].controls, b[i].controls) << i;  // bit for bit
    EXPECT_EQ(a[i].sigma_min, b[i].sigma_min) << i;
    EXPECT_EQ(a[i].residual_energy, b[i].residual_energy) << i;
    EXPECT_EQ(a[i].pose.position, b[i].pose.position) << i;
  }
}

TEST(Workspace, ThreadCountDoesNotChangeResults) {
  const Model model = LoadModel(ModelFile("4dof_reduced"));
  WorkspaceOptions options;
  options.ranges = {{kX, -0.3, 0.3}, {kY, -0.3, 0.3}, {kZ, 0.4, 0.95}};
  options.random_samples = 200;
  options.wave_size = 5;
  options.seed = 7;
  options.tile_size = 2;  // draws as a 6 x 6 x 6 grid: bins of 3 x 3 x 3 tiles
  const WorkspaceResult one = ComputeWorkspace(model, options);
  options.threads = 2;
  const WorkspaceResult two = ComputeWorkspace(model, options);
  EXPECT_EQ(one.tiles, 27);
  ExpectSameSamples(one.samples, two.samples);
  ExpectSameSamples(one.samples, TileByTile(model, options));
  EXPECT_GT(one.reachable, 100);
  EXPECT_LT(one.reachable, 200);  // some draws above z = 0.85
  for (const WorkspaceSample& a : one.samples) {
    // Reachability of random draws matches the closed form (the edge is z = 0.85).
    std::vector<Eigen::Vector3d> bases;
    if (std::abs(a.pose.position.z() - 0.85) > 0.01) {
      EXPECT_EQ(a.reachable, ClosedFormReachable(model, a.pose, &bases)) << " z " << a.pose.position.z();
    }
  }
}

// A grid in tiles of 4 x 4 cells (with partial tiles at the far ends):
// the same map on 1 and 3 threads and tile by tile; every row in exactly
// one tile; the tiles, their seeds and their dependencies come from the
// options and the home pose alone.
TEST(Workspace, TilesCoverTheGridOnceAndMapsDoNotDependOnThreads) {
  const Model model = LoadModel(ModelFile("4dof_reduced"));
  WorkspaceOptions options;
  options.ranges = {{kX, -0.4, 0.4}, {kZ, 0.3, 1.2}};
  options.resolution = 18;  // 5 x 5 tiles of up to 4 x 4 cells
  options.tile_size = 4;
  const std::vector<WorkspaceTile> tiles = WorkspaceTiles(model, options);
  ASSERT_EQ(tiles.size(), 25u);
  std::vector<int> seen(18 * 18, 0);
  for (const WorkspaceTile& t : tiles) {
    for (long long row : t.rows) ++seen[static_cast<size_t>(row)];
    EXPECT_TRUE(std::is_sorted(t.rows.begin(), t.rows.end()));
    for (int d : t.depends_on) EXPECT_LT(tiles[static_cast<size_t>(d)].order, t.order);
  }
  for (int count : seen) EXPECT_EQ(count, 1);
  EXPECT_EQ(tiles[24].rows.size(), 4u);  // the corner tile: 2 x 2 cells
  // Home (x 0, z 0.6) is nearest cell (9, 6) (x = +0.0235 by rounding): tile
  // (2, 1) = 11 has order 0; tile 0 = (0, 0) has order 2 + 1 and depends on
  // (0, 1), (1, 0) and (1, 1).
  EXPECT_EQ(tiles[11].order, 0);
  EXPECT_TRUE(tiles[11].depends_on.empty());
  EXPECT_EQ(tiles[0].order, 3);
  EXPECT_EQ(tiles[0].depends_on, (std::vector<int>{1, 5, 6}));
  WorkspaceOptions three = options;
  three.threads = 3;
  const std::vector<WorkspaceTile> again = WorkspaceTiles(model, three);
  for (size_t t = 0; t < tiles.size(); ++t) {
    EXPECT_EQ(again[t].rows, tiles[t].rows);
    EXPECT_EQ(again[t].depends_on, tiles[t].depends_on);
  }
  const WorkspaceResult one = ComputeWorkspace(model, options);
  const WorkspaceResult threaded = ComputeWorkspace(model, three);
  ExpectSameSamples(one.samples, threaded.samples);
  ExpectSameSamples(one.samples, TileByTile(model, options));
  EXPECT_EQ(one.samples[9 * 18 + 6].start, -1);  // home's cell starts from home
  EXPECT_EQ(one.samples[9 * 18 + 6].wave, 0);
  EXPECT_EQ(one.samples[9 * 18 + 6].tile, 11);
  // The same reachable count as one tile (the global wave continuation):
  // 192 of 324 (z up to 0.85 m, from 0.3 m, where the legs pass horizontal).
  EXPECT_EQ(one.reachable, 192);
  WorkspaceOptions single = options;
  single.tile_size = 18;
  const WorkspaceResult global = ComputeWorkspace(model, single);
  EXPECT_EQ(global.tiles, 1);
  EXPECT_EQ(global.reachable, 192);
}

TEST(Workspace, PosesOnTheGridAndOthersAtHome) {
  const Model model = LoadModel(ModelFile("4dof_reduced"));
  const WorkspaceOptions options = ZYawGrid();
  const std::vector<PoseTarget> poses = WorkspacePoses(model, options);
  ASSERT_EQ(poses.size(), 64u);
  const EndEffectorPose home = ComputeEndEffectorPose(model, State::Home(model));
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(poses[i].position.z(), 0.40 + 0.1 * static_cast<double>(i / 8), 1e-12);  // first range slowest
    EXPECT_NEAR(poses[i].rpy.z(), -0.3 + 0.6 * static_cast<double>(i % 8) / 7, 1e-12);
    EXPECT_EQ(poses[i].position.x(), home.position.x());
    EXPECT_EQ(poses[i].position.y(), home.position.y());
  }
  // Seeded draws: reproducible, inside the ranges.
  WorkspaceOptions random = options;
  random.random_samples = 50;
  const std::vector<PoseTarget> a = WorkspacePoses(model, random), b = WorkspacePoses(model, random);
  ASSERT_EQ(a.size(), 50u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position, b[i].position);
    EXPECT_GE(a[i].position.z(), 0.40);
    EXPECT_LE(a[i].position.z(), 1.10);
  }
}

TEST(Workspace, ExplicitPosesFromHomeAndFromAGivenStart) {
  const Model model = LoadModel(ModelFile("4dof_reduced"));
  WorkspaceOptions options = ZYawGrid();
  const EndEffectorPose home = ComputeEndEffectorPose(model, State::Home(model));
  PoseTarget up{home.position + Eigen::Vector3d(0, 0, 0.1), home.rpy};
  PoseTarget too_high{home.position + Eigen::Vector3d(0, 0, 0.4), home.rpy};
  const std::vector<WorkspaceSample> from_home = EvaluateWorkspacePoses(model, options, {up, too_high});
  ASSERT_EQ(from_home.size(), 2u);
  EXPECT_TRUE(from_home[0].reachable);
  EXPECT_FALSE(from_home[1].reachable);
  // Starting at the reached sample itself: already there, same controls.
  const std::vector<WorkspaceSample> again =
      EvaluateWorkspacePoses(model, options, {up}, {{from_home[0].state, from_home[0].controls}});
  EXPECT_TRUE(again[0].reachable);
  EXPECT_LT((again[0].controls - from_home[0].controls).norm(), 1e-9);
  EXPECT_THROW(EvaluateWorkspacePoses(model, options, {up, up}, {{from_home[0].state, from_home[0].controls}}),
               std::invalid_argument);
}

// A sample whose walk needs more than kMaxPathSteps path steps (2 km in steps
// of 10 mm) is unreachable with the path's reason; the near ones are still
// mapped (the whole map used to be aborted with std::invalid_argument).
TEST(Workspace, SampleTooManyPathStepsAwayIsUnreachable) {
  const Model model = LoadModel(ModelFile("4dof_reduced"));
  WorkspaceOptions options;
  options.ranges = {{kX, 0.0, 2000.0}, {kZ, 0.5, 0.75}};
  options.resolution = 2;
  const WorkspaceResult result = ComputeWorkspace(model, options);
  ASSERT_EQ(result.samples.size(), 4u);
  EXPECT_EQ(result.reachable, 2);
  for (const WorkspaceSample& s : result.samples) {
    const bool near = s.pose.position.x() == 0.0;
    EXPECT_EQ(s.reachable, near) << "x " << s.pose.position.x() << " z " << s.pose.position.z() << ": " << s.warning;
    if (near) continue;
    EXPECT_NE(s.warning.find("100000 steps"), std::string::npos) << s.warning;
    EXPECT_EQ(s.steps, 0);
    EXPECT_EQ(s.sigma_min, 0);
    EXPECT_NEAR(s.error, 2000.0, 1e-6);  // still at its start, 2 km short
    EXPECT_EQ(s.controls.size(), model.num_controls());
    EXPECT_EQ(s.state.num_bodies(), model.num_bodies());
  }
  // A pose out of range is still refused, not taken for a far one.
  PoseTarget bad = result.samples[0].pose;
  bad.position.x() = std::nan("");
  EXPECT_THROW(EvaluateWorkspacePoses(model, options, {bad}), std::invalid_argument);
}

TEST(Workspace, OptionsAreBounded) {
  const Model model = LoadModel(ModelFile("4dof_reduced"));
  std::string why;
  EXPECT_TRUE(ZYawGrid().IsValid(model, &why)) << why;
  auto bad = [&](const std::function<void(WorkspaceOptions&)>& change, const std::string& word) {
    WorkspaceOptions o = ZYawGrid();
    change(o);
    std::string message;
    EXPECT_FALSE(o.IsValid(model, &message)) << word;
    EXPECT_NE(message.find(word), std::string::npos) << message;
    EXPECT_THROW(ComputeWorkspace(model, o), std::invalid_argument) << word;
  };
  bad([](WorkspaceOptions& o) { o.ranges.clear(); }, "ranges");
  bad([](WorkspaceOptions& o) { o.ranges.push_back({3, 0, 1}); }, "roll is not a controlled");
  bad([](WorkspaceOptions& o) { o.ranges.push_back({kZ, 0, 1}); }, "twice");
  bad([](WorkspaceOptions& o) { o.ranges[0].lo = 2; }, "lo <= hi");
  bad([](WorkspaceOptions& o) { o.ranges[0].hi = std::nan(""); }, "finite");
  bad([](WorkspaceOptions& o) { o.ranges[0].component = 9; }, "0..5");
  bad([](WorkspaceOptions& o) { o.resolution = 0; }, "resolution");
  bad([](WorkspaceOptions& o) { o.resolution = 1001; }, "exceed");  // 1001^2 > 1e6
  bad([](WorkspaceOptions& o) { o.random_samples = 100001; }, "samples");
  bad([](WorkspaceOptions& o) { o.threads = 0; }, "threads");
  bad([](WorkspaceOptions& o) { o.threads = 257; }, "threads");
  bad([](WorkspaceOptions& o) { o.wave_size = 0; }, "wave_size");
  bad([](WorkspaceOptions& o) { o.tile_size = -1; }, "tile_size");
  bad([](WorkspaceOptions& o) { o.tile_size = 10001; }, "tile_size");
  bad([](WorkspaceOptions& o) { o.control.lambda = 2; }, "control.lambda");
}

// ---- the command ------------------------------------------------------------

// gnuplot on PATH (the plots are optional without it).
bool HaveGnuplot() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path == nullptr ? "" : path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && access((dir + "/gnuplot").c_str(), X_OK) == 0) return true;
  }
  return false;
}

testing::ToolRun Ccma(const std::vector<std::string>& args) { return testing::RunTool(args, 300); }

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

TEST(WorkspaceCli, CsvColumnsAndJsonSummary) {
  const std::string out = ccma::testing::TestDir() + "/workspace_cli.csv";
  const testing::ToolRun r = Ccma({"workspace", "--model=" + ModelFile("4dof_reduced"), "--out=" + out,
                                   "--z=0.5:1.0", "--resolution=3", "--threads=2"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["samples"], 3);
  EXPECT_EQ(j["reachable"], 2);  // z = 0.5, 0.75 (not 1.0)
  EXPECT_GE(j["seconds"].get<double>(), 0);
  std::ifstream csv(out);
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "x,y,z,yaw,reachable,residual_energy,sigma_min,error,rcond,max_limit_violation,limited_by,wave,start,"
            "ee_std_m,u0,u1,u2,u3,u4,u5,u6,u7,u8");
  std::vector<std::vector<std::string>> rows;
  while (std::getline(csv, line)) rows.push_back(Split(line));
  ASSERT_EQ(rows.size(), 3u);
  for (const auto& row : rows) ASSERT_EQ(row.size(), 23u) << line;
  EXPECT_EQ(std::stod(rows[0][2]), 0.5);
  EXPECT_EQ(std::stod(rows[2][2]), 1.0);
  EXPECT_EQ(std::stod(rows[0][0]), 0.0);  // x, y, yaw at home
  EXPECT_EQ(rows[0][4], "1");
  EXPECT_EQ(rows[2][4], "0");
  EXPECT_GT(std::stod(rows[0][6]), 0);
  EXPECT_EQ(std::stod(rows[2][6]), 0);     // sigma_min 0 when unreachable
  // ee_std_m: a fraction of a millimetre-scale noise times the leverage; 0 when unreachable.
  EXPECT_GT(std::stod(rows[0][13]), 1e-4);
  EXPECT_LT(std::stod(rows[0][13]), 1e-2);
  EXPECT_EQ(std::stod(rows[2][13]), 0);
  EXPECT_FALSE(rows[0][14].empty());
  EXPECT_TRUE(rows[2][14].empty());        // no controls when unreachable
  EXPECT_TRUE(rows[2][22].empty());
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
}

TEST(WorkspaceCli, FarSamplesUnreachableNotAnAbort) {
  const std::string out = ccma::testing::TestDir() + "/workspace_far.csv";
  const testing::ToolRun r = Ccma({"workspace", "--model=" + ModelFile("4dof_reduced"), "--out=" + out,
                                   "--x=0:2000", "--z=0.5:0.75", "--resolution=2"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["samples"], 4);
  EXPECT_EQ(j["reachable"], 2);
  std::ifstream csv(out);
  std::string line;
  std::getline(csv, line);  // header
  std::vector<std::vector<std::string>> rows;
  while (std::getline(csv, line)) rows.push_back(Split(line));
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& row : rows) {
    ASSERT_GE(row.size(), 5u);
    EXPECT_EQ(row[4], std::stod(row[0]) == 0.0 ? "1" : "0") << "x " << row[0] << " z " << row[2];
  }
}

TEST(WorkspaceCli, HostileFlagsExitTwoWithNothingOnStdout) {
  const std::string model = "--model=" + ModelFile("4dof_reduced");
  const std::string out = "--out=" + ccma::testing::TestDir() + "/workspace_bad.csv";
  const std::vector<std::pair<std::vector<std::string>, std::string>> calls = {
      {{"workspace", model, out}, "range"},
      {{"workspace", model, out, "--z=0.5"}, "--z"},
      {{"workspace", model, out, "--z=1:0.5"}, "--z"},
      {{"workspace", model, out, "--z=a:b"}, "z"},
      {{"workspace", model, out, "--z=0:1:2"}, "--z"},
      {{"workspace", model, out, "--z=nan:1"}, "z"},
      {{"workspace", model, out, "--z=0:1e300"}, "--z"},
      {{"workspace", model, out, "--roll=0:1"}, "--roll"},
      {{"workspace", model, out, "--z=0:1", "--resolution=0"}, "--resolution"},
      {{"workspace", model, out, "--z=0:1", "--resolution=99999999999"}, "resolution"},
      {{"workspace", model, out, "--z=0:1", "--x=0:1", "--y=0:1", "--resolution=1000"}, "exceed"},
      {{"workspace", model, out, "--z=0:1", "--samples=-1"}, "--samples"},
      {{"workspace", model, out, "--z=0:1", "--samples=1000000"}, "--samples"},
      {{"workspace", model, out, "--z=0:1", "--threads=0"}, "--threads"},
      {{"workspace", model, out, "--z=0:1", "--threads=1000"}, "--threads"},
      {{"workspace", model, out, "--z=0:1", "--lambda=3"}, "lambda"},
      {{"workspace", model, "--z=0:1"}, "--out"},
      {{"workspace", out, "--z=0:1"}, "--model"},
      {{"workspace", model, "--out=" + ccma::testing::TestDir(), "--z=0:1"}, "out"},
      {{"workspace", model, out, "--z=0:1", "--bogus=1"}, "bogus"},
  };
  for (const auto& [args, word] : calls) {
    const testing::ToolRun r = Ccma(args);
    std::string joined;
    for (const std::string& a : args) joined += a + " ";
    EXPECT_EQ(r.status, 2) << joined << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << joined << "\n" << r.out;
    EXPECT_NE(r.err.find(word), std::string::npos) << joined << "\n" << r.err;
  }
}

TEST(WorkspaceCli, PlotsWrittenWhenGnuplotIsPresent) {
  const std::string dir = ccma::testing::TestDir() + "/workspace_plots";
  const testing::ToolRun r = Ccma({"workspace", "--model=" + ModelFile("4dof_reduced"),
                                   "--out=" + dir + "/w.csv", "--z=0.5:0.95", "--yaw=-0.2:0.2", "--resolution=3",
                                   "--plot=" + dir});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["reachable"], 6);
  std::ifstream dat(dir + "/workspace_slice.dat");
  int lines = 0;
  for (std::string line; std::getline(dat, line);) ++lines;
  EXPECT_EQ(lines, 9);
  if (HaveGnuplot()) {
    EXPECT_TRUE(std::ifstream(dir + "/reachability.png").good());
    EXPECT_TRUE(std::ifstream(dir + "/sigma_min.png").good());
  }
}

}  // namespace
}  // namespace ccma
