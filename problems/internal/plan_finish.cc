#include "problems/internal/plan_finish.h"

#include <algorithm>
#include <map>
#include <utility>

#include "ccma/internal/format.h"
#include "collision/clearance.h"
#include "problems/internal/lm_loop.h"

namespace ccma {
namespace {

// A midpoint whose least-squares configuration leaves this residual energy
// [m^2] (1 mm of constraint residual) is torn: the mean controls do not
// assemble (tied controls), whatever its clearance.
constexpr double kTornEnergy = 1e-6;
// A row within this [m] of its floors is finished (the step constraints
// hold to 1e-10).
constexpr double kRowSlack = 1e-9;

// Keeps the worse of two shortfalls: a torn midpoint first, then the larger.
void Keep(const PlanShortfall& candidate, PlanShortfall* worst) {
  if (!worst->any || candidate.torn > worst->torn ||
      (candidate.torn == worst->torn && candidate.shortfall_m > worst->shortfall_m)) {
    *worst = candidate;
  }
}

// A row or the start: where an interval begins or ends.
struct PathPoint {
  Eigen::VectorXd u;
  State s;
  double time = 0;
};

class Finisher {
 public:
  explicit Finisher(ControlProblem& problem) : p_(problem), collision_(problem.forward().model()) {}

  // Worst shortfall at `s` against the floors of a step that begins at
  // `from`: the margin, or a pair's clearance at `from` when lower.
  PlanShortfall Shortfall(const State& from, const State& s) {
    PlanShortfall worst;
    if (!collision_.enabled()) return worst;
    const double margin = collision_.margin();
    std::map<std::pair<int, int>, double> floors;
    collision_.PlaceShapes(from, &shapes_);
    for (const PairClearance& p : NearClearances(collision_, shapes_, margin)) {
      if (p.distance.distance < margin) floors[{p.a, p.b}] = p.distance.distance;
    }
    collision_.PlaceShapes(s, &shapes_);
    for (const PairClearance& p : NearClearances(collision_, shapes_, margin)) {
      const auto it = floors.find({p.a, p.b});
      const double floor = it == floors.end() ? margin : it->second;
      if (floor - p.distance.distance > worst.shortfall_m) {
        worst.shortfall_m = floor - p.distance.distance;
        worst.clearance_m = p.distance.distance;
        worst.floor_m = floor;
        worst.a = collision_.Name(p.a);
        worst.b = collision_.Name(p.b);
      }
    }
    return worst;
  }

  // Re-solves `row` (reached from `from`) to `target` with its step
  // constraints begun at `from`; false (the row unchanged) if it does not
  // assemble.
  bool Restore(const PathPoint& from, const PoseTarget& target, bool waypoint, TrajectoryStep* row) {
    p_.forward().Restore(row->state, row->controls);
    ControlStepResult result = LmLoop(&p_).SolveStepFrom(target, from.u, from.s);
    if (!result.assembled) {
      p_.forward().Restore(row->state, row->controls);
      return false;
    }
    if (!waypoint) result.reached = true;
    row->result = result;
    row->controls = p_.controls();
    row->state = p_.forward().state();
    row->reached = p_.forward().end_effector();
    if (!waypoint)
      row->result.error = (row->reached.position - row->target.position).lpNorm<Eigen::Infinity>();
    return true;
  }

