#include "problems/plan.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ccma/internal/format.h"
#include "ccma/internal/in_range.h"
#include "collision/clearance.h"
#include "problems/internal/control_workspace.h"
#include "problems/internal/detour_seeds.h"
#include "problems/internal/plan_finish.h"
#include "problems/internal/trajectory_planner.h"
#include "problems/path.h"

namespace ccma {
namespace {

// The plan's unknowns (steps x effective controls) are bounded: its sparse
// KKT system is factorised in every iteration.
constexpr long kMaxPlanUnknowns = 100000;


// The greedy steps of the legs it completed, then straight-path steps for
// the others, all at the last assembled configuration.
// Only the user's waypoints (`original`) are waypoints to the plan.
std::vector<PlannedStep> StartingSteps(const ControlProblem& problem, const SeededPath& seeded,
                                       const std::vector<TrajectoryStep>& greedy, int reached,
                                       const Eigen::VectorXd& u0, const State& s0, const PoseTarget& start_pose) {
  const std::vector<Waypoint>& waypoints = seeded.waypoints;
  std::vector<PlannedStep> steps;
  for (size_t i = 0; i < greedy.size(); ++i) {
    if (greedy[i].leg >= reached) break;
    const bool leg_end = i + 1 == greedy.size() || greedy[i + 1].leg != greedy[i].leg;
    const bool waypoint = leg_end && seeded.original[static_cast<size_t>(greedy[i].leg)];
    steps.push_back({greedy[i].target, waypoint, greedy[i].controls, greedy[i].state, greedy[i].result.residual_energy});
  }
  const ControlOptions& o = problem.options();
  PoseTarget from = reached == 0 ? start_pose
                                 : PoseTarget{waypoints[static_cast<size_t>(reached - 1)].position,
                                              waypoints[static_cast<size_t>(reached - 1)].rpy};
  const Eigen::VectorXd u = steps.empty() ? u0 : steps.back().u;
  const State s = steps.empty() ? s0 : steps.back().s;
  const double energy = steps.empty() ? problem.forward().Energy() : steps.back().energy;
  for (size_t w = static_cast<size_t>(reached); w < waypoints.size(); ++w) {
    const PoseTarget to{waypoints[w].position, waypoints[w].rpy};
    const PosePath path(problem.forward().model(), from, to, o.max_step_m, o.max_step_rad);
    for (int i = 1; i <= path.steps(); ++i) {
      steps.push_back({path.At(i), i == path.steps() && seeded.original[w], u, s, energy});
    }
    from = to;
  }
  return steps;
}

PathMeasures Measure(const Model& model, const Eigen::VectorXd& u0, const std::vector<TrajectoryStep>& steps,
                     int reached) {
  PathMeasures m;
  m.reached_waypoints = reached;
  m.min_clearance_m = std::numeric_limits<double>::infinity();
  const CollisionModel collision(model);
  Eigen::VectorXd previous = u0;
  for (const TrajectoryStep& s : steps) {
    for (int k = 0; k < model.num_bases(); ++k) {
      m.travel_m += (s.controls.segment<2>(3 * k) - previous.segment<2>(3 * k)).norm();
    }
    previous = s.controls;
    const ClearanceSummary c = MinimumClearance(collision, s.state);
    if (c.any) m.min_clearance_m = std::min(m.min_clearance_m, c.min);
  }
  return m;
}

// The planned steps as trajectory rows: each waypoint's step solved exactly
// from its planned controls (a control step), the others as planned.
std::vector<TrajectoryStep> Rows(ControlProblem& problem, const std::vector<Waypoint>& waypoints,
                                 std::vector<PlannedStep>* planned, int* reached) {
  std::vector<TrajectoryStep> rows;
  *reached = 0;
  int leg = 0;
  size_t leg_first = 0;
  double previous_time = waypoints.front().time;
  for (size_t k = 0; k < planned->size(); ++k) {
    PlannedStep& step = (*planned)[k];
    problem.forward().Restore(step.s, step.u);
    TrajectoryStep row;
    if (step.waypoint) {
      row.result = problem.SolveStep(step.target);
      if (!row.result.reached) problem.forward().Restore(step.s, step.u);
    } else if (!(step.energy < problem.forward().options().assembly_tolerance)) {
      // Assembled exactly where the plan left it nearly so: a control step
      // to the end-effector pose it has.
      const ControlStepResult polished = problem.SolveStep(problem.CurrentPose());
      if (!polished.assembled) problem.forward().Restore(step.s, step.u);
      row.result = polished;
    } else {
      row.result.assembled = true;
      row.result.residual_energy = step.energy;
    }
    if (!step.waypoint) row.result.reached = row.result.assembled;
    step.u = problem.controls();
    step.s = problem.forward().state();
    row.target = step.target;
    row.controls = step.u;
    row.state = step.s;
    row.reached = problem.forward().end_effector();
    row.leg = leg;
    if (!step.waypoint) {
      const Eigen::Vector3d dp = row.reached.position - step.target.position;
      row.result.error = dp.lpNorm<Eigen::Infinity>();
    }
    rows.push_back(row);
    if (step.waypoint) {
      const double t = waypoints[static_cast<size_t>(leg)].time;
      const size_t n = rows.size() - leg_first;
      for (size_t i = leg_first; i < rows.size(); ++i) {
        rows[i].time = previous_time + (t - previous_time) * double(i - leg_first + 1) / double(n);
      }
      if (row.result.reached && *reached == leg) ++*reached;
      previous_time = t;
      leg_first = rows.size();
      ++leg;
    }
  }
  return rows;
}

// The wall clock of one plan and its progress reports.
class PlanClock {
 public:
  explicit PlanClock(const PlanOptions& options)
      : options_(options), start_(std::chrono::steady_clock::now()) {}
  double Elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  bool TimeLeft() const { return Elapsed() < options_.max_seconds; }
  void Report(const std::string& phase, int done, int total) const {
    if (options_.on_progress) options_.on_progress(PlanProgress{phase, done, total, Elapsed()});
  }

