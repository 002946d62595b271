// The linearised whole-trajectory plan (problems/plan.h) over the changes d
// of every step's effective controls, stacked d = [d_1; ...; d_N]:
//   min 1/2 d^T (H + mu I) d + g^T d   subject to   a . d_k >= b
// for every one-sided row of every step (clearance, joint limits). H is
// sparse (block diagonal plus the smoothness coupling of neighbouring
// steps); the rows are held by an active set: solve with the active rows as
// equalities (a sparse KKT system, Eigen's SparseLU), add the rows the
// solution violates, repeat.
#ifndef CCMA_PROBLEMS_INTERNAL_PLAN_SYSTEM_H_
#define CCMA_PROBLEMS_INTERNAL_PLAN_SYSTEM_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "problems/internal/step_constraint.h"

namespace ccma {

struct PlanRow {
  int step = 0;  // block of d (0-based: d_1 is block 0)
  InequalityRow row;
};

struct PlanSystem {
  int controls = 0;  // effective controls per step (block size)
  int steps = 0;
  Eigen::SparseMatrix<double> H;  // (steps * controls)^2, symmetric
  Eigen::VectorXd g;
  std::vector<PlanRow> rows;
};

// The step d (steps * controls) within the box |d_i| <= max_change (a
// trust region, held by the same active set). Returns false when the KKT
// system cannot be factorised or the active set does not settle within
// `max_passes`.
bool SolvePlanSystem(const PlanSystem& system, double mu, double max_change, int max_passes, Eigen::VectorXd* d);

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_PLAN_SYSTEM_H_
