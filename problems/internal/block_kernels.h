// The dense 6 x 6 kernels of the block factorisations (SparseLM's block
// LL^T of J^T J, HessianSolver's block LDL^T of dG/ds): one diagonal block
// factorised and its triangular factor inverted, so that the column scaling
// and the substitutions are plain fixed-size products.
//
// Written as loops that the compiler unrolls completely (CCMA_UNROLL_6 on
// every level): Eigen's LLT and triangular solve of a 6 x 6 block go through
// its general blocked kernels and took three times as long, and without the
// unrolling GCC keeps the triangular loops as loops (a tenth of a forward
// solve's instructions more, callgrind).
#ifndef CCMA_PROBLEMS_INTERNAL_BLOCK_KERNELS_H_
#define CCMA_PROBLEMS_INTERNAL_BLOCK_KERNELS_H_

#include <cmath>

#include <Eigen/Core>

#include "ccma/state.h"

#define CCMA_UNROLL_6 _Pragma("GCC unroll 6")

namespace ccma {
namespace block_kernels {

constexpr int kT = kPoseTangentSize;

// out = L^-1 for the lower triangular L (strict lower part read) with
// diagonal 1 / inverse_diagonal; zeros above the diagonal. Row by row: each
// row of the inverse reads only the rows above it.
inline void WriteInverseOfLower(const double (&L)[kT][kT], const double (&inverse_diagonal)[kT],
                                Eigen::Matrix<double, kT, kT>* out) {
  double X[kT][kT];
  CCMA_UNROLL_6
  for (int i = 0; i < kT; ++i) {
    CCMA_UNROLL_6
    for (int j = 0; j < i; ++j) {
      double v = 0;
      CCMA_UNROLL_6
      for (int k = j; k < i; ++k) v -= L[i][k] * X[k][j];
      X[i][j] = v * inverse_diagonal[i];
    }
    X[i][i] = inverse_diagonal[i];
    CCMA_UNROLL_6
    for (int j = i + 1; j < kT; ++j) X[i][j] = 0;
  }
  CCMA_UNROLL_6
  for (int j = 0; j < kT; ++j) {
    CCMA_UNROLL_6
    for (int i = 0; i < kT; ++i) (*out)(i, j) = X[i][j];
  }
}

// Replaces the symmetric positive definite 6 x 6 block m (lower triangle
// read) by L^{-1}, L its Cholesky factor (lower triangular, zeros above);
// false if m is not positive definite.
inline bool InvertCholeskyFactor(Eigen::Matrix<double, kT, kT>* m) {
  Eigen::Matrix<double, kT, kT>& a = *m;
  double L[kT][kT];
  double inverse_diagonal[kT];
  CCMA_UNROLL_6
  for (int j = 0; j < kT; ++j) {
    double d = a(j, j);
    CCMA_UNROLL_6
    for (int k = 0; k < j; ++k) d -= L[j][k] * L[j][k];
    if (!(d > 0)) return false;  // also NaN
    inverse_diagonal[j] = 1 / std::sqrt(d);
    CCMA_UNROLL_6
    for (int i = j + 1; i < kT; ++i) {
      double v = a(i, j);
      CCMA_UNROLL_6
      for (int k = 0; k < j; ++k) v -= L[i][k] * L[j][k];
      L[i][j] = v * inverse_diagonal[j];
    }
  }
  WriteInverseOfLower(L, inverse_diagonal, m);
  return true;
}

// a = L D L^T for the symmetric 6 x 6 block a (lower triangle read), L unit
// lower triangular, without pivoting; a is replaced by L^-1 (unit lower
// triangular, zeros above) and d (6) by the pivots. False if a pivot is
// zero or not finite.
inline bool InvertLdltFactor(Eigen::Matrix<double, kT, kT>* block, double* d) {
  Eigen::Matrix<double, kT, kT>& a = *block;
  double L[kT][kT];
  CCMA_UNROLL_6
  for (int c = 0; c < kT; ++c) {
    double v[kT];  // L(c, k) d_k
    double pivot = a(c, c);
    CCMA_UNROLL_6
    for (int k = 0; k < c; ++k) {
      v[k] = L[c][k] * d[k];
      pivot -= L[c][k] * v[k];
    }
    if (!(std::isfinite(pivot) && pivot != 0)) return false;
    d[c] = pivot;
    const double inverse_pivot = 1 / pivot;
    CCMA_UNROLL_6
    for (int r = c + 1; r < kT; ++r) {
      double x = a(r, c);
      CCMA_UNROLL_6
      for (int k = 0; k < c; ++k) x -= L[r][k] * v[k];
      L[r][c] = x * inverse_pivot;
    }
  }
  const double unit[kT] = {1, 1, 1, 1, 1, 1};
  WriteInverseOfLower(L, unit, block);
  return true;
}

}  // namespace block_kernels
}  // namespace ccma

#undef CCMA_UNROLL_6

#endif  // CCMA_PROBLEMS_INTERNAL_BLOCK_KERNELS_H_
