// Limits of base controls (a legged base's `body_limits`: height, roll and
// pitch; ccma/base_kind.h BaseKind::Limits): an inequality on the controls
// themselves, held like a joint limit. A control in the active set is held at
// the bound it would cross, u_c + d_c = bound: the row is exact (linear), so
// it holds after one step.
#ifndef CCMA_PROBLEMS_INTERNAL_BASE_CONTROL_LIMIT_CONSTRAINT_H_
#define CCMA_PROBLEMS_INTERNAL_BASE_CONTROL_LIMIT_CONSTRAINT_H_

#include <string>
#include <vector>

#include "ccma/model.h"
#include "problems/internal/step_constraint.h"

namespace ccma {

// One limited base control: its index into u, its column among the
// effective controls, its range and its name ("base 'dog0' height").
struct LimitedBaseControl {
  int control = 0;
  int column = -1;
  ControlRange range;
  std::string name;
  const char* unit = "m";
};

// The limited controls of every base of `model`; column_of maps an index
// into u to its effective column (-1: not effective, then not listed).
std::vector<LimitedBaseControl> LimitedBaseControls(const Model& model, const std::vector<int>& column_of);

class BaseControlLimitConstraint final : public StepConstraint {
 public:
  explicit BaseControlLimitConstraint(std::vector<LimitedBaseControl> limited) : limited_(std::move(limited)) {}

  int num_items() const override { return static_cast<int>(limited_.size()); }
  double MaxViolation(const Eigen::VectorXd& u, const State& s) const override;
  double trial_slack() const override { return 1e-6; }
  int NumRows(const std::vector<int>& active) const override { return static_cast<int>(active.size()); }
  void AppendRows(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du,
                  const std::vector<int>& active, int first_row, LinearConstraints* rows) const override;
  std::vector<int> WouldCross(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du,
                              const Eigen::VectorXd& d, double tolerance) const override;
  std::vector<int> AtOrBeyond(const Eigen::VectorXd& u, const State& s, double tolerance) const override;
  void AppendInequalities(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du, double watch,
                          std::vector<InequalityRow>* rows) const override;
  // Sets result->max_limit_violation (the larger of it and this one's) and
  // names the active controls ("base 'dog0' height at its upper limit 0.55 m").
  std::string Report(const Eigen::VectorXd& u, const State& s, const std::vector<int>& active,
                     ControlStepResult* result) const override;

 private:
  const std::vector<LimitedBaseControl> limited_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_BASE_CONTROL_LIMIT_CONSTRAINT_H_
