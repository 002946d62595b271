// The step constraints of one model (step_constraint.h), in a fixed order
// (differential arcs, joint limits, clearance, effort limits: the order of the rows), and the
// active set of their inequalities. Used by the control problem's LM loop.
#ifndef CCMA_PROBLEMS_INTERNAL_STEP_CONSTRAINTS_H_
#define CCMA_PROBLEMS_INTERNAL_STEP_CONSTRAINTS_H_

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/model.h"
#include "ccma/state.h"
#include "problems/internal/step_constraint.h"

namespace ccma {

// Active items per constraint: active[c] lists the items of constraint c
// held at a bound.
using ActiveSet = std::vector<std::vector<int>>;

class StepConstraints {
 public:
  // Every kind that applies to `model` (effective: its effective controls).
  StepConstraints(const Model& model, const std::vector<int>& effective);

  // Whether there is anything to constrain.
  bool empty() const { return constraints_.empty(); }
  // An empty active set of the right shape.
  ActiveSet NoneActive() const { return ActiveSet(constraints_.size()); }
  // The step starts at controls u0 and state s0 (the previous row of a path).
  void Begin(const Eigen::VectorXd& u0, const State& s0);

  // Whether every constraint holds to `tolerance` at (u, s).
  bool Hold(const Eigen::VectorXd& u, const State& s, double tolerance) const;
  // Whether every constraint that checks trial steps is within its slack.
  bool WithinTrialSlack(const Eigen::VectorXd& u, const State& s) const;

  // All rows at (u, s): each constraint's, in order, for its active items.
  LinearConstraints Linearize(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du,
                              const ActiveSet& active) const;
  // Adds to `active` the items that the change d from (u, s) would push past a bound
  // (tolerance 1e-12); returns whether it grew.
  bool Grow(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du, const Eigen::VectorXd& d, ActiveSet* active) const;
  // The items at or beyond a bound at (u, s) (tolerance 1e-12 beyond), then
  // those of `active` not among them: what a projection must hold.
  ActiveSet AtOrBeyond(const Eigen::VectorXd& u, const State& s, const ActiveSet& active) const;
  // Every inequality's one-sided rows within `watch` of a bound at (u, s).
  std::vector<InequalityRow> Inequalities(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du,
                                          double watch) const;
  // Whether some constraint holds equalities in every step (differential arcs).
  bool has_equalities() const;

  // Upper bound on the active-set passes of one LM step.
  int max_passes() const { return num_items_; }

  // Writes every constraint's measure into `result` and sets
  // result->limited_by (the active items that hold the step back).
  void Report(const Eigen::VectorXd& u, const State& s, const ActiveSet& active, ControlStepResult* result) const;

 private:
  std::vector<std::unique_ptr<StepConstraint>> constraints_;
  int num_items_ = 0;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_STEP_CONSTRAINTS_H_
