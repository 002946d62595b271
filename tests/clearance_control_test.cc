// Clearance kept by control and trajectories (model_format.md, "Collision
// geometry and obstacles"; cli.md, "Clearance in the output"): a redundant
// model goes round a pillar standing on a base's straight path, a model
// without the redundancy stops before it and names it, the bundled paths
// keep realistic base radii apart, a pair that starts below the margin is
// never made worse, and every CSV row's clearance is what the row's
// controls give.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "collision/clearance.h"
#include "formats/model_loader.h"
#include "formats/obstacles_file.h"
#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "problems/trajectory.h"
#include "tool_run.h"
#include "tests/tool_run.h"

namespace ccma {
namespace clearance_control_test {

std::string Bundled(const std::string& name) {
  return testing::Slurp(std::string(CCMA_MODELS_DIR) + "/" + name + ".yaml");
}

// The end-effector 1 m along +x in four waypoints, attitude kept.
std::vector<Waypoint> AlongX() {
  std::vector<Waypoint> path;
  for (int i = 1; i <= 4; ++i) path.push_back({double(i), Eigen::Vector3d(0.25 * i, 0, 0.6), Eigen::Vector3d::Zero()});
  return path;
}

// The smallest clearance over every checked pair, by brute force (no broad phase).
double BruteForceMinimum(const Model& model, const State& s) {
  const CollisionModel collision(model);
  std::vector<PlacedShape> shapes;
  collision.PlaceShapes(s, &shapes);
  double least = INFINITY;
  for (int i = 0; i < collision.num_shapes(); ++i) {
    for (int j = i + 1; j < collision.num_shapes(); ++j) {
      if (collision.Checked(i, j)) least = std::min(least, Distance(shapes[i], shapes[j]).distance);
    }
  }
  return least;
}

struct Walk {
  TrajectoryResult result;
  std::vector<TrajectoryStep> steps;
};
Walk Follow(const Model& model, const std::vector<Waypoint>& path) {
  ControlProblem control(model);
  control.SetControls(model.home_controls());
  Walk walk;
  walk.result = FollowWaypoints(control, path, [&](const TrajectoryStep& s) { walk.steps.push_back(s); });
  return walk;
}

// The smallest clearance between two shapes of the mechanism (no obstacle).
double MechanismMinimum(const Model& model, const State& s) {
  const CollisionModel collision(model);
  std::vector<PlacedShape> shapes;
  collision.PlaceShapes(s, &shapes);
  double least = INFINITY;
  for (int i = 0; i < collision.num_shapes(); ++i) {
    for (int j = i + 1; j < collision.num_shapes(); ++j) {
      if (collision.Checked(i, j) && collision.BodyOf(i) != kWorld &&
          collision.BodyOf(j) != kWorld) {
        least = std::min(least, Distance(shapes[i], shapes[j]).distance);
      }
    }
  }
  return least;
}

const char* kFarPillar =
    "obstacles:\n  - {name: far, cylinder: {center: [40, 40], radius: 0.1, height: 1.0}}\n";

// The smallest distance between two bases' home positions.
double SmallestSpacing(const Model& model) {
  double least = INFINITY;
  for (int a = 0; a < model.num_bases(); ++a) {
    for (int b = a + 1; b < model.num_bases(); ++b) {
      least = std::min(
          least,
          (model.mobile_bases[a].home_pose - model.mobile_bases[b].home_pose).head<2>().norm());
    }
  }
  return least;
}

// Every bundled model, obstacles added, starts with its own shapes apart:
// the default base radius never makes two bases overlap at home.
TEST(ClearanceControl, EveryBundledModelKeepsItsShapesApartAtHomeWithObstacles) {
  int with_shapes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CCMA_MODELS_DIR)) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string name = entry.path().filename().string();
    Model model = LoadModel(entry.path().string());
    AddObstaclesFromString(kFarPillar, "far.yaml", &model);
    const double least = MechanismMinimum(model, State::Home(model));
    if (model.num_bases() == 0) {  // planar_3rpr, stewart_gough_6ups: nothing of theirs is a shape
      EXPECT_EQ(least, INFINITY) << name;
      continue;
    }
    ++with_shapes;
    // At least twice the margin: each base may move a margin towards the other.
    EXPECT_GE(least, 2 * model.collision.margin - 1e-12) << name;
    for (double r : model.collision.base_radii) {
      EXPECT_GT(r, 0.05) << name;
      EXPECT_LE(r, 0.3) << name;
    }
  }
  EXPECT_GE(with_shapes, 7);
}

