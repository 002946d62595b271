#include "problems/internal/secondary_objective.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "problems/internal/control_workspace.h"
#include "problems/internal/pivot_ratio.h"

namespace ccma {

void SecondaryObjectiveTerms::Add(double value, const Eigen::VectorXd& row, bool with_gradient) {
  values_.push_back(value);
  if (with_gradient) rows_.push_back(row);
}

void SecondaryObjectiveTerms::AddSingularityBarrier(const PoseTarget& target, bool with_gradient) {
  // Barrier sqrt(w) (sigma_0 / sigma - 1) below sigma_0: C1 at sigma_0
  // (value and slope 0), infinite at sigma = 0.
  const ControlOptions::Secondary& sec = p_.options_.secondary;
  const int k = static_cast<int>(p_.effective_.size());
  Eigen::VectorXd g;
  const double sigma = p_.SmallestSingularValue(target, with_gradient ? &g : nullptr);
  const double sigma_0 = sec.singularity_threshold;
  if (std::isfinite(sigma) && sigma < sigma_0) {
    const double root = std::sqrt(sec.singularity_weight);
    values_.push_back(root * (sigma_0 / std::max(sigma, 1e-300) - 1));
    if (with_gradient) rows_.push_back(-root * sigma_0 / (sigma * sigma) * g);
  } else if (!std::isfinite(sigma)) {
    Add(std::numeric_limits<double>::infinity(), Eigen::VectorXd::Zero(k), with_gradient);  // never accepted
  }
}

void SecondaryObjectiveTerms::AddPivotBarrier(bool with_gradient) {
  // The same barrier on every pivot ratio of dG/ds below rho_0, not only
  // the smallest: where the smallest pivot changes index, a barrier on rho
  // alone would push up the pivot that is smallest now while another one
  // falls to zero. A non-positive ratio (an indefinite or singular Hessian:
  // the assembly is no strict minimum of E there) is never accepted.
  const ControlOptions::Secondary& sec = p_.options_.secondary;
  ControlProblem::Workspace& ws = *p_.workspace_;
  const int k = static_cast<int>(p_.effective_.size());
  const PivotRatioResult p =
      PivotRatioOfdGds(p_.forward_.constraints(), p_.forward_.state(), p_.forward_.controls(), p_.effective_,
                       with_gradient, sec.sigma_step, &ws.sigma_solver, &ws.sigma_derivatives);
  const double rho_0 = sec.pivot_threshold;
  const double root = std::sqrt(sec.pivot_weight);
  if (!p.valid || !(p.rho > 0)) {
    Add(std::numeric_limits<double>::infinity(), Eigen::VectorXd::Zero(k), with_gradient);
    return;
  }
  for (Eigen::Index i = 0; i < p.ratios.size(); ++i) {
    const double rho_i = p.ratios[i];
    if (rho_i >= rho_0) continue;
    values_.push_back(root * (rho_0 / rho_i - 1));
    if (with_gradient) rows_.push_back(-root * rho_0 / (rho_i * rho_i) * p.ratio_gradients.row(i).transpose());
  }
}

void SecondaryObjectiveTerms::AddSpread(bool with_gradient) {
  const ControlOptions::Secondary& sec = p_.options_.secondary;
  const Model& model = p_.forward_.model();
  const Eigen::VectorXd& u = p_.forward_.controls();
  const std::vector<int>& column = p_.workspace_->effective_column;
  const int k = static_cast<int>(p_.effective_.size());
  const double root = std::sqrt(sec.spread_weight);
  for (int i = 0; i < model.num_bases(); ++i) {
    for (int j = i + 1; j < model.num_bases(); ++j) {
      const int a = model.base_control(i), b = model.base_control(j);
      const Eigen::Vector2d d_ij(u[a] - u[b], u[a + 1] - u[b + 1]);
      const double distance = d_ij.norm();
      if (distance >= sec.clearance_m) continue;
      values_.push_back(root * (sec.clearance_m - distance));
      if (!with_gradient) continue;
      Eigen::VectorXd row = Eigen::VectorXd::Zero(k);
      // d|d_ij|/d(p_i) = d_ij / |d_ij| (0 for coincident bases: no direction to push).
      const Eigen::Vector2d n = distance > 0 ? Eigen::Vector2d(d_ij / distance) : Eigen::Vector2d::Zero();
      for (int c = 0; c < 2; ++c) {
        if (column[a + c] >= 0) row[column[a + c]] -= root * n[c];
        if (column[b + c] >= 0) row[column[b + c]] += root * n[c];
      }
      rows_.push_back(row);
    }
  }
}

void SecondaryObjectiveTerms::AddTravel(bool with_gradient) {
  const double root = std::sqrt(p_.options_.secondary.travel_weight);
  const Eigen::VectorXd& u = p_.forward_.controls();
  const std::vector<int>& effective = p_.effective_;
  const int k = static_cast<int>(effective.size());
  for (int c = 0; c < k; ++c) {
    values_.push_back(root * (u[effective[c]] - p_.travel_origin_[effective[c]]));
    if (with_gradient) rows_.push_back(root * Eigen::VectorXd::Unit(k, c));
  }
}

void SecondaryObjectiveTerms::Evaluate(const PoseTarget& target, Eigen::VectorXd* r2, Eigen::MatrixXd* J2) {
  const ControlOptions::Secondary& sec = p_.options_.secondary;
  const bool with_gradient = J2 != nullptr;
  values_.clear();
  rows_.clear();
  if (sec.singularity_weight > 0) AddSingularityBarrier(target, with_gradient);
  if (sec.pivot_weight > 0) AddPivotBarrier(with_gradient);
  if (sec.spread_weight > 0) AddSpread(with_gradient);
  if (sec.travel_weight > 0) AddTravel(with_gradient);
  r2->resize(static_cast<Eigen::Index>(values_.size()));
  for (size_t i = 0; i < values_.size(); ++i) (*r2)[static_cast<Eigen::Index>(i)] = values_[i];
  if (with_gradient) {
    const int k = static_cast<int>(p_.effective_.size());
    J2->resize(static_cast<Eigen::Index>(rows_.size()), k);
    for (size_t i = 0; i < rows_.size(); ++i) J2->row(static_cast<Eigen::Index>(i)) = rows_[i].transpose();
  }
}

}  // namespace ccma
