// Static equilibrium of an assembled mechanism (cli.md, `ccma statics`):
// the joint reactions and the effort of every control under gravity on every
// mass (model_format.md, "Masses and loads"), the payload and an external
// wrench on the end-effector body.
//
// Method. The loads are a generalized force Q over the state tangent (per
// body [M; F]: moment about the body's origin and force, world frame, the
// work conjugates of (dphi, dp), state.h). Equilibrium is Q + J_s^T lambda = 0
// with J_s = dC/ds of every constraint row: lambda is its least-squares,
// minimum-norm solution, unique when the rows are independent
// (`determinate`). Where J_s has full column rank it comes from the sparse
// normal equations with a refinement step, elsewhere from a complete
// orthogonal decomposition (problems/internal/constraint_factorization.h),
// by the same operations in statics, EffortEvaluator and inverse dynamics. A joint's reaction on a body is
// its rows' J_s^T lambda on that body; a control's effort is
// -(dC/du)^T lambda, which obeys virtual work: effort . du = -Q . ds along
// every motion that keeps the constraints (J_s ds + J_u du = 0). Analytic:
// the Jacobians of the cost functions, no finite differences.
//
// A compliant model (any `stiffness` key, analyses/compliance.h) is solved
// as such: the reactions and efforts are the compliant mechanism's (its
// springs share the loads, which makes them unique wherever the springs
// remove the indeterminacy), with the springs' forces in the reactions of
// compliant joints, and `compliance` holds its deflection and compliance.
//
// Units: N, N*m, m, kg.
#ifndef CCMA_ANALYSES_STATICS_H_
#define CCMA_ANALYSES_STATICS_H_

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analyses/compliance.h"
#include "ccma/limits.h"
#include "ccma/loads.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// What body between[0] exerts on body between[1] through a joint (its motor
// included), world frame, the moment about the joint's current point.
struct JointReaction {
  std::string name;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // m
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // N
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // N*m
};


// The generalized force a control must supply: N along a base's x or y,
// N*m about its heading; a legged base's wrench on the chain (N, N*m); N*m
// or N at an actuated joint.
struct ActuatorEffort {
  std::string name;  // the base's or the joint's
  // "base_x", "base_y", "base_theta" (wheeled bases), "base_force_x" ...
  // "base_moment_z" (legged bases: BaseKind::Efforts), or "joint".
  std::string kind = "joint";
  double effort = 0;
};

struct StaticsReport {
  std::vector<JointReaction> joints;      // every joint, file order
  std::vector<ActuatorEffort> actuators;  // every control, control order (model.h)
  // The generalized effort of every control, control order (N for a control
  // in m, N*m for one in rad): what `actuators` reports, except that a legged
  // base's entries there are its body's wrench (BaseKind::Efforts).
  Eigen::VectorXd control_efforts;
  bool determinate = true;   // the reactions and efforts are unique (else the minimum-norm ones)
  double residual = 0;       // max |Q + J_s^T lambda| [N or N*m]: loads the joints cannot hold
  bool balanced = true;      // residual within rounding of the loads
  bool limits_given = false;  // some effort_limits or push_limit
  bool within_limits = true;
  std::vector<std::string> limiting;  // actuators beyond their limits
  bool compliant = false;     // the model has stiffness: the compliant mechanism's reactions
  ComplianceReport compliance;  // when compliant
};

// Whether the model gives anything statics weighs or limits: a mass, a
// payload, effort limits or a push limit.
bool HasLoads(const Model& model);

// Statics at (s, u). Throws std::invalid_argument when the constraint
// Jacobian would exceed kMaxStaticsEntries doubles.
StaticsReport ComputeStatics(const Model& model, const State& s, const Eigen::VectorXd& u,
                             const ExternalWrench& wrench = {});

class ConstraintSet;  // internal (ccma/internal/constraint_set.h)
class ConstraintFactorization;  // internal (problems/internal/constraint_factorization.h)
class HessianSolver;            // internal (problems/internal/hessian_solver.h)

// The efforts alone, at many configurations of one model: control_efforts,
// actuators, residual and the limits (no joint reactions, no compliance
// report, no determinacy), the same numbers as ComputeStatics', with the
// model's constraint set built once: a trajectory's effort columns.
class EffortEvaluator {
 public:
  explicit EffortEvaluator(const Model& model);  // keeps a reference to `model`
  ~EffortEvaluator();
  StaticsReport At(const State& s, const Eigen::VectorXd& u, const ExternalWrench& wrench = {}) const;
  // The same under any generalized loads Q (s.tangent_size(), loads.h's
  // layout): At is AtLoads(s, u, GeneralizedLoads(model, s, wrench)), and
  // inverse dynamics adds the inertial loads (analyses/dynamics.h), so that
  // at rest the two give the same numbers by the same operations.
  StaticsReport AtLoads(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& Q) const;
  // The control efforts (num_controls x k) under each of the k columns of
  // `loads`, through one factorisation: efforts are linear in the loads,
  // so retime's efforts a s'' + b s'^2 + c come from three columns
  // (analyses/retime.h). Column j equals AtLoads(s, u, loads.col(j)).
  Eigen::MatrixXd EffortsUnder(const State& s, const Eigen::VectorXd& u, const Eigen::MatrixXd& loads) const;
  // Both with the constraints at (s, u) already factorised (inverse dynamics
  // shares the factorisation with the motion, problems/internal/
  // control_motion.h): the same numbers by the same operations. A compliant
  // model ignores it.
  StaticsReport AtLoads(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& Q,
                        const ConstraintFactorization& factored) const;
  Eigen::MatrixXd EffortsUnder(const State& s, const Eigen::VectorXd& u, const Eigen::MatrixXd& loads,
                               const ConstraintFactorization& factored) const;

 private:
  StaticsReport Solve(const State& s, const Eigen::VectorXd& u, const Eigen::VectorXd& Q,
                      const ConstraintFactorization* factored) const;
  Eigen::MatrixXd SolveMany(const State& s, const Eigen::VectorXd& u, const Eigen::MatrixXd& loads,
                            const ConstraintFactorization* factored) const;
  const Model& model_;
  std::unique_ptr<const ConstraintSet> set_;
  std::unique_ptr<const HessianSolver> symbolic_;  // of set_
};

}  // namespace ccma

#endif  // CCMA_ANALYSES_STATICS_H_
