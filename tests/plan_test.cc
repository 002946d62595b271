// Whole-trajectory planning (problems/plan.h, `ccma plan`): it finds a detour
// where the greedy walk stalls against a pillar, keeps every step and every
// midpoint between steps clear of it, is never worse than the greedy walk,
// and refuses what it does not handle.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ccma/internal/format.h"
#include "collision/clearance.h"
#include "formats/model_loader.h"
#include "formats/waypoints.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "problems/internal/plan_finish.h"
#include "problems/plan.h"
#include "problems/trajectory.h"
#include "tool_run.h"
#include "tests/tool_run.h"

namespace ccma {
namespace plan_test {

const std::string kExamples = std::string(CCMA_SOURCE_DIR) + "/examples/obstacles/";

double Clearance(const Model& model, const State& s) {
  const ClearanceSummary c = MinimumClearance(CollisionModel(model), s);
  return c.any ? c.min : INFINITY;
}

TEST(Plan, FindsTheDetourWhereTheGreedyWalkStalls) {
  const Model model = LoadModel(kExamples + "pillar_detour.yaml");
  const std::vector<Waypoint> path = LoadWaypoints(kExamples + "one_metre_x.csv");
  {  // The greedy walk stops in front of the pillar and names it.
    ControlProblem greedy(model);
    greedy.SetControls(model.home_controls());
    const TrajectoryResult walked = FollowWaypoints(greedy, path, nullptr);
    EXPECT_FALSE(walked.converged);
    EXPECT_NE(walked.warning.find("'base2' and 'pillar'"), std::string::npos) << walked.warning;
  }
  ControlProblem problem(model);
  problem.SetControls(model.home_controls());
  const PlanResult plan = PlanTrajectory(problem, path);
  ASSERT_TRUE(plan.used_plan) << plan.note;
  EXPECT_TRUE(plan.converged);
  EXPECT_EQ(plan.plan.reached_waypoints, 2);
  EXPECT_EQ(plan.greedy.reached_waypoints, 1);
  const TrajectoryStep& last = plan.steps.back();
  EXPECT_LT((last.reached.position - Eigen::Vector3d(1.0, 0, 0.6)).norm(), 1e-9);
  // Every step assembled and clear; base2 passes the pillar beside it.
  ForwardProblem forward(model);
  Eigen::VectorXd u = model.home_controls();
  State s = State::Home(model);
  bool beside = false;
  for (const TrajectoryStep& step : plan.steps) {
    EXPECT_TRUE(step.result.assembled);
    EXPECT_GE(Clearance(model, step.state), 0.05 - 1e-9);
    const Eigen::Vector2d base2 = step.controls.segment<2>(6);
    beside = beside || (std::abs(base2.x() - 1.0) < 0.05 && std::abs(base2.y() + 0.29) >= 0.1 + 0.15 + 0.05);
    // Half-way between this step and the last, re-solved: clear too.
    forward.SetState(s);
    forward.Solve(0.5 * (u + step.controls));
    EXPECT_GE(Clearance(model, forward.state()), 0.05 - 1e-6);
    u = step.controls;
    s = step.state;
  }
  EXPECT_TRUE(beside);
  EXPECT_NEAR(plan.plan.min_clearance_m, 0.154, 0.01);
}

TEST(Plan, IsNeverWorseThanTheGreedyWalk) {
  struct Case {
    std::string model, path;
  };
  for (const Case& c : {Case{std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml",
                             std::string(CCMA_MODELS_DIR) + "/paths/4dof_sequential.csv"},
                        Case{kExamples + "six_agents_pillar.yaml", kExamples + "path_x.csv"}}) {
    const Model model = LoadModel(c.model);
    ControlProblem problem(model);
    problem.SetControls(model.home_controls());
    PlanOptions options;
    options.max_iterations = 30;  // the comparison holds after any number
    const PlanResult plan = PlanTrajectory(problem, LoadWaypoints(c.path), options);
    const PathMeasures& chosen = plan.used_plan ? plan.plan : plan.greedy;
    EXPECT_GE(chosen.reached_waypoints, plan.greedy.reached_waypoints) << c.model;
    if (chosen.reached_waypoints == plan.greedy.reached_waypoints) {
      EXPECT_LE(chosen.travel_m, plan.greedy.travel_m + 1e-9) << c.model;
    }
    EXPECT_GE(chosen.min_clearance_m, std::min(plan.greedy.min_clearance_m, model.collision.margin) - 1e-9);
    EXPECT_TRUE(plan.converged) << c.model;
    EXPECT_EQ(plan.used_plan, plan.note.empty());
  }
}

// The six agents round a pillar, planned with 5 iterations: the optimised
// steps keep the margin only to the constraints' trial slack, and half way
// between steps base1 cuts the pillar's margin by about 0.1 mm (straight
// chords of a curve). The plan is finished, not thrown away: every row at
// the margin to 1e-9 m, every midpoint within 1e-6 m of it.
TEST(Plan, FinishesAPlanThatEndsWithinAMillimetreOfTheMargin) {
  const Model model = LoadModel(kExamples + "six_agents_pillar.yaml");
  ControlProblem problem(model);
  problem.SetControls(model.home_controls());
  PlanOptions options;
  options.max_iterations = 5;
  const PlanResult plan = PlanTrajectory(problem, LoadWaypoints(kExamples + "path_x.csv"), options);
  ASSERT_TRUE(plan.used_plan) << plan.note;
  EXPECT_TRUE(plan.converged);
  EXPECT_FALSE(plan.shortfall.any);
  EXPECT_GT(plan.inserted_rows, 0);  // it had midpoints to restore
  EXPECT_EQ(plan.stopped_by, "plan_iterations");
  ForwardProblem forward(model);
  Eigen::VectorXd u = model.home_controls();
  State s = State::Home(model);
  double least = INFINITY;
  for (const TrajectoryStep& step : plan.steps) {
    EXPECT_TRUE(step.result.assembled);
    least = std::min(least, Clearance(model, step.state));
    forward.SetState(s);
    forward.Solve(0.5 * (u + step.controls));
    EXPECT_GE(Clearance(model, forward.state()), 0.05 - 1e-6);
    u = step.controls;
    s = step.state;
  }
  EXPECT_GE(least, 0.05 - 1e-9);
  EXPECT_LT(least, 0.05 + 1e-6);  // base1 does pass the pillar at the margin
  EXPECT_NEAR(plan.plan.min_clearance_m, least, 1e-12);
  EXPECT_NEAR(plan.steps.back().reached.position.x(), 1.0, 1e-6);
}

// Rows on both sides of a wall: a jump through it, which no midpoint row
// can mend. The finishing reports it: the pair, the row, the shortfall.
TEST(Plan, FinishingNamesThePairTheRowAndTheShortfallOfAJumpThroughAWall) {
  Model model = LoadModel(kExamples + "pillar_detour.yaml");
  model.collision.obstacles.push_back(model.collision.obstacles[0]);
  Obstacle& wall = model.collision.obstacles.back();
  wall.name = "wall";
  wall.shape = ObstacleShape::kBox;
  wall.center = Eigen::Vector3d(1.0, 0, 0.5);
  wall.size = Eigen::Vector3d(0.1, 20, 1.0);
  wall.z_min = 0;
  wall.z_max = 1.0;
  ControlProblem problem(model);
  problem.SetControls(model.home_controls());
  // Every base 2 m along x: a rigid translation, assembled and clear of
  // the wall at both ends.
  Eigen::VectorXd far = model.home_controls();
  for (int k = 0; k < model.num_bases(); ++k) far[3 * k] += 2.0;
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Assemble(far).assembled);
  TrajectoryStep row;
  row.time = 1.0;
  row.controls = far;
  row.state = forward.state();
  row.reached = forward.end_effector();
  row.target = PoseTarget{row.reached.position, row.reached.rpy};
  row.result.assembled = row.result.reached = true;
  ASSERT_GE(Clearance(model, row.state), 0.05);
  std::vector<TrajectoryStep> rows = {row};
  int inserted = 0, repaired = 0;
  const PlanShortfall f = FinishPlan(problem, model.home_controls(), State::Home(model), 0.0, &rows,
                                     &inserted, &repaired);
  ASSERT_TRUE(f.any);
  EXPECT_TRUE(f.midpoint);
  EXPECT_FALSE(f.torn);
  EXPECT_TRUE(f.a == "wall" || f.b == "wall") << f.a << " " << f.b;
  EXPECT_GE(f.step, 1);
  EXPECT_EQ(
      f.step, 1 + [&] {  // the rows inserted before the midpoint
        int before = 0;
        for (size_t k = 0; k + 1 < rows.size() && rows[k].time < f.time_s; ++k) ++before;
        return before;
      }());
  EXPECT_GT(f.time_s, 0.0);
  EXPECT_LT(f.time_s, 1.0);
  EXPECT_EQ(f.floor_m, 0.05);
  EXPECT_NEAR(f.shortfall_m, f.floor_m - f.clearance_m, 1e-15);
  EXPECT_GT(f.shortfall_m, 1e-6);
  EXPECT_EQ(static_cast<int>(rows.size()), 1 + inserted);
  const std::string text = DescribeShortfall(f, 0.05);
  std::ostringstream between;
  between << "half way between the plan's rows " << f.step - 1 << " and " << f.step;
  EXPECT_NE(text.find(between.str()), std::string::npos) << text;
  EXPECT_NE(text.find("'wall'"), std::string::npos) << text;
  EXPECT_NE(text.find(FormatG(f.shortfall_m) + " m below the margin 0.05 m"), std::string::npos)
      << text;
}

// The time bound stops the seeds and the optimisation and says so; the
// plan is still finished and chosen. Progress is reported in every phase.
TEST(Plan, TimeBoundStopsTheOptimisationAndProgressIsReported) {
  const Model model = LoadModel(kExamples + "pillar_detour.yaml");
  ControlProblem problem(model);
  problem.SetControls(model.home_controls());
  PlanOptions options;
  std::vector<PlanProgress> seen;
  options.on_progress = [&](const PlanProgress& p) { seen.push_back(p); };
  const PlanResult plan =
      PlanTrajectory(problem, LoadWaypoints(kExamples + "one_metre_x.csv"), options);
  ASSERT_TRUE(plan.used_plan) << plan.note;
  EXPECT_EQ(plan.stopped_by, "converged");
  std::vector<std::string> phases;
  for (const PlanProgress& p : seen) {
    if (phases.empty() || phases.back() != p.phase) phases.push_back(p.phase);
    EXPECT_LE(p.done, p.total) << p.phase;
  }
  EXPECT_EQ(phases,
            std::vector<std::string>({"greedy walk", "detour seeds", "optimisation", "finishing"}));
  for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i].elapsed_s, seen[i - 1].elapsed_s);

  const std::string dir = ccma::testing::TestDir();
  const testing::ToolRun run =
      testing::RunTool({"plan", "--model=" + kExamples + "pillar_detour.yaml",
                        "--waypoints=" + kExamples + "one_metre_x.csv",
                        "--out=" + dir + "/bounded.csv", "--plan_time_s=0"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("\"stopped_by\": \"plan_time_s\""), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("\"iterations\": 0"), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("--plan_time_s=0"), std::string::npos) << run.err;
  const testing::ToolRun bad =
      testing::RunTool({"plan", "--model=" + kExamples + "pillar_detour.yaml",
                        "--waypoints=" + kExamples + "one_metre_x.csv", "--out=" + dir + "/no.csv",
                        "--plan_time_s=-1"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_TRUE(bad.out.empty());
  EXPECT_NE(bad.err.find("--plan_time_s"), std::string::npos) << bad.err;
}

TEST(Plan, RefusesWhatItDoesNotHandle) {
  const Model differential = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_differential.yaml");
  ControlProblem arcs(differential);
  const std::vector<Waypoint> path = {{1.0, Eigen::Vector3d(0.01, 0, 0.6), Eigen::Vector3d::Zero()}};
  EXPECT_THROW(PlanTrajectory(arcs, path), std::invalid_argument);
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  ControlOptions bfgs;
  bfgs.method = ControlMethod::kBfgs;
  ControlProblem with_bfgs(model, bfgs);
  EXPECT_THROW(PlanTrajectory(with_bfgs, path), std::invalid_argument);
  ControlProblem problem(model);
  PlanOptions bad;
  bad.path_weight = -1;
  EXPECT_THROW(PlanTrajectory(problem, path, bad), std::invalid_argument);
  bad = PlanOptions();
  bad.max_iterations = 0;
  EXPECT_FALSE(bad.IsValid(nullptr));
}

TEST(Plan, CliWritesTheTrajectoryCsvAndSaysWhichItKept) {
  const std::string dir = ccma::testing::TestDir();
  const testing::ToolRun run =
      testing::RunTool({"plan", "--model=" + kExamples + "pillar_detour.yaml",
                        "--waypoints=" + kExamples + "one_metre_x.csv", "--out=" + dir + "/plan.csv"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("\"used\": \"plan\""), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("\"converged\": true"), std::string::npos);
  const std::string csv = testing::Slurp(dir + "/plan.csv");
  EXPECT_EQ(csv.rfind("time_s,target_x_m,", 0), 0u);
  EXPECT_NE(csv.find(",clearance_m,clearance_pair\n"), std::string::npos);
  const testing::ToolRun refused =
      testing::RunTool({"plan", "--model=" + std::string(CCMA_MODELS_DIR) + "/4dof_differential.yaml",
                        "--waypoints=" + kExamples + "one_metre_x.csv", "--out=" + dir + "/no.csv"});
  EXPECT_EQ(refused.status, 2);
  EXPECT_TRUE(refused.out.empty());
  EXPECT_NE(refused.err.find("differential"), std::string::npos);
  const testing::ToolRun bad_flag = testing::RunTool(
      {"plan", "--model=" + kExamples + "pillar_detour.yaml", "--waypoints=" + kExamples + "one_metre_x.csv",
       "--out=" + dir + "/no.csv", "--path_weight=-1"});
  EXPECT_EQ(bad_flag.status, 2);
  EXPECT_NE(bad_flag.err.find("--path_weight"), std::string::npos) << bad_flag.err;
}

}  // namespace
}  // namespace ccma
