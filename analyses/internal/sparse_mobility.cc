#include "analyses/internal/sparse_mobility.h"

#include <algorithm>
#include <cmath>

#include <Eigen/QR>

#include "analyses/internal/sparse_rank.h"
#include "ccma/end_effector.h"
#include "ccma/internal/constraint_set.h"
#include "ccma/internal/dense_factorizations.h"

namespace ccma {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

void AppendTriplets(const SparseMatrixCol& A, int row, int col, Triplets* out) {
  for (int j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrixCol::InnerIterator it(A, j); it; ++it) {
      out->emplace_back(row + static_cast<int>(it.row()), col + static_cast<int>(it.col()), it.value());
    }
  }
}

// [top; bottom], both with the same number of columns.
SparseMatrixCol Stack(const SparseMatrixCol& top, const SparseMatrixCol& bottom) {
  Triplets t;
  t.reserve(static_cast<size_t>(top.nonZeros() + bottom.nonZeros()));
  AppendTriplets(top, 0, 0, &t);
  AppendTriplets(bottom, static_cast<int>(top.rows()), 0, &t);
  SparseMatrixCol out(top.rows() + bottom.rows(), top.cols());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

// The nonzeros of the dense X in the first X.cols() of `cols` columns.
SparseMatrixCol Sparse(const Eigen::MatrixXd& X, int cols) {
  SparseMatrixCol out(X.rows(), cols);
  Triplets t;
  for (int j = 0; j < X.cols(); ++j) {
    for (int i = 0; i < X.rows(); ++i) {
      if (X(i, j) != 0) t.emplace_back(i, j, X(i, j));
    }
  }
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

// [J_s, J_u(:, effective)]: motions of the state and the effective controls.
SparseMatrixCol WithControls(const SparseMatrixCol& J_s, const SparseMatrixCol& J_u, const std::vector<int>& effective) {
  Triplets t;
  AppendTriplets(J_s, 0, 0, &t);
  for (size_t c = 0; c < effective.size(); ++c) {
    for (SparseMatrixCol::InnerIterator it(J_u, effective[c]); it; ++it) {
      t.emplace_back(static_cast<int>(it.row()), static_cast<int>(J_s.cols() + c), it.value());
    }
  }
  SparseMatrixCol out(J_s.rows(), J_s.cols() + static_cast<Eigen::Index>(effective.size()));
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

// End-effector DOF over the null space N of A (first n columns the state):
// rank(dX/ds N) = rank([A; dX]) - rank(A), as null(A) ∩ null(dX) has the
// dimension cols - rank([A; dX]). `free_dof` receives cols - rank(A).
int EndEffectorDof(const SparseMatrixCol& A, const SparseMatrixCol& X, double threshold, int* free_dof) {
  const int rank = SparseRank(A, threshold);
  *free_dof = static_cast<int>(A.cols()) - rank;
  return SparseRank(Stack(A, X), threshold) - rank;
}

// The no-lateral-velocity rows of the differential bases that constrain the
// motion (mobility.cc, LateralRows): a base whose heading column lies in the
// range of [J_s; dX/ds] turns without moving the end-effector and is left out.
SparseMatrixCol LateralRows(const Model& model, const Eigen::VectorXd& u, const SparseMatrixCol& J_s,
                            const SparseMatrixCol& J_u, const SparseMatrixCol& X, const std::vector<int>& effective,
                            double threshold) {
  const int n = static_cast<int>(J_s.cols()), m = static_cast<int>(J_s.rows());
  std::vector<int> differential;
  for (int b = 0; b < model.num_bases(); ++b) {
    if (model.mobile_bases[b].type == BaseType::kDifferential) differential.push_back(b);
  }
  Eigen::MatrixXd headings = Eigen::MatrixXd::Zero(m + X.rows(), static_cast<Eigen::Index>(differential.size()));
  for (size_t i = 0; i < differential.size(); ++i) {
    headings.col(static_cast<Eigen::Index>(i)).head(m) = J_u.col(model.base_control(differential[i]) + 2);
  }
  const std::vector<bool> outside = OutsideRange(Stack(J_s, X.leftCols(n)), headings, threshold);
  Triplets t;
  int rows = 0;
  for (size_t i = 0; i < differential.size(); ++i) {
    if (!outside[i]) continue;
    const int b = differential[i];
    const double theta = u[model.base_control(b) + 2];
    for (size_t c = 0; c < effective.size(); ++c) {
      if (effective[c] == model.base_control(b)) t.emplace_back(rows, n + static_cast<int>(c), -std::sin(theta));
      if (effective[c] == model.base_control(b) + 1) t.emplace_back(rows, n + static_cast<int>(c), std::cos(theta));
    }
    ++rows;
  }
  SparseMatrixCol L(rows, n + static_cast<Eigen::Index>(effective.size()));
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

// MobilityReport::free_motions from an orthonormal null-space basis. Per
// body, a column-pivoted Householder QR of its rows (6 x d, transposed)
// rotates the directions not yet assigned: the first `moving` move the body,
// the others leave it still. Each rotation costs O(n d).
std::vector<FreeMotion> SplitByBody(Eigen::MatrixXd unassigned) {
  std::vector<FreeMotion> motions;
  for (Eigen::Index b = 0; b < unassigned.rows() / kPoseTangentSize && unassigned.cols() > 0; ++b) {
    const Eigen::MatrixXd rows = unassigned.middleRows(kPoseTangentSize * b, kPoseTangentSize);
    const Eigen::VectorXd sigma = JacobiSvd(rows).singularValues();
    const int moving = static_cast<int>((sigma.array() > kMovingBodyTolerance).count());
    if (moving == 0) continue;
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(rows.transpose());
    unassigned = unassigned * qr.householderQ();
    for (int k = 0; k < moving; ++k) motions.push_back({unassigned.col(k), FreeMotionBodies(unassigned.col(k)), {}});
    unassigned = unassigned.rightCols(unassigned.cols() - moving).eval();
  }
  return motions;
}

}  // namespace

std::vector<int> FreeMotionBodies(const Eigen::VectorXd& ds) {
  const double threshold = kMovingBodyTolerance * ds.cwiseAbs().maxCoeff();
  std::vector<int> bodies;
  for (int b = 0; b < ds.size() / kPoseTangentSize; ++b) {
    if (ds.segment(kPoseTangentSize * b, kPoseTangentSize).cwiseAbs().maxCoeff() > threshold) bodies.push_back(b);
  }
  return bodies;
}

SparseEndEffectorRanks::SparseEndEffectorRanks(const Model& model, const State& s, const Eigen::VectorXd& u,
                                               double rank_tolerance) {
  const ConstraintSet constraints(model);
  EnergyDerivatives derivatives;
  constraints.EvaluateDerivatives(s, u, &derivatives);
  threshold_ = rank_tolerance * std::max(1.0, LargestSingularValue(derivatives.J_s));
  A_ = WithControls(derivatives.J_s, derivatives.J_u, model.effective_control_indices());
  X_ = Sparse(EndEffectorJacobian(model, s), static_cast<int>(A_.cols()));
  rank_A_ = SparseRank(A_, threshold_);
}

int SparseEndEffectorRanks::Rank(const std::array<bool, 6>& rows) const {
  Triplets t;
  int count = 0;
  for (int r = 0; r < 6; ++r) {
    if (!rows[r]) continue;
    for (int j = 0; j < X_.outerSize(); ++j) {
      for (SparseMatrixCol::InnerIterator it(X_, j); it; ++it) {
        if (it.row() == r) t.emplace_back(count, static_cast<int>(it.col()), it.value());
      }
    }
    ++count;
  }
  if (count == 0) return 0;
  SparseMatrixCol X_rows(count, X_.cols());
  X_rows.setFromTriplets(t.begin(), t.end());
  return SparseRank(Stack(A_, X_rows), threshold_) - rank_A_;
}

bool SparseIdleMotions(const Model& model, const State& s, const Eigen::VectorXd& u, double rank_tolerance,
                       Eigen::MatrixXd* basis) {
  const ConstraintSet constraints(model);
  EnergyDerivatives derivatives;
  constraints.EvaluateDerivatives(s, u, &derivatives);
  const double threshold = rank_tolerance * std::max(1.0, LargestSingularValue(derivatives.J_s));
  const SparseMatrixCol M = Stack(derivatives.J_s, Sparse(EndEffectorJacobian(model, s), model.state_size()));
  const double dof = static_cast<double>(M.cols() - SparseRank(M, threshold));
  if (static_cast<double>(M.cols()) * dof * dof > kMaxFreeMotionWork) return false;
  *basis = dof > 0 ? SparseNullSpace(M, threshold) : Eigen::MatrixXd(M.cols(), 0);
  return true;
}

void AnalyzeMobilitySparse(const Model& model, const State& s, const Eigen::VectorXd& u, double rank_tolerance,
                           MobilityReport* report) {
  const ConstraintSet constraints(model);
  EnergyDerivatives derivatives;
  constraints.EvaluateDerivatives(s, u, &derivatives);
  const SparseMatrixCol J_s = derivatives.J_s, J_u = derivatives.J_u;
  const int n = model.state_size();
  const double threshold = rank_tolerance * std::max(1.0, LargestSingularValue(J_s));
  report->constraint_rank = SparseRank(J_s, threshold);
  report->dof_with_controls_fixed = n - report->constraint_rank;
  report->rigid_with_controls_fixed = report->dof_with_controls_fixed == 0;
  report->smallest_singular_value = report->rigid_with_controls_fixed ? SmallestSingularValue(J_s, threshold) : 0;
  const double d = report->dof_with_controls_fixed;
  report->free_motions_listed = static_cast<double>(n) * d * d <= kMaxFreeMotionWork;
  if (!report->rigid_with_controls_fixed && report->free_motions_listed) {
    report->free_motions = SplitByBody(SparseNullSpace(J_s, threshold));
  }

  const std::vector<int> effective = model.effective_control_indices();
  const SparseMatrixCol A = WithControls(J_s, J_u, effective);
  const SparseMatrixCol X = Sparse(EndEffectorJacobian(model, s), static_cast<int>(A.cols()));
  report->end_effector_dof = EndEffectorDof(A, X, threshold, &report->dof_with_controls_free);
  const SparseMatrixCol L = LateralRows(model, u, J_s, J_u, X, effective, threshold);
  int free_dof = 0;
  report->end_effector_dof_nonholonomic =
      L.rows() == 0 ? report->end_effector_dof : EndEffectorDof(Stack(A, L), X, threshold, &free_dof);
}

}  // namespace ccma
