// Joint limits (model_format.md `limits`): a limited revolute or prismatic
// joint keeps its coordinate q in [lower, upper]. An inequality: a joint in
// the active set is held at the bound it would cross, q(u + d) = bound,
// linearised through dq/du = dq/ds ds/du; the LM loop adds a joint to the
// active set when a step would push it past a bound (WouldCross).
#ifndef CCMA_PROBLEMS_INTERNAL_JOINT_LIMIT_CONSTRAINT_H_
#define CCMA_PROBLEMS_INTERNAL_JOINT_LIMIT_CONSTRAINT_H_

#include <vector>

#include "ccma/model.h"
#include "problems/internal/step_constraint.h"

namespace ccma {

// q of a revolute [rad] or prismatic [m] joint at s as limits compare it
// (LimitCoordinate, q_home included), and dq/ds (a row over the state tangent).
double JointCoordinateGradient(const Model& model, const Joint& joint, const State& s, Eigen::RowVectorXd* dq_ds);

class JointLimitConstraint final : public StepConstraint {
 public:
  // `joints`: indices into model.joints of the limited joints.
  JointLimitConstraint(const Model& model, std::vector<int> joints);

  int num_items() const override { return static_cast<int>(joints_.size()); }
  // Largest distance [rad or m] of a coordinate beyond its bounds (0 if none).
  double MaxViolation(const Eigen::VectorXd& u, const State& s) const override;
  double trial_slack() const override { return 1e-6; }
  int NumRows(const std::vector<int>& active) const override { return static_cast<int>(active.size()); }
  // q(u + d) = bound for each active joint (bound: the nearer one to its
  // current q, or the one it is beyond).
  void AppendRows(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du,
                  const std::vector<int>& active, int first_row, LinearConstraints* rows) const override;
  std::vector<int> WouldCross(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du, const Eigen::VectorXd& d,
                              double tolerance) const override;
  std::vector<int> AtOrBeyond(const Eigen::VectorXd& u, const State& s, double tolerance) const override;
  // q + a d >= lower and -(q + a d) >= -upper for the bounds within `watch`.
  void AppendInequalities(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du, double watch,
                          std::vector<InequalityRow>* rows) const override;
  // Sets result->max_limit_violation; names the active joints ("joint 'leg0'
  // at its upper limit 0.1 m") while a limited joint sits at a bound.
  std::string Report(const Eigen::VectorXd& u, const State& s, const std::vector<int>& active,
                     ControlStepResult* result) const override;

 private:
  const Model& model_;
  const std::vector<int> joints_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_JOINT_LIMIT_CONSTRAINT_H_
