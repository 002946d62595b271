#include "problems/internal/step_constraints.h"

#include <algorithm>
#include <cmath>

#include "problems/internal/base_control_limit_constraint.h"
#include "problems/internal/clearance_constraint.h"
#include "problems/internal/differential_arc_constraint.h"
#include "problems/internal/effort_limit_constraint.h"
#include "problems/internal/joint_limit_constraint.h"

namespace ccma {

StepConstraints::StepConstraints(const Model& model, const std::vector<int>& effective) {
  std::vector<int> column_of(static_cast<size_t>(model.num_controls()), -1);
  for (size_t c = 0; c < effective.size(); ++c) column_of[static_cast<size_t>(effective[c])] = static_cast<int>(c);
  std::vector<int> differential, limited;
  for (int k = 0; k < model.num_bases(); ++k) {
    if (model.mobile_bases[k].type == BaseType::kDifferential) differential.push_back(k);
  }
  for (int j = 0; j < static_cast<int>(model.joints.size()); ++j) {
    if (model.joints[j].limited) limited.push_back(j);
  }
  std::vector<LimitedBaseControl> limited_controls = LimitedBaseControls(model, column_of);
  // The order of the rows: arcs, limits, clearance, efforts. A new kind: one line here.
  if (!differential.empty()) {
    constraints_.push_back(std::make_unique<DifferentialArcConstraint>(model, differential, column_of));
  }
  if (!limited.empty()) constraints_.push_back(std::make_unique<JointLimitConstraint>(model, limited));
  if (!limited_controls.empty()) {
    constraints_.push_back(std::make_unique<BaseControlLimitConstraint>(std::move(limited_controls)));
  }
  if (model.collision.enabled) constraints_.push_back(std::make_unique<ClearanceConstraint>(model));
  if (HasEffortLimits(model)) constraints_.push_back(std::make_unique<EffortLimitConstraint>(model, effective));
  for (const auto& c : constraints_) num_items_ += c->num_items();
}

void StepConstraints::Begin(const Eigen::VectorXd& u0, const State& s0) {
  for (const auto& c : constraints_) c->Begin(u0, s0);
}

bool StepConstraints::Hold(const Eigen::VectorXd& u, const State& s, double tolerance) const {
  for (const auto& c : constraints_) {
    if (!(c->MaxViolation(u, s) <= tolerance)) return false;
  }
  return true;
}

bool StepConstraints::WithinTrialSlack(const Eigen::VectorXd& u, const State& s) const {
  for (const auto& c : constraints_) {
    if (std::isfinite(c->trial_slack()) && !(c->MaxViolation(u, s) <= c->trial_slack())) return false;
  }
  return true;
}

LinearConstraints StepConstraints::Linearize(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du,
                                             const ActiveSet& active) const {
  int rows = 0;
  for (size_t c = 0; c < constraints_.size(); ++c) rows += constraints_[c]->NumRows(active[c]);
  LinearConstraints out;
  out.A.setZero(rows, ds_du.cols());
  out.b.setZero(rows);
  int row = 0;
  for (size_t c = 0; c < constraints_.size(); ++c) {
    constraints_[c]->AppendRows(u, s, ds_du, active[c], row, &out);
    row += constraints_[c]->NumRows(active[c]);
  }
  return out;
}

bool StepConstraints::Grow(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du, const Eigen::VectorXd& d,
                           ActiveSet* active) const {
  bool grew = false;
  for (size_t c = 0; c < constraints_.size(); ++c) {
    std::vector<int>& items = (*active)[c];
    for (int item : constraints_[c]->WouldCross(u, s, ds_du, d, 1e-12)) {
      if (std::find(items.begin(), items.end(), item) == items.end()) {
        items.push_back(item);
        grew = true;
      }
    }
  }
  return grew;
}

ActiveSet StepConstraints::AtOrBeyond(const Eigen::VectorXd& u, const State& s, const ActiveSet& active) const {
  ActiveSet out = NoneActive();
  for (size_t c = 0; c < constraints_.size(); ++c) {
    out[c] = constraints_[c]->AtOrBeyond(u, s, -1e-12);
    for (int item : active[c]) {
      if (std::find(out[c].begin(), out[c].end(), item) == out[c].end()) out[c].push_back(item);
    }
  }
  return out;
}

std::vector<InequalityRow> StepConstraints::Inequalities(const Eigen::VectorXd& u, const State& s,
                                                         const SensitivityView& ds_du, double watch) const {
  std::vector<InequalityRow> rows;
  for (const auto& c : constraints_) c->AppendInequalities(u, s, ds_du, watch, &rows);
  return rows;
}

bool StepConstraints::has_equalities() const {
  for (const auto& c : constraints_) {
    if (c->is_equality()) return true;
  }
  return false;
}

void StepConstraints::Report(const Eigen::VectorXd& u, const State& s, const ActiveSet& active,
                             ControlStepResult* result) const {
  std::string limited_by;
  for (size_t c = 0; c < constraints_.size(); ++c) {
    const std::string text = constraints_[c]->Report(u, s, active[c], result);
    if (!text.empty()) limited_by += (limited_by.empty() ? "" : ", ") + text;
  }
  result->limited_by = limited_by;
}

}  // namespace ccma
