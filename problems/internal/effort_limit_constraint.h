// Effort limits while control moves (model_format.md `effort_limits`,
// `push_limit`; statics in analyses/statics.h): under the model's own loads
// (masses, payload), an actuated joint's effort stays in [lower, upper] and
// a base's horizontal push |e_xy| at most its push_limit. An inequality like
// a joint limit (joint_limit_constraint.h): an item in the active set is held
// at the bound it would cross, e(u + d) = bound, linearised through de/du.
//
// de/du along each effective control's motion (ds_i, e_i) is the
// derivative of the adjoint Lagrangian of equilibrium.h, ds_i the
// minimum-norm state motion with J_s ds_i = -J_u e_i (= ds/du_i where the
// controls fix the mechanism; Equilibrium::StateMotion), whose remaining
// second-order part (the Jacobians' change along the motion) is a central
// difference along it: a few dense Jacobian evaluations per active item and
// control, paid only by models that give both masses and effort limits.
// Violations are measured relative to the limit (N / N), so one tolerance
// serves joints and bases; Report gives them in N.
#ifndef CCMA_PROBLEMS_INTERNAL_EFFORT_LIMIT_CONSTRAINT_H_
#define CCMA_PROBLEMS_INTERNAL_EFFORT_LIMIT_CONSTRAINT_H_

#include <string>
#include <vector>

#include "ccma/internal/constraint_set.h"
#include "ccma/model.h"
#include "problems/internal/step_constraint.h"

namespace ccma {

// Whether a model's control is held by effort limits: some limit given and
// some mass or payload to load it.
bool HasEffortLimits(const Model& model);

class EffortLimitConstraint final : public StepConstraint {
 public:
  // `effective`: the effective controls (indices into u), the columns of d.
  EffortLimitConstraint(const Model& model, std::vector<int> effective);

  int num_items() const override { return static_cast<int>(items_.size()); }
  // Largest violation beyond a limit, relative to the limit (0 if none).
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
  // Sets result->max_effort_violation [N or N*m]; names the active items
  // ("effort of 'leg0' at its upper limit 30 N", "push of 'base1' at its limit 60 N").
  std::string Report(const Eigen::VectorXd& u, const State& s, const std::vector<int>& active,
                     ControlStepResult* result) const override;

 private:
  struct Item {
    std::string name;
    bool push = false;   // a base's |e_xy| (control, control + 1), else a joint's e_control
    int control = 0;
    double lower = 0, upper = 0;  // a push: upper = push_limit
    const char* unit = " N";      // of the limits: N, or N*m for a revolute motor
  };
  // One item's value at the efforts e [N or N*m], the bound it is held at
  // (the nearer, or the one it is beyond) and the weight w with d value = w . d e.
  struct Reading {
    double value = 0, bound = 0, scale = 1;
    Eigen::VectorXd w;
  };
  Reading Read(const Item& item, const Eigen::VectorXd& e) const;
  Eigen::VectorXd Efforts(const Eigen::VectorXd& u, const State& s) const;
  // d value / d (effective control i) for every i: a row over the effective controls.
  Eigen::RowVectorXd Gradient(const Eigen::VectorXd& u, const State& s, const Reading& reading) const;
  // d value along the control change d (effective), the state following
  // by Equilibrium::StateMotion.
  double AlongChange(const Eigen::VectorXd& u, const State& s, const Reading& reading, const Eigen::VectorXd& d) const;

  const Model& model_;
  const ConstraintSet set_;
  const std::vector<int> effective_;
  std::vector<Item> items_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_EFFORT_LIMIT_CONSTRAINT_H_
