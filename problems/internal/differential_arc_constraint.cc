#include "problems/internal/differential_arc_constraint.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "ccma/rotation.h"

namespace ccma {
namespace {

std::vector<int> FirstControlsOf(const Model& model, std::vector<int> bases) {
  for (int& k : bases) k = model.base_control(k);
  return bases;
}

}  // namespace

DifferentialArcConstraint::DifferentialArcConstraint(const Model& model, std::vector<int> bases,
                                                     std::vector<int> column_of)
    : bases_(FirstControlsOf(model, std::move(bases))), column_of_(std::move(column_of)), u0_(model.home_controls()) {}

double DifferentialArcConstraint::Lateral(const Eigen::VectorXd& u, int first, Eigen::Vector3d* gradient) const {
  const int i = first;
  const double dx = u[i] - u0_[i], dy = u[i + 1] - u0_[i + 1];
  const double mid = u0_[i + 2] + 0.5 * WrapAngle(u[i + 2] - u0_[i + 2]);
  const double s = std::sin(mid), c = std::cos(mid);
  if (gradient != nullptr) *gradient << -s, c, 0.5 * (-c * dx - s * dy);
  return -s * dx + c * dy;
}

double DifferentialArcConstraint::MaxViolation(const Eigen::VectorXd& u, const State& /*s*/) const {
  double worst = 0;
  for (int k : bases_) worst = std::max(worst, std::abs(Lateral(u, k, nullptr)));
  return worst;
}

void DifferentialArcConstraint::AppendRows(const Eigen::VectorXd& u, const State& /*s*/,
                                           const SensitivityView& /*ds_du*/, const std::vector<int>& /*active*/,
                                           int first_row, LinearConstraints* rows) const {
  int row = first_row;
  for (int base : bases_) {
    Eigen::Vector3d gradient;
    rows->b[row] = -Lateral(u, base, &gradient);
    for (int c = 0; c < 3; ++c) {
      const int column = column_of_[static_cast<size_t>(base + c)];
      if (column >= 0) rows->A(row, column) = gradient[c];
    }
    ++row;
  }
}

std::string DifferentialArcConstraint::Report(const Eigen::VectorXd& u, const State& s,
                                              const std::vector<int>& /*active*/, ControlStepResult* result) const {
  result->max_lateral_displacement = MaxViolation(u, s);
  return "";
}

}  // namespace ccma