  // The rows to insert between `from` and `to` (in order) where the
  // midpoint falls short; the worst shortfall left into *worst.
  // `rows_before`: the rows before this interval.
  void Split(const PathPoint& from, const TrajectoryStep& to, int depth, int rows_before,
             std::vector<TrajectoryStep>* inserted, PlanShortfall* worst) {
    TrajectoryStep mid = to;
    p_.forward().SetState(from.s);
    const ForwardResult solved = p_.forward().Solve(0.5 * (from.u + to.controls));
    mid.controls = p_.controls();
    mid.state = p_.forward().state();
    mid.reached = p_.forward().end_effector();
    mid.time = 0.5 * (from.time + to.time);
    PlanShortfall shortfall = Shortfall(from.s, mid.state);
    shortfall.residual_energy = solved.residual_energy;
    shortfall.torn = !(solved.residual_energy < kTornEnergy);
    if (!shortfall.torn && shortfall.shortfall_m <= kMidpointSlack) return;
    if (depth < kMaxMidpointSplits) {
      mid.target = PoseTarget{mid.reached.position, mid.reached.rpy};
      if (Restore(from, mid.target, /*waypoint=*/false, &mid) &&
          Shortfall(from.s, mid.state).shortfall_m <= kRowSlack) {
        Split(from, mid, depth + 1, rows_before, inserted, worst);
        inserted->push_back(mid);
        Split(PathPoint{mid.controls, mid.state, mid.time}, to, depth + 1, rows_before, inserted,
              worst);
        return;
      }
    }
    shortfall.any = true;
    shortfall.midpoint = true;
    shortfall.time_s = mid.time;
    // `from` is row rows_before + inserted rows so far (1-based; 0: the start).
    shortfall.step = rows_before + static_cast<int>(inserted->size()) + 1;
    Keep(shortfall, worst);
  }

 private:
  ControlProblem& p_;
  const CollisionModel collision_;
  std::vector<PlacedShape> shapes_;
};

// Whether row k ends its leg (a waypoint's row).
bool EndsLeg(const std::vector<TrajectoryStep>& rows, size_t k) {
  return k + 1 == rows.size() || rows[k + 1].leg != rows[k].leg;
}

}  // namespace

PlanShortfall FinishPlan(ControlProblem& problem, const Eigen::VectorXd& u0, const State& s0,
                         double start_time, std::vector<TrajectoryStep>* rows, int* inserted_rows,
                         int* repaired_rows, const std::function<void(int, int)>& progress) {
  Finisher finisher(problem);
  PlanShortfall worst;
  std::vector<TrajectoryStep> out;
  out.reserve(rows->size());
  PathPoint from{u0, s0, start_time};
  *inserted_rows = 0;
  *repaired_rows = 0;
  for (size_t k = 0; k < rows->size(); ++k) {
    TrajectoryStep row = (*rows)[k];
    const bool waypoint = EndsLeg(*rows, k);
    if (finisher.Shortfall(from.s, row.state).shortfall_m > 0) {
      finisher.Restore(from,
                       waypoint ? row.target : PoseTarget{row.reached.position, row.reached.rpy},
                       waypoint, &row);
      ++*repaired_rows;
    }
    PlanShortfall left = finisher.Shortfall(from.s, row.state);
    std::vector<TrajectoryStep> inserted;
    finisher.Split(from, row, 0, static_cast<int>(out.size()), &inserted, &worst);
    *inserted_rows += static_cast<int>(inserted.size());
    for (TrajectoryStep& mid : inserted) out.push_back(std::move(mid));
    out.push_back(row);
    if (left.shortfall_m > kRowSlack) {
      left.any = true;
      left.time_s = row.time;
      left.step = static_cast<int>(out.size());
      Keep(left, &worst);
    }
    from = PathPoint{row.controls, row.state, row.time};
    if (progress) progress(static_cast<int>(k) + 1, static_cast<int>(rows->size()));
  }
  *rows = std::move(out);
  return worst;
}

std::string DescribeShortfall(const PlanShortfall& f, double margin) {
  const std::string where =
      (f.midpoint ? "half way between the plan's rows " + std::to_string(f.step - 1) + " and " +
                        std::to_string(f.step)
                  : "at the plan's row " + std::to_string(f.step)) +
      " (time " + FormatG(f.time_s) + " s)";
  if (f.torn) {
    return where + " the mechanism does not assemble (residual energy " +
           FormatG(f.residual_energy) + " m^2): the plan jumps between rows";
  }
  return where + " the clearance between " + Quote(f.a) + " and " + Quote(f.b) + " is " +
         FormatG(f.clearance_m) + " m, " + FormatG(f.shortfall_m) + " m below " +
         (f.floor_m < margin ? "its clearance at the row before, " : "the margin ") +
         FormatG(f.floor_m) + " m, and the finishing could not restore it";
}

}  // namespace ccma