// The default radius: 0.3 m where the bases stand far apart, the largest
// that leaves twice the margin between the closest bases otherwise; a given
// base_radius wins.
TEST(ClearanceControl, DefaultBaseRadiusFollowsTheBasesSpacing) {
  const Model far_apart = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  EXPECT_EQ(far_apart.collision.base_radii, std::vector<double>(3, 0.3));
  const std::string six = Bundled("6dof_six_agents");
  const Model close = LoadModelFromString(six, "six.yaml");
  const double d = SmallestSpacing(close);
  EXPECT_NEAR(d, 0.2263513, 1e-6);
  for (double r : close.collision.base_radii) EXPECT_NEAR(r, 0.5 * d - 0.02, 1e-12);
  const Model wide_margin = LoadModelFromString(six + "collision: {margin: 0.05}\n", "six.yaml");
  for (double r : wide_margin.collision.base_radii) EXPECT_NEAR(r, 0.5 * d - 0.05, 1e-12);
  EXPECT_NEAR(MechanismMinimum(wide_margin, State::Home(wide_margin)), 0.1, 1e-9);
  const Model given = LoadModelFromString(six + "collision: {base_radius: 0.12}\n", "six.yaml");
  EXPECT_EQ(given.collision.base_radii, std::vector<double>(6, 0.12));
}

// Two bases 3 cm apart leave no room for a default radius: with clearance
// on, the model is refused and the message names the key to set.
TEST(ClearanceControl, BasesTooCloseForADefaultRadiusAreRefusedNamingTheKey) {
  const std::string text =
      "name: close_pair\nbodies:\n  - {name: bar, position: [0, 0, 0.5]}\n"
      "mobile_bases:\n  - {name: left, type: omni, actuation: complete, pose: [0, 0, 0]}\n  - "
      "{name: right, type: omni, actuation: complete, pose: [0.03, 0, 0]}\n"
      "joints:\n  - {type: spherical, between: [left, bar], point: [0, 0, 0.5]}\n"
      "  - {type: spherical, between: [right, bar], point: [0.03, 0, 0.5]}\n"
      "end_effector: {body: bar, point: [0, 0, 0.5], controlled: [x, y]}\n";
  try {
    LoadModelFromString(text + kFarPillar, "close.yaml");
    ADD_FAILURE() << "loaded";
  } catch (const ModelError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("close.yaml:"), std::string::npos) << what;
    EXPECT_NE(what.find("collision.base_radius"), std::string::npos) << what;
    EXPECT_NE(what.find("'left' and 'right' stand 0.03 m apart"), std::string::npos) << what;
  }
  Model plain = LoadModelFromString(text, "close.yaml");  // no clearance asked: loads
  EXPECT_THROW(AddObstaclesFromString(kFarPillar, "far.yaml", &plain), ModelError);
  EXPECT_TRUE(plain.collision.obstacles.empty());
  EXPECT_NO_THROW(
      LoadModelFromString(text + "collision: {base_radius: 0.01}\n" + kFarPillar, "close.yaml"));
  EXPECT_NO_THROW(LoadModelFromString(text + "collision: {ignore: [[left, right]]}\n" + kFarPillar,
                                      "close.yaml"));
  const std::string dir = ccma::testing::TestDir();
  std::ofstream(dir + "/close.yaml") << text;
  std::ofstream(dir + "/far.yaml") << kFarPillar;
  const testing::ToolRun run = testing::RunTool(
      {"check", "--model=" + dir + "/close.yaml", "--obstacles=" + dir + "/far.yaml"});
  EXPECT_EQ(run.status, 2);
  EXPECT_TRUE(run.out.empty());
  EXPECT_NE(run.err.find("collision.base_radius"), std::string::npos) << run.err;
}

