// Differential (non-holonomic) bases: every control step of such a base is
// one circular arc, so its lateral displacement from the step's start
// controls u0,
//   l(u) = -sin(theta_mid) dx + cos(theta_mid) dy,
// (theta_mid: the mean of the start and end headings, the short way) is held
// at zero: one equality row per differential base, in every step.
#ifndef CCMA_PROBLEMS_INTERNAL_DIFFERENTIAL_ARC_CONSTRAINT_H_
#define CCMA_PROBLEMS_INTERNAL_DIFFERENTIAL_ARC_CONSTRAINT_H_

#include <vector>

#include "ccma/model.h"
#include "problems/internal/step_constraint.h"

namespace ccma {

class DifferentialArcConstraint final : public StepConstraint {
 public:
  // `bases`: indices of the differential bases; column_of: control index ->
  // column among the effective controls, or -1.
  DifferentialArcConstraint(const Model& model, std::vector<int> bases, std::vector<int> column_of);

  int num_items() const override { return static_cast<int>(bases_.size()); }
  bool is_equality() const override { return true; }
  void Begin(const Eigen::VectorXd& u0, const State& /*s0*/) override { u0_ = u0; }
  // Largest |l(u)| over the bases [m].
  double MaxViolation(const Eigen::VectorXd& u, const State& s) const override;
  int NumRows(const std::vector<int>& /*active*/) const override { return num_items(); }
  void AppendRows(const Eigen::VectorXd& u, const State& s, const SensitivityView& ds_du,
                  const std::vector<int>& active, int first_row, LinearConstraints* rows) const override;
  // Sets result->max_lateral_displacement.
  std::string Report(const Eigen::VectorXd& u, const State& s, const std::vector<int>& active,
                     ControlStepResult* result) const override;

 private:
  // l(u) of one base [m] and, if asked, dl/d(x, y, theta).
  // first: the index into u of the base's x.
  double Lateral(const Eigen::VectorXd& u, int first, Eigen::Vector3d* gradient) const;

  const std::vector<int> bases_;  // the index into u of each base's x
  const std::vector<int> column_of_;
  Eigen::VectorXd u0_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_DIFFERENTIAL_ARC_CONSTRAINT_H_
