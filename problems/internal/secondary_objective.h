// The secondary objective of redundancy resolution (ControlOptions::Secondary)
//   Phi(u) = 1/2 |r2(u)|^2
// as residual rows r2 and their gradient rows dr2/du over the effective
// controls, one kind of term per function: barriers on sigma (the smallest
// singular value of dX_c/du) and on the pivot ratios of dG/ds, base spread
// and base travel. Minimised in the null space of the task by
// null_space_step.h.
#ifndef CCMA_PROBLEMS_INTERNAL_SECONDARY_OBJECTIVE_H_
#define CCMA_PROBLEMS_INTERNAL_SECONDARY_OBJECTIVE_H_

#include <vector>

#include <Eigen/Core>

#include "problems/control_problem.h"

namespace ccma {

class SecondaryObjectiveTerms {
 public:
  // Reads the current solution of `problem` (not changed).
  explicit SecondaryObjectiveTerms(ControlProblem* problem) : p_(*problem) {}

  // r2 and, if J2 is not null, dr2/du_eff (rows x k) at the current solution.
  // A singular dG/ds (or a non-positive pivot) gives an infinite row.
  void Evaluate(const PoseTarget& target, Eigen::VectorXd* r2, Eigen::MatrixXd* J2);

 private:
  // sqrt(w) (sigma_0 / sigma - 1) below sigma_0.
  void AddSingularityBarrier(const PoseTarget& target, bool with_gradient);
  // sqrt(w) (rho_0 / rho_i - 1) for every pivot ratio rho_i below rho_0.
  void AddPivotBarrier(bool with_gradient);
  // sqrt(w) (c - d_ij) for every pair of bases closer than c.
  void AddSpread(bool with_gradient);
  // sqrt(w) (u_eff - u_eff_start).
  void AddTravel(bool with_gradient);
  void Add(double value, const Eigen::VectorXd& row, bool with_gradient);

  ControlProblem& p_;
  std::vector<double> values_;
  std::vector<Eigen::VectorXd> rows_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_SECONDARY_OBJECTIVE_H_
