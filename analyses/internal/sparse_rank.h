// Ranks, null spaces and extreme singular values of large sparse matrices
// (the constraint Jacobians of `ccma check` beyond a few hundred state
// components), with SuiteSparseQR's rank-revealing sparse QR: time and
// memory grow with the matrix's nonzeros and the factor's fill, never with
// rows x columns as a dense SVD does.
//
// Rank decisions: a column whose remaining norm during the factorisation is
// at most `threshold` counts as dependent (Heath's rule, as SuiteSparseQR
// applies it); the caller passes rank_tolerance * largest singular value,
// the same threshold the dense SVD compares singular values with.
#ifndef CCMA_ANALYSES_INTERNAL_SPARSE_RANK_H_
#define CCMA_ANALYSES_INTERNAL_SPARSE_RANK_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace ccma {

using SparseMatrixCol = Eigen::SparseMatrix<double, Eigen::ColMajor>;

// The largest singular value of A (power iteration on A^T A from a fixed
// start, to a relative change of 1e-10 or 500 iterations): enough for a
// rank threshold. 0 for an empty or zero matrix.
double LargestSingularValue(const SparseMatrixCol& A);

// The numerical rank of A.
int SparseRank(const SparseMatrixCol& A, double threshold);

// The smallest singular value of A (rows >= columns, full column rank at
// `threshold`), by inverse iteration on R^T R with A P = Q R: 0 when A has
// fewer rows than columns or is rank deficient at `threshold` (singular).
double SmallestSingularValue(const SparseMatrixCol& A, double threshold);

// An orthonormal basis (columns) of the null space of A (the last
// columns of Q in A^T P = Q R, as SuiteSparseQR's spqr_null): n x (n - rank).
Eigen::MatrixXd SparseNullSpace(const SparseMatrixCol& A, double threshold);

// For each column c of `columns` (as many rows as A), whether c lies outside
// the range of A: its distance from that range, |c - Q Q^T c| over the first
// rank(A) columns of Q, exceeds `threshold`.
std::vector<bool> OutsideRange(const SparseMatrixCol& A, const Eigen::MatrixXd& columns, double threshold);

}  // namespace ccma

#endif  // CCMA_ANALYSES_INTERNAL_SPARSE_RANK_H_
