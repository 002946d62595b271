// The Gauss-Newton model of the control residual r(u) = [e; sqrt(lambda) C]
// at the current solution (ControlProblem::Linearize), shared by the parts
// of a control step: the LM loop, the null-space step, the differential
// turning and the BFGS loop's final report.
#ifndef CCMA_PROBLEMS_INTERNAL_CONTROL_LINEARIZATION_H_
#define CCMA_PROBLEMS_INTERNAL_CONTROL_LINEARIZATION_H_

#include <functional>
#include <memory>

#include <Eigen/Core>

#include "ccma/internal/dense_factorizations.h"

namespace ccma {

class Sensitivity;    // sensitivity.h
class LargeLmSystem;  // large_lm_system.h

struct ControlLinearization {
  Eigen::VectorXd r;      // [e; sqrt(lambda) C] (ne + m)
  Eigen::MatrixXd ds_du;  // n x k, or empty when not formed (sparse products)
  // The factorised dG/ds of this linearisation (implicit ds/du for the step
  // constraints, sensitivity_view.h); valid until the next one.
  std::shared_ptr<const Sensitivity> sensitivity;
  Eigen::MatrixXd J_e;    // de/du_eff (ne x k): the end-effector rows of dr/du
  Eigen::VectorXd Jtr;    // (dr/du)^T r (k)
  // Many controls (k >= kMinLargeLmControls): the LM step without the dense
  // k x k matrix (large_lm_system.h); JtJ is then formed only when a reader
  // needs it (DenseJtJ: a step constraint becomes active, a secondary
  // objective, differential turning).
  std::shared_ptr<const LargeLmSystem> large;
  std::function<Eigen::MatrixXd()> form_JtJ;  // set with `large`
  // (dr/du)^T dr/du (k x k).
  const Eigen::MatrixXd& DenseJtJ() const {
    if (JtJ.size() == 0 && form_JtJ) JtJ = form_JtJ();
    return JtJ;
  }
  mutable Eigen::MatrixXd JtJ;  // as DenseJtJ; written by Linearize
  // Once per linearisation, for every trial (up to kMaxEigenSolveSize controls).
  SymmetricEigenSolver JtJ_eigen;
  bool has_eigen = false;
  const SymmetricEigenSolver* eigen() const { return has_eigen ? &JtJ_eigen : nullptr; }
  double rcond = 0;       // pivot ratio of dG/ds
  bool singular = false;  // dG/ds singular
};

// Smallest singular value of the end-effector rows of an LM Jacobian
// (dX_c/du, m or rad per control unit); 0 for an empty one.
inline double SmallestSingularValueOf(const Eigen::MatrixXd& J_end_effector) {
  if (J_end_effector.rows() == 0 || J_end_effector.cols() == 0) return 0.0;
  return JacobiSvd(J_end_effector).singularValues().minCoeff();
}

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_CONTROL_LINEARIZATION_H_