// The bundled 6-agent model with a pillar added on the command line
// (--obstacles): every step keeps the margin, base1 goes round the pillar,
// and no two bases are ever the pair that stops it.
TEST(ClearanceControl, SixAgentsWithAPillarAddedGoRoundItNotThroughEachOther) {
  const std::string obstacles =
      std::string(CCMA_MODELS_DIR) + "/../examples/obstacles/pillar_six_agents.yaml";
  Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/6dof_six_agents.yaml");
  AddObstaclesFromFile(obstacles, &model);
  const Walk walk = Follow(model, AlongX());
  EXPECT_TRUE(walk.result.converged) << walk.result.warning;
  const Eigen::Vector2d pillar(-0.05, 0.26);
  const double base_radius = model.collision.base_radii[1];
  for (const TrajectoryStep& s : walk.steps) {
    EXPECT_GE(BruteForceMinimum(model, s.state), model.collision.margin - 1e-9);
    EXPECT_GE((s.controls.segment<2>(3) - pillar).norm(),
              0.1 + base_radius + model.collision.margin - 1e-9);
  }
  const std::string dir = ccma::testing::TestDir();
  const testing::ToolRun run = testing::RunTool(
      {"trajectory", "--model=" + std::string(CCMA_MODELS_DIR) + "/6dof_six_agents.yaml",
       "--obstacles=" + obstacles,
       "--waypoints=" + std::string(CCMA_MODELS_DIR) + "/../examples/obstacles/path_x.csv",
       "--out=" + dir + "/six.csv"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("\"converged\": true"), std::string::npos) << run.out;
  EXPECT_EQ(run.err.find("below the margin"), std::string::npos) << run.err;
  std::istringstream csv(testing::Slurp(dir + "/six.csv"));
  std::string line;
  std::getline(csv, line);
  int rows = 0;
  for (; std::getline(csv, line); ++rows) {
    const size_t pair = line.rfind(',');
    const double clearance = std::stod(line.substr(line.rfind(',', pair - 1) + 1));
    EXPECT_GE(clearance, model.collision.margin - 1e-9) << line.substr(pair + 1);
  }
  EXPECT_EQ(rows, 100);
}

// 6dof_six_agents (12 controls for 6 components): base1's straight path
// without obstacles passes (-0.05, 0.26) when the end-effector is half way.
const char* kSixAgentsPillar =
    "collision:\n  margin: 0.05\n  base_radius: 0.08\n"
    "obstacles:\n  - {name: pillar, cylinder: {center: [-0.05, 0.26], radius: 0.1, height: 1.0}}\n";

TEST(ClearanceControl, RedundantModelGoesRoundAPillarOnItsPath) {
  const Model free_model = LoadModelFromString(Bundled("6dof_six_agents"), "free.yaml");
  const Walk straight = Follow(free_model, AlongX());
  ASSERT_TRUE(straight.result.converged);
  const Eigen::Vector2d pillar(-0.05, 0.26);
  double nearest = INFINITY;  // base1 without the pillar: through it
  for (const TrajectoryStep& s : straight.steps) nearest = std::min(nearest, (s.controls.segment<2>(3) - pillar).norm());
  EXPECT_LT(nearest, 0.02);

  const Model model = LoadModelFromString(Bundled("6dof_six_agents") + kSixAgentsPillar, "pillar.yaml");
  const Walk walk = Follow(model, AlongX());
  EXPECT_TRUE(walk.result.converged) << walk.result.warning;
  EXPECT_LT(walk.result.max_error, 1e-6);
  double least = INFINITY, detour = INFINITY;
  for (const TrajectoryStep& s : walk.steps) {
    EXPECT_TRUE(s.result.reached);
    least = std::min(least, BruteForceMinimum(model, s.state));
    detour = std::min(detour, (s.controls.segment<2>(3) - pillar).norm());
  }
  EXPECT_GE(least, 0.05 - 1e-9);
  EXPECT_LT(least, 0.05 + 1e-6);      // it did hold a pair at the margin
  EXPECT_GE(detour, 0.1 + 0.08 + 0.05 - 1e-9);  // base1 kept off the pillar
  EXPECT_NEAR(walk.steps.back().reached.position.x(), 1.0, 1e-6);
}

TEST(ClearanceControl, ModelWithoutRedundancyStopsBeforeThePillarAndNamesIt) {
  // 4dof_reduced with all six components controlled: 6 controls for 6.
  std::string text = Bundled("4dof_reduced");
  text.replace(text.find("controlled: [x, y, z, yaw]"), 26, "controlled: [x, y, z, roll, pitch, yaw]");
  text += "collision:\n  margin: 0.05\n  base_radius: 0.15\n"
          "obstacles:\n  - {name: pillar, cylinder: {center: [1.0, -0.29], radius: 0.1, height: 1.0}}\n";
  const Model model = LoadModelFromString(text, "stop.yaml");
  const Walk walk = Follow(model, AlongX());
  EXPECT_FALSE(walk.result.converged);
  EXPECT_NE(walk.result.warning.find("clearance between 'base2' and 'pillar' at the margin 0.05 m"),
            std::string::npos)
      << walk.result.warning;
  ASSERT_FALSE(walk.steps.empty());
  for (const TrajectoryStep& s : walk.steps) {
    if (s.result.assembled) EXPECT_GE(BruteForceMinimum(model, s.state), 0.05 - 1e-9);
  }
  // It stopped before the pillar: base2 (radius 0.15) short of it by the margin.
  const double x_stop = walk.steps.back().controls[6];
  EXPECT_LT(x_stop, 1.0 - 0.1 - 0.15);
  EXPECT_GT(walk.steps.back().reached.position.x(), 0.1);  // after moving a good way
}

TEST(ClearanceControl, BundledPathsKeepRealisticBasesApart) {
  for (const char* name : {"4dof_reduced", "4dof_complete", "6dof_symmetric"}) {
    const Model model =
        LoadModelFromString(Bundled(name) + "collision:\n  margin: 0.05\n  base_radius: 0.25\n", "paths.yaml");
    for (const char* path : {"4dof_combined", "4dof_sequential"}) {
      const Walk walk = Follow(model, LoadWaypoints(std::string(CCMA_MODELS_DIR) + "/paths/" + path + ".csv"));
      EXPECT_TRUE(walk.result.converged) << name << " " << path;
      for (const TrajectoryStep& s : walk.steps) EXPECT_GE(BruteForceMinimum(model, s.state), 0.05) << name;
    }
  }
}

TEST(ClearanceControl, APairBelowTheMarginAtTheStartIsNeverMadeWorse) {
  // 6dof_six_agents with base radius 0.12: base1 and base2 (0.226 m apart)
  // overlap by 0.014 m at home.
  const Model model =
      LoadModelFromString(Bundled("6dof_six_agents") + "collision:\n  margin: 0.05\n  base_radius: 0.12\n", "o.yaml");
  const double start = BruteForceMinimum(model, State::Home(model));
  ASSERT_NEAR(start, std::hypot(0.612447096 - 0.499271447, 0.418938487 - 0.222912513) - 0.24, 1e-9);
  const Walk walk = Follow(model, AlongX());
  EXPECT_TRUE(walk.result.converged) << walk.result.warning;  // the overlap does not freeze it
  EXPECT_GT(walk.steps.size(), 50u);
  for (const TrajectoryStep& s : walk.steps) EXPECT_GE(BruteForceMinimum(model, s.state), start - 1e-9);
}

// Every trajectory row's clearance_m is what its controls give, simulated
// again from home, row after row (the check the contract allows a user).
TEST(ClearanceControl, TrajectoryCsvRowsCarryTheirClearance) {
  const std::string dir = ccma::testing::TestDir();
  {
    std::ofstream(dir + "/pillar.yaml") << Bundled("6dof_six_agents") << kSixAgentsPillar;
    std::ofstream path(dir + "/path.csv");
    path << "time,x,y,z,roll,pitch,yaw\n";
    for (const Waypoint& w : AlongX()) path << w.time << "," << w.position.x() << ",0,0.6,0,0,0\n";
  }
  const testing::ToolRun run = testing::RunTool({"trajectory", "--model=" + dir + "/pillar.yaml",
                                                 "--waypoints=" + dir + "/path.csv", "--out=" + dir + "/rows.csv"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("\"min_on_path\""), std::string::npos);
  const Model model = LoadModel(dir + "/pillar.yaml");
  std::istringstream csv(testing::Slurp(dir + "/rows.csv"));
  std::string line;
  std::getline(csv, line);
  ASSERT_NE(line.find(",clearance_m,clearance_pair"), std::string::npos);
  ForwardProblem forward(model);
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    Eigen::VectorXd u(model.num_controls());
    for (int i = 0; i < u.size(); ++i) u[i] = std::stod(cells[13 + i]);
    ASSERT_TRUE(forward.Solve(u).assembled);
    const ClearanceSummary c = MinimumClearance(CollisionModel(model), forward.state());
    EXPECT_NEAR(std::stod(cells[cells.size() - 2]), c.min, 1e-6);
    EXPECT_EQ(cells.back(), c.a + "|" + c.b);
    EXPECT_GE(c.min, 0.05 - 1e-9);
    ++rows;
  }
  EXPECT_GT(rows, 50);
}

TEST(ClearanceControl, CliReportsClearanceAndNamesTheStoppingPair) {
  const std::string dir = ccma::testing::TestDir();
  { std::ofstream(dir + "/room.yaml") << "obstacles:\n  - {name: pillar, cylinder: {center: [1.0, -0.29], radius: 0.1, height: 1.0}}\n"; }
  const std::string model = std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml";
  const testing::ToolRun check = testing::RunTool({"check", "--model=" + model, "--obstacles=" + dir + "/room.yaml"});
  ASSERT_EQ(check.status, 0) << check.err;
  // Home: base2 at (0.505, -0.292) with the default radius 0.3.
  EXPECT_NE(check.out.find("\"pair\": [\"base2\",\"pillar\"]"), std::string::npos) << check.out;
  const testing::ToolRun control = testing::RunTool(
      {"control", "--model=" + model, "--obstacles=" + dir + "/room.yaml", "--target=0.5,0,0.6,0,0,0"});
  ASSERT_EQ(control.status, 0) << control.err;
  EXPECT_NE(control.out.find("\"converged\": false"), std::string::npos);
  EXPECT_NE(control.err.find("'base2' and 'pillar'"), std::string::npos) << control.err;
  const testing::ToolRun bad = testing::RunTool({"simulate", "--model=" + model, "--obstacles=" + dir + "/none.yaml"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_TRUE(bad.out.empty());
  EXPECT_NE(bad.err.find("none.yaml"), std::string::npos);
}

}  // namespace
}  // namespace ccma