 private:
  const PlanOptions& options_;
  const std::chrono::steady_clock::time_point start_;
};

// Waypoints reached in order: legs whose last row reached its waypoint.
int ReachedWaypoints(const std::vector<TrajectoryStep>& rows) {
  int reached = 0;
  for (size_t k = 0; k < rows.size(); ++k) {
    const bool ends_leg = k + 1 == rows.size() || rows[k + 1].leg != rows[k].leg;
    if (ends_leg && rows[k].result.reached && rows[k].leg == reached) ++reached;
  }
  return reached;
}

void CheckPlanInputs(const ControlProblem& problem, const PlanOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("plan options: " + why);
  if (problem.options().method != ControlMethod::kLevenbergMarquardt) {
    throw std::invalid_argument("plan: the whole-path optimisation uses the lm method");
  }
  for (const MobileBase& base : problem.forward().model().mobile_bases) {
    if (base.type == BaseType::kDifferential) {
      throw std::invalid_argument(
          "plan: differential bases (their arcs tie neighbouring steps) are not planned yet");
    }
  }
}

// Chooses between the finished plan (`rows`) and the greedy walk.
void Choose(const Model& model, std::vector<TrajectoryStep> rows,
            std::vector<TrajectoryStep> greedy, PlanResult* result) {
  const double margin = model.collision.margin;
  const bool close =
      !(result->plan.min_clearance_m >= std::min(result->greedy.min_clearance_m, margin) - 1e-9);
  const bool more = result->plan.reached_waypoints > result->greedy.reached_waypoints;
  const bool as_many = result->plan.reached_waypoints == result->greedy.reached_waypoints;
  const bool safe = !result->shortfall.any && !close;
  result->used_plan =
      safe && (more || (as_many && result->plan.travel_m <= result->greedy.travel_m + 1e-9));
  if (result->used_plan) {
    result->steps = std::move(rows);
    return;
  }
  result->note = result->shortfall.any ? DescribeShortfall(result->shortfall, margin)
                 : close
                     ? "the plan's smallest clearance " + FormatG(result->plan.min_clearance_m) +
                           " m is below the greedy walk's " +
                           FormatG(result->greedy.min_clearance_m) + " m"
                 : result->plan.reached_waypoints < result->greedy.reached_waypoints
                     ? "the plan reached fewer waypoints"
                     : "the plan travelled further";
  result->steps = std::move(greedy);
}

}  // namespace

namespace {

// IsValid with the message naming max_iterations and max_seconds as `ccma
// plan` and Python's plan() do: plan_iterations, plan_time_s.
bool IsValidAsPlanCommand(const PlanOptions& options, std::string* why) {
  std::string message;
  if (options.IsValid(&message)) return true;
  if (why != nullptr) *why = RenameLeadingWord(message, {{"max_iterations", "plan_iterations"}, {"max_seconds", "plan_time_s"}});
  return false;
}

}  // namespace

bool PlanOptionsFromSettings(const PlanCommandSettings& settings, PlanOptions* options, std::string* why) {
  options->path_weight = settings.path_weight;
  options->smoothness_weight = settings.smoothness_weight;
  options->travel_weight = settings.travel_weight;
  options->max_iterations = settings.plan_iterations;
  options->max_seconds = settings.plan_time_s;
  return IsValidAsPlanCommand(*options, why);
}

bool PlanOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& text) {
    if (why != nullptr) *why = text;
    return false;
  };
  if (!(waypoint_weight > 0 && waypoint_weight <= 1e6)) return fail("waypoint_weight must lie in (0, 1e6]");
  if (!InRange(path_weight, 0, 1e6)) return fail("path_weight must lie in [0, 1e6]");
  if (!InRange(smoothness_weight, 0, 1e6)) return fail("smoothness_weight must lie in [0, 1e6]");
  if (!InRange(travel_weight, 0, 1e6)) return fail("travel_weight must lie in [0, 1e6]");
  if (max_iterations < 1 || max_iterations > 10000) return fail("max_iterations must lie in [1, 10000]");
  if (!InRange(max_seconds, 0, 1e6)) return fail("max_seconds must lie in [0, 1e6]");
  return true;
}

