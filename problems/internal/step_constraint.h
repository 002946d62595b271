// One kind of constraint a control step is solved under (the LM outer loop,
// problems/internal/lm_loop.h): linear equalities A d = b on the change d of
// the effective controls, linearised at the current controls u and state s
// in every iteration, so that they converge quadratically with the
// iterations (Newton). Equalities (a differential base's arc) add their rows
// in every step; inequalities (a joint limit) add rows only for the items
// in the active set, which the LM loop grows with WouldCross().
//
// A new kind (clearance, effort limits, ...) is one new file implementing
// this interface plus one line in StepConstraints::ForModel
// (problems/internal/step_constraints.cc).
#ifndef CCMA_PROBLEMS_INTERNAL_STEP_CONSTRAINT_H_
#define CCMA_PROBLEMS_INTERNAL_STEP_CONSTRAINT_H_

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/state.h"
#include "problems/control_problem.h"
#include "problems/internal/sensitivity_view.h"

namespace ccma {

// One-sided rows a . d >= b over the effective controls (a plan's
// linearisation of one step, problems/internal/trajectory_planner.h).
struct InequalityRow {
  Eigen::RowVectorXd a;
  double b = 0;
};

// Rows A d = b over the effective controls.
struct LinearConstraints {
  Eigen::MatrixXd A;  // c x k (effective controls)
  Eigen::VectorXd b;  // c
  int rows() const { return static_cast<int>(b.size()); }
};

class StepConstraint {
 public:
  virtual ~StepConstraint() = default;

  // Items (bases, joints, ...) this constraint holds; bounds the active-set passes.
  virtual int num_items() const = 0;
  // The step starts at controls u0 and state s0 (the previous row of a path).
  virtual void Begin(const Eigen::VectorXd& /*u0*/, const State& /*s0*/) {}
  // Largest violation at (u, s) [m or rad]; 0 when it holds.
  virtual double MaxViolation(const Eigen::VectorXd& u, const State& s) const = 0;
  // How far a trial LM step may leave the constraint and still be accepted
  // (second-order slack, removed by the next iterations) [m or rad];
  // infinity: trials are not checked.
  virtual double trial_slack() const { return std::numeric_limits<double>::infinity(); }

  // Number of rows AppendRows() writes for `active`.
  virtual int NumRows(const std::vector<int>& active) const = 0;
  // Writes its rows at (u, s) into rows->A and rows->b from `first_row` on
  // (A is zeroed and sized by the caller): the rows held in every step, then
  // one per item of `active`. ds_du: state tangent x effective controls.
  virtual void AppendRows(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du,
                          const std::vector<int>& active, int first_row, LinearConstraints* rows) const = 0;

  // Inequalities only: items that the control change d from (u, s) would
  // push past a bound by more than `tolerance`, to first order.
  virtual std::vector<int> WouldCross(const Eigen::VectorXd& /*u*/, const State& /*s*/, const SensitivityView& /*ds_du*/,
                                      const Eigen::VectorXd& /*d*/, double /*tolerance*/) const {
    return {};
  }
  // Inequalities only: a one-sided row per bound within `watch` of the
  // items' values at (u, s) (a whole-trajectory plan holds them all at once).
  virtual void AppendInequalities(const Eigen::VectorXd& /*u*/, const State& /*s*/, const SensitivityView& /*ds_du*/,
                                  double /*watch*/, std::vector<InequalityRow>* /*rows*/) const {}
  // Whether the constraint holds equalities in every step (a plan refuses it).
  virtual bool is_equality() const { return false; }

  // Inequalities only: items beyond a bound at (u, s), or within `tolerance` of one.
  virtual std::vector<int> AtOrBeyond(const Eigen::VectorXd& /*u*/, const State& /*s*/, double /*tolerance*/) const {
    return {};
  }

  // Writes this constraint's measure into `result` (for example
  // max_limit_violation) and returns what holds the step back, naming the
  // active items ("" if nothing).
  virtual std::string Report(const Eigen::VectorXd& u, const State& s, const std::vector<int>& active,
                             ControlStepResult* result) const = 0;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_STEP_CONSTRAINT_H_
