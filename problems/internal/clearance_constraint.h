// Clearance (model_format.md, "Collision geometry and obstacles"): every
// checked pair of shapes keeps its clearance d >= collision.margin. An
// inequality, like a joint limit: a pair in the active set is held at its
// floor, d(u + delta) = floor, linearised through dd/du = dd/ds ds/du
// (collision/clearance.h); the LM loop adds a pair when a step would push it
// below (WouldCross). A pair already below the margin when the step begins
// keeps its clearance then as its floor: a step never makes it worse.
//
// Items are pairs of shapes, numbered as the step meets them.
#ifndef CCMA_PROBLEMS_INTERNAL_CLEARANCE_CONSTRAINT_H_
#define CCMA_PROBLEMS_INTERNAL_CLEARANCE_CONSTRAINT_H_

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ccma/model.h"
#include "collision/clearance.h"
#include "collision/collision_model.h"
#include "problems/internal/step_constraint.h"

namespace ccma {

class ClearanceConstraint final : public StepConstraint {
 public:
  explicit ClearanceConstraint(const Model& model);

  // Bounds the active-set passes: one per shape.
  int num_items() const override { return collision_.num_shapes(); }
  // Records the floors of the pairs below the margin at (u0, s0).
  void Begin(const Eigen::VectorXd& u0, const State& s0) override;
  // Largest amount [m] by which a pair's clearance is below its floor.
  double MaxViolation(const Eigen::VectorXd& u, const State& s) const override;
  double trial_slack() const override { return 1e-6; }
  int NumRows(const std::vector<int>& active) const override { return static_cast<int>(active.size()); }
  // d(u + delta) = floor for each active pair.
  void AppendRows(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du,
                  const std::vector<int>& active, int first_row, LinearConstraints* rows) const override;
  std::vector<int> WouldCross(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du, const Eigen::VectorXd& d,
                              double tolerance) const override;
  std::vector<int> AtOrBeyond(const Eigen::VectorXd& u, const State& s, double tolerance) const override;
  // d + a delta >= floor for the pairs within `watch` of their floor.
  void AppendInequalities(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du, double watch,
                          std::vector<InequalityRow>* rows) const override;
  // Sets result->max_clearance_violation; names the active pairs at their
  // floor ("clearance between 'base0' and 'pillar' at its margin 0.05 m").
  std::string Report(const Eigen::VectorXd& u, const State& s, const std::vector<int>& active,
                     ControlStepResult* result) const override;

 private:
  // The item number of a pair (a new one the first time it is met).
  int ItemOf(int a, int b) const;
  // dd/du (effective controls) of one pair at s.
  Eigen::RowVectorXd ControlGradient(const State& s, const PairClearance& p, const SensitivityView& ds_du) const;
  double Floor(const std::pair<int, int>& pair) const;
  // The clearances of the pairs within `threshold` at s.
  std::vector<PairClearance> Near(const State& s, double threshold) const;

  const CollisionModel collision_;
  std::map<std::pair<int, int>, double> floors_;  // pairs below the margin when the step began
  // Workspace of one step (a problem is used by one thread at a time).
  mutable std::vector<std::pair<int, int>> items_;
  mutable std::map<std::pair<int, int>, int> item_of_;
  mutable std::vector<PlacedShape> shapes_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_CLEARANCE_CONSTRAINT_H_
