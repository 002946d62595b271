// The linear equality constraints a control step solves under (control
// problem, LM outer loop), over the effective controls:
//  * differential bases: every step is one circular arc, i.e. the lateral
//    displacement -sin(theta_mid) dx + cos(theta_mid) dy of each such base,
//    from the step's start controls, is zero (theta_mid: mean heading, short way);
//  * joint limits, active set: a limited joint whose coordinate would leave
//    [lower, upper] is held at the bound it would cross, q(u + d) = bound,
//    linearised through dq/du = dq/ds ds/du.
// Both are nonlinear in u; each LM iteration linearises them at the current
// controls, so they converge quadratically with the iterations (Newton).
#ifndef CCMA_PROBLEMS_INTERNAL_STEP_CONSTRAINTS_H_
#define CCMA_PROBLEMS_INTERNAL_STEP_CONSTRAINTS_H_

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// dq/ds of a revolute or prismatic joint (a row over the state tangent) and q.
double JointCoordinateGradient(const Model& model, const Joint& joint, const State& s, Eigen::RowVectorXd* dq_ds);

struct LinearConstraints {
  Eigen::MatrixXd A;  // c x k (effective controls)
  Eigen::VectorXd b;  // c
  int rows() const { return static_cast<int>(b.size()); }
};

class StepConstraints {
 public:
  StepConstraints(const Model& model, const std::vector<int>& effective);

  // Whether there is anything to constrain (differential bases or limits).
  bool empty() const { return differential_.empty() && limited_.empty(); }
  // The step starts at controls u0 (the previous row of a path).
  void Begin(const Eigen::VectorXd& u0);

  // Largest lateral displacement [m] of a differential base between u0 and u.
  double MaxLateral(const Eigen::VectorXd& u) const;
  // Largest violation [rad or m] of a joint limit at state s (0 if none).
  double MaxLimitViolation(const State& s) const;
  // Joints (indices into Model::joints) whose q at s is beyond a bound by
  // more than `tolerance`, or within it of a bound.
  std::vector<int> JointsAtOrBeyond(const State& s, double tolerance) const;

  // The linearised rows at (u, s): lateral rows of every differential base,
  // then q(u + d) = bound for each joint in `active` (bound: the nearer one
  // to its current q, or the one it is beyond). ds_du: state tangent x k.
  LinearConstraints Linearize(const Eigen::VectorXd& u, const State& s, const Eigen::MatrixXd& ds_du,
                              const std::vector<int>& active) const;

  // Predicted q after a control change d (first order), for every limited
  // joint; used to find joints that a step would push past a bound.
  std::vector<int> WouldCross(const State& s, const Eigen::MatrixXd& ds_du, const Eigen::VectorXd& d,
                              double tolerance) const;

  // "joint 'leg0' at its upper limit 0.1" for the joints in `active`.
  std::string Describe(const State& s, const std::vector<int>& active) const;

 private:
  double Lateral(const Eigen::VectorXd& u, int base, Eigen::Vector3d* gradient) const;

  const Model& model_;
  std::vector<int> column_of_;     // u index -> column in the effective controls, or -1
  std::vector<int> differential_;  // base indices
  std::vector<int> limited_;       // joint indices
  Eigen::VectorXd u0_;
};

// The damped least-squares step of LM under linear equality constraints:
//   min |J d + r|^2 + mu |d|^2   subject to   A d = b
// given J^T J (k x k) and J^T r (k), through the null space of A (SVD,
// rank-revealing): d = d0 + N z with d0 the least-norm solution of A d = b; z
// by the same least-norm eigen-solve as the unconstrained step. With no
// constraint rows it is the unconstrained step, -V (Lambda + mu)^-1 V^T J^T r
// with J^T J = V Lambda V^T; pass that decomposition (`JtJ_eigen`) to reuse
// it across damping trials.
// Above this many controls the unconstrained step uses an LDLT instead of
// the eigen-decomposition (see ConstrainedLmStep).
constexpr int kMaxEigenSolveSize = 64;

Eigen::VectorXd ConstrainedLmStep(const Eigen::MatrixXd& JtJ, const Eigen::VectorXd& Jtr, double mu,
                                  const LinearConstraints& constraints,
                                  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>* JtJ_eigen = nullptr);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_STEP_CONSTRAINTS_H_