PlanResult PlanTrajectory(ControlProblem& problem, const std::vector<Waypoint>& waypoints, const PlanOptions& options) {
  CheckPlanInputs(problem, options);
  const PlanClock clock(options);
  const Model& model = problem.forward().model();
  PlanResult result;
  if (waypoints.empty()) return result;
  const Eigen::VectorXd u0 = problem.controls();
  const State s0 = problem.forward().state();
  const PoseTarget start_pose = problem.CurrentPose();
  // The greedy trajectory: the start, and what the plan must not be worse than.
  std::vector<TrajectoryStep> greedy;
  const TrajectoryResult walked = FollowWaypoints(problem, waypoints, [&](const TrajectoryStep& s) {
    greedy.push_back(s);
    clock.Report("greedy walk", s.leg + 1, static_cast<int>(waypoints.size()));
  });
  result.greedy = Measure(model, u0, greedy, walked.reached_waypoints);
  result.greedy_warning = walked.warning;
  // Where the greedy walk stalls, the plan starts from a detour (detour_seeds.h).
  SeededWalk seed{{waypoints, std::vector<bool>(waypoints.size(), true)}, walked, greedy, result.greedy.travel_m};
  const auto after_walk = [&](int done, int total) {
    clock.Report("detour seeds", done, total);
    return clock.TimeLeft();
  };
  if (!walked.converged && model.collision.enabled)
    seed = WalkWithDetours(problem, waypoints, u0, s0, 4, after_walk);
  std::vector<PlannedStep> planned =
      StartingSteps(problem, seed.path, seed.steps, seed.result.reached_waypoints, u0, s0, start_pose);
  const long unknowns = static_cast<long>(planned.size()) * static_cast<long>(problem.effective_controls().size());
  if (unknowns > kMaxPlanUnknowns) {
    throw std::invalid_argument("plan: " + std::to_string(planned.size()) + " steps of " +
                                std::to_string(problem.effective_controls().size()) + " controls exceed " +
                                std::to_string(kMaxPlanUnknowns) + " unknowns; use fewer or longer steps (--max_step_m)");
  }
  const auto after_iteration = [&](int done) {
    clock.Report("optimisation", done, options.max_iterations);
    return clock.TimeLeft();
  };
  result.iterations = TrajectoryPlanner(&problem, options)
                          .Optimize(u0, s0, &planned, after_iteration, &result.stopped_by);
  int reached = 0;
  std::vector<TrajectoryStep> rows = Rows(problem, waypoints, &planned, &reached);
  result.shortfall = FinishPlan(
      problem, u0, s0, waypoints.front().time, &rows, &result.inserted_rows, &result.repaired_rows,
      [&](int done, int total) { clock.Report("finishing", done, total); });
  result.plan = Measure(model, u0, rows, ReachedWaypoints(rows));
  Choose(model, std::move(rows), std::move(greedy), &result);
  const TrajectoryStep* last = result.steps.empty() ? nullptr : &result.steps.back();
  if (last != nullptr) problem.forward().Restore(last->state, last->controls);
  const int reached_final = result.used_plan ? result.plan.reached_waypoints : result.greedy.reached_waypoints;
  result.converged = reached_final == static_cast<int>(waypoints.size());
  result.solve_time_ms = 1e3 * clock.Elapsed();
  return result;
}

}  // namespace ccma
