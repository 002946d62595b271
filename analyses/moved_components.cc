#include "analyses/moved_components.h"

#include <algorithm>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>


#include "analyses/internal/sparse_mobility.h"
#include "analyses/mobility.h"
#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "analyses/internal/dense_rank.h"
#include "analyses/internal/sparse_rank.h"
#include "ccma/internal/dense_factorizations.h"

namespace ccma {
namespace {

// Y = dX/ds over an orthonormal basis of the null space of [dC/ds,
// dC/du_eff] (its state rows), as mobility.cc's EndEffectorDof; the rank
// threshold scaled by the largest singular value of dC/ds.
Eigen::MatrixXd DenseMotions(const Model& model, const State& s, const Eigen::VectorXd& u, double rank_tolerance) {
  const ConstraintSet constraints(model);
  Eigen::VectorXd C;
  Eigen::MatrixXd J_s, J_u;
  constraints.Evaluate(s, u, &C, &J_s, &J_u);
  const int n = model.state_size();
  const double threshold = rank_tolerance * std::max(1.0, LargestSingularValue(SparseMatrixCol(J_s.sparseView())));
  const std::vector<int> effective = model.effective_control_indices();
  Eigen::MatrixXd A(J_s.rows(), n + static_cast<Eigen::Index>(effective.size()));
  A.leftCols(n) = J_s;
  for (std::size_t c = 0; c < effective.size(); ++c) A.col(n + static_cast<Eigen::Index>(c)) = J_u.col(effective[c]);
  // Column-pivoting QR: hundreds of columns on an imported robot
  // (RankRevealingDecomposition; benchmarks/RESULTS.md, "Rank decisions").
  const RankRevealingDecomposition motions(A, {threshold, 0.0}, RankRevealingDecomposition::Method::kPivotedQr);
  return EndEffectorJacobian(model, s) * motions.nullSpace().topRows(n);
}

// The rank of the rows `rows` of Y, relative to Y's largest singular value.
int DenseRank(const Eigen::MatrixXd& Y, double threshold, const ComponentSet& rows) {
  Eigen::MatrixXd picked(6, Y.cols());
  int count = 0;
  for (int r = 0; r < 6; ++r) {
    if (rows[r]) picked.row(count++) = Y.row(r);
  }
  if (count == 0 || Y.cols() == 0) return 0;
  return RankAbove(JacobiSvd(picked.topRows(count)).singularValues(), threshold);
}

}  // namespace

MovedComponents AnalyzeMovedComponents(const Model& model, const State& s, const Eigen::VectorXd& u,
                                       const ComponentSet& given, double rank_tolerance) {
  const int n = model.state_size();
  if (n > kMaxMobilityStateSize) {
    throw std::invalid_argument("end-effector components: state size " + std::to_string(n) +
                                " is above the bound of " + std::to_string(kMaxMobilityStateSize));
  }
  std::function<int(const ComponentSet&)> rank_of;
  Eigen::MatrixXd Y;
  std::unique_ptr<SparseEndEffectorRanks> sparse;
  if (n <= kDenseMobilityStateSize) {
    Y = DenseMotions(model, s, u, rank_tolerance);
    const double largest = Y.cols() > 0 ? JacobiSvd(Y).singularValues()[0] : 0.0;
    const double threshold = rank_tolerance * std::max(1.0, largest);
    rank_of = [&Y, threshold](const ComponentSet& rows) { return DenseRank(Y, threshold, rows); };
  } else {
    sparse = std::make_unique<SparseEndEffectorRanks>(model, s, u, rank_tolerance);
    rank_of = [&sparse](const ComponentSet& rows) { return sparse->Rank(rows); };
  }
  MovedComponents out;
  for (int c = 0; c < 6; ++c) {
    ComponentSet with = out.chosen;
    with[c] = true;
    const int rank = rank_of(with);
    if (rank > out.rank) out.chosen = with, out.rank = rank;
  }
  out.given_rank = rank_of(given);
  return out;
}

}  // namespace ccma
