// ds/du (state tangent x effective controls) as the step constraints read it
// (step_constraint.h): a dense matrix when one was formed (finite
// differences, a projection), or the factorised dG/ds of the last
// linearisation (sensitivity.h), so that a step under constraints costs a
// few solves, not one per control: S d is one solve, g S one adjoint solve.
#ifndef CCMA_PROBLEMS_INTERNAL_SENSITIVITY_VIEW_H_
#define CCMA_PROBLEMS_INTERNAL_SENSITIVITY_VIEW_H_

#include <Eigen/Core>

#include "problems/internal/sensitivity.h"

namespace ccma {

class SensitivityView {
 public:
  // A dense S (n x k); the matrix must outlive the view. Implicit, so that a
  // matrix can be passed where a view is expected.
  SensitivityView(const Eigen::MatrixXd& dense) : dense_(&dense), k_(dense.cols()) {}  // NOLINT
  // S = -(dG/ds)^-1 dG/du through `implicit` (k chosen controls), which must
  // outlive the view.
  SensitivityView(const Sensitivity& implicit, Eigen::Index k) : implicit_(&implicit), k_(k) {}

  Eigen::Index cols() const { return k_; }
  // S d (n) for a change d of the controls (k).
  Eigen::VectorXd Times(const Eigen::VectorXd& d) const {
    if (dense_ != nullptr) return *dense_ * d;
    return implicit_->StateChange(d);
  }
  // g S (k) for a row g over the state tangent (n).
  Eigen::RowVectorXd RowTimes(const Eigen::RowVectorXd& g) const {
    if (dense_ != nullptr) return g * *dense_;
    return implicit_->TotalDerivative(g.transpose(), Eigen::VectorXd::Zero(k_)).transpose();
  }

 private:
  const Eigen::MatrixXd* dense_ = nullptr;
  const Sensitivity* implicit_ = nullptr;
  Eigen::Index k_ = 0;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_SENSITIVITY_VIEW_H_
