// The mobility report of analyses/mobility.h for large mechanisms: the same
// quantities from the sparse Jacobians and sparse QR
// (analyses/internal/sparse_rank.h), in time and memory that grow with the
// Jacobians' nonzeros instead of rows x columns.
#ifndef CCMA_ANALYSES_INTERNAL_SPARSE_MOBILITY_H_
#define CCMA_ANALYSES_INTERNAL_SPARSE_MOBILITY_H_

#include <array>
#include <vector>

#include <Eigen/Core>

#include "analyses/internal/sparse_rank.h"
#include "analyses/mobility.h"
#include "ccma/model.h"
#include "ccma/state.h"

namespace ccma {

// Fills every field of `report` but constraint_rows and energy (the caller's).
// Ranks are decided at rank_tolerance * max(1, largest singular value of
// dC/ds), as in the dense analysis. Free motions are split body by body as
// MobilityReport::free_motions says, with Householder rotations (a direction
// set spanning the same subspaces as the dense SVD's, not the same vectors),
// and only when state_size * dof^2 <= kMaxFreeMotionWork.
void AnalyzeMobilitySparse(const Model& model, const State& s, const Eigen::VectorXd& u, double rank_tolerance,
                           MobilityReport* report);

// Ranks of sets of rows of dX/ds (x y z roll pitch yaw) over the motions
// with the effective controls free (analyses/moved_components.h), for large
// mechanisms: rank([A; X_rows]) - rank(A), A = [dC/ds, dC/du_eff], at the
// threshold of AnalyzeMobilitySparse. One sparse QR per call.
class SparseEndEffectorRanks {
 public:
  SparseEndEffectorRanks(const Model& model, const State& s, const Eigen::VectorXd& u, double rank_tolerance);
  int Rank(const std::array<bool, 6>& rows) const;

 private:
  SparseMatrixCol A_, X_;
  double threshold_ = 0;
  int rank_A_ = 0;
};

// An orthonormal basis of the null space of [dC/ds; dX/ds] at (s, u), the
// idle motions of analyses/configuration_difference.h, for large
// mechanisms, at the threshold of AnalyzeMobilitySparse. False (basis
// untouched) when state_size * dof^2 exceeds kMaxFreeMotionWork.
bool SparseIdleMotions(const Model& model, const State& s, const Eigen::VectorXd& u, double rank_tolerance,
                       Eigen::MatrixXd* basis);

// The bodies whose components of the direction ds exceed
// kMovingBodyTolerance times its largest component, ascending.
std::vector<int> FreeMotionBodies(const Eigen::VectorXd& ds);

}  // namespace ccma

#endif  // CCMA_ANALYSES_INTERNAL_SPARSE_MOBILITY_H_
