#include "problems/internal/base_control_limit_constraint.h"

#include <algorithm>
#include <cmath>

#include "ccma/internal/format.h"

namespace ccma {

std::vector<LimitedBaseControl> LimitedBaseControls(const Model& model, const std::vector<int>& column_of) {
  std::vector<LimitedBaseControl> out;
  for (int k = 0; k < model.num_bases(); ++k) {
    const MobileBase& base = model.mobile_bases[static_cast<size_t>(k)];
    const BaseKind& kind = KindOf(base);
    const std::vector<ControlRange> limits = kind.Limits(base);
    for (int i = 0; i < kind.num_controls(); ++i) {
      const int c = model.base_control(k) + i;
      if (!limits[static_cast<size_t>(i)].limited || column_of[static_cast<size_t>(c)] < 0) continue;
      out.push_back({c, column_of[static_cast<size_t>(c)], limits[static_cast<size_t>(i)],
                     "base '" + base.name + "' " + kind.controls()[static_cast<size_t>(i)].name,
                     kind.controls()[static_cast<size_t>(i)].unit});
    }
  }
  return out;
}

double BaseControlLimitConstraint::MaxViolation(const Eigen::VectorXd& u, const State& /*s*/) const {
  double worst = 0;
  for (const LimitedBaseControl& l : limited_) worst = std::max({worst, l.range.lower - u[l.control], u[l.control] - l.range.upper});
  return worst;
}

std::vector<int> BaseControlLimitConstraint::AtOrBeyond(const Eigen::VectorXd& u, const State& /*s*/,
                                                        double tolerance) const {
  std::vector<int> out;
  for (size_t i = 0; i < limited_.size(); ++i) {
    const LimitedBaseControl& l = limited_[i];
    if (u[l.control] <= l.range.lower + tolerance || u[l.control] >= l.range.upper - tolerance) {
      out.push_back(static_cast<int>(i));
    }
  }
  return out;
}

void BaseControlLimitConstraint::AppendRows(const Eigen::VectorXd& u, const State& /*s*/,
                                            const SensitivityView& /*ds_du*/, const std::vector<int>& active,
                                            int first_row, LinearConstraints* rows) const {
  int row = first_row;
  for (int i : active) {
    const LimitedBaseControl& l = limited_[static_cast<size_t>(i)];
    const double v = u[l.control];
    const double bound = std::abs(v - l.range.lower) < std::abs(v - l.range.upper) ? l.range.lower : l.range.upper;
    rows->A(row, l.column) = 1.0;
    rows->b[row] = bound - v;
    ++row;
  }
}

void BaseControlLimitConstraint::AppendInequalities(const Eigen::VectorXd& u, const State& s,
                                                    const SensitivityView& ds_du, double watch,
                                                    std::vector<InequalityRow>* rows) const {
  for (int i : AtOrBeyond(u, s, watch)) {
    const LimitedBaseControl& l = limited_[static_cast<size_t>(i)];
    Eigen::RowVectorXd a = Eigen::RowVectorXd::Zero(ds_du.cols());
    a[l.column] = 1.0;
    const double v = u[l.control];
    if (v <= l.range.lower + watch) rows->push_back({a, l.range.lower - v});
    if (v >= l.range.upper - watch) rows->push_back({-a, v - l.range.upper});
  }
}

std::vector<int> BaseControlLimitConstraint::WouldCross(const Eigen::VectorXd& u, const State& /*s*/,
                                                        const SensitivityView& /*ds_du*/, const Eigen::VectorXd& d,
                                                        double tolerance) const {
  std::vector<int> out;
  for (size_t i = 0; i < limited_.size(); ++i) {
    const LimitedBaseControl& l = limited_[i];
    const double v = u[l.control] + d[l.column];
    if (v < l.range.lower - tolerance || v > l.range.upper + tolerance) out.push_back(static_cast<int>(i));
  }
  return out;
}

std::string BaseControlLimitConstraint::Report(const Eigen::VectorXd& u, const State& s,
                                               const std::vector<int>& active, ControlStepResult* result) const {
  result->max_limit_violation = std::max(result->max_limit_violation, std::max(0.0, MaxViolation(u, s)));
  if (AtOrBeyond(u, s, 1e-8).empty()) return "";
  std::string text;
  for (int i : active) {
    const LimitedBaseControl& l = limited_[static_cast<size_t>(i)];
    const bool upper = std::abs(u[l.control] - l.range.upper) < std::abs(u[l.control] - l.range.lower);
    text += std::string(text.empty() ? "" : ", ") + l.name + " at its " + (upper ? "upper" : "lower") + " limit " +
            FormatG(upper ? l.range.upper : l.range.lower) + " " + l.unit;
  }
  return text;
}

}  // namespace ccma
