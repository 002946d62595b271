#include "problems/internal/hessian_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/OrderingMethods>

#include "problems/internal/block_kernels.h"

namespace ccma {
namespace {

using Permutation = HessianSolver::Permutation;
constexpr int kB = kPoseTangentSize;

// The fill-reducing order of the scalar pattern, as Eigen's sparse LDL^T
// would choose it (AMD): (P v)[P[i]] = v[i].
Permutation FillReducingOrder(const SparseColMajor& pattern) {
  if (pattern.rows() != pattern.cols() || pattern.rows() % kB != 0) {
    throw std::logic_error("HessianSolver: the Hessian pattern is not square in blocks of 6");
  }
  Eigen::AMDOrdering<int> amd;
  Permutation inverse;
  amd(pattern, inverse);
  return inverse.inverse();
}

// The 6 x 6 blocks of P H P^T that hold an entry of the pattern.
std::vector<std::pair<int, int>> BlockCouplings(const SparseColMajor& pattern, const Permutation& P) {
  std::vector<std::pair<int, int>> couplings;
  for (int c = 0; c < pattern.outerSize(); ++c) {
    for (SparseColMajor::InnerIterator it(pattern, c); it; ++it) {
      const int i = P.indices()[it.row()] / kB, j = P.indices()[c] / kB;
      if (i > j) couplings.emplace_back(i, j);
    }
  }
  return couplings;
}


}  // namespace

HessianSolver::HessianSolver(const ConstraintSet& constraints)
    : HessianSolver(constraints, FillReducingOrder(constraints.hessian_pattern())) {}

HessianSolver::HessianSolver(const ConstraintSet& constraints, Permutation P)
    : P_(std::move(P)), elimination_(constraints.state_size() / kB, BlockCouplings(constraints.hessian_pattern(), P_)) {
  const SparseColMajor& pattern = constraints.hessian_pattern();
  const int n = constraints.state_size();
  const int block_size = kB * kB;
  std::vector<char> written(static_cast<size_t>(elimination_.num_blocks()) * block_size, 0);
  for (int c = 0; c < pattern.outerSize(); ++c) {
    for (int k = pattern.outerIndexPtr()[c]; k < pattern.outerIndexPtr()[c + 1]; ++k) {
      const int row = pattern.innerIndexPtr()[k];
      if (row < c) continue;  // the mirror of an entry below the diagonal
      const int p = P_.indices()[row], q = P_.indices()[c];
      const int i = std::max(p, q), j = std::min(p, q);
      const int place = elimination_.Block(i / kB, j / kB) * block_size + (j % kB) * kB + i % kB;
      scatter_.emplace_back(k, place);
      written[static_cast<size_t>(place)] = 1;
    }
  }
  // What the scatter leaves: the fill blocks, and the zeros of the pattern's
  // blocks (all of a block below the diagonal is read; of a diagonal block
  // only its lower triangle).
  for (int b = 0; b < elimination_.num_blocks(); ++b) {
    for (int col = 0; col < kB; ++col) {
      for (int row = b < elimination_.num_columns() ? col : 0; row < kB; ++row) {
        const int place = b * block_size + col * kB + row;
        if (!written[static_cast<size_t>(place)]) zeros_.push_back(place);
      }
    }
  }
  factor_.assign(static_cast<size_t>(elimination_.num_blocks()), Block::Zero());
  int longest_column = 0;
  for (int j = 0; j < elimination_.num_columns(); ++j) {
    longest_column = std::max(longest_column, elimination_.column_end(j) - elimination_.column_begin(j));
  }
  scaled_.assign(static_cast<size_t>(longest_column), Block::Zero());
  D_ = Eigen::VectorXd::Zero(n);
  mark_.assign(static_cast<size_t>(elimination_.num_columns()), 0);
  group_work_ = GroupWork::Zero(n, kGroup);
}

bool HessianSolver::Factorize(const SparseColMajor& H) {
  pivot_ratio_ = 0;
  factorized_ = false;
  double* factor = factor_.front().data();
  const double* values = H.valuePtr();
  for (const auto& [from, to] : scatter_) factor[to] = values[from];
  for (int place : zeros_) factor[place] = 0;
  // Right-looking block LDL^T: column j's diagonal block factorised, its
  // blocks below scaled to L_ij = A_ij L_jj^-T D_j^-1, and the rest of the
  // matrix updated by -L_aj D_j L_bj^T = -(L_aj D_j) L_bj^T.
  for (int j = 0; j < elimination_.num_columns(); ++j) {
    if (!block_kernels::InvertLdltFactor(&factor_[j], D_.data() + kB * j)) return false;
    const Block inverse_transpose = factor_[j].transpose();
    const Eigen::Array<double, 1, kB> inverse_pivots = D_.segment<kB>(kB * j).transpose().array().inverse();
    const int begin = elimination_.column_begin(j), end = elimination_.column_end(j);
    for (int k = begin; k < end; ++k) {
      Block& L = factor_[elimination_.block(k)];
      Block& scaled = scaled_[k - begin];
      scaled.noalias() = L.lazyProduct(inverse_transpose);  // L_ij D_j
      L = scaled.array().rowwise() * inverse_pivots;
    }
    const int first = elimination_.block(begin);
    for (const BlockElimination::Update* up = elimination_.updates_begin(j); up != elimination_.updates_end(j); ++up) {
      factor_[up->target].noalias() -= scaled_[up->a - first].lazyProduct(factor_[up->b].transpose());
    }
  }
  factorized_ = true;
  const double largest = D_.cwiseAbs().maxCoeff();
  pivot_ratio_ = largest > 0 ? D_.minCoeff() / largest : 0.0;  // negative: indefinite
  return true;
}

void HessianSolver::ForwardInPlace(double* y) const {
  for (int j = 0; j < elimination_.num_columns(); ++j) {
    Eigen::Map<BlockVector> y_j(y + kB * j);
    const BlockVector x = factor_[j].lazyProduct(y_j);
    y_j = x;
    for (int k = elimination_.column_begin(j); k < elimination_.column_end(j); ++k) {
      Eigen::Map<BlockVector>(y + kB * elimination_.row(k)).noalias() -= factor_[elimination_.block(k)].lazyProduct(x);
    }
  }
}

void HessianSolver::BackwardInPlace(double* y) const {
  for (int j = elimination_.num_columns() - 1; j >= 0; --j) {
    BlockVector x = Eigen::Map<const BlockVector>(y + kB * j);
    for (int k = elimination_.column_begin(j); k < elimination_.column_end(j); ++k) {
      x.noalias() -= factor_[elimination_.block(k)].transpose().lazyProduct(
          Eigen::Map<const BlockVector>(y + kB * elimination_.row(k)));
    }
    Eigen::Map<BlockVector>(y + kB * j).noalias() = factor_[j].transpose().lazyProduct(x);
  }
}

template <int Width>
void HessianSolver::ForwardSubstituteColumns(Eigen::MatrixXd* Y, Eigen::Index first) const {
  for (int j = 0; j < elimination_.num_columns(); ++j) {
    auto y_j = Y->block<kB, Width>(kB * j, first);
    const Eigen::Matrix<double, kB, Width> x = factor_[j].lazyProduct(y_j);
    y_j = x;
    for (int k = elimination_.column_begin(j); k < elimination_.column_end(j); ++k) {
      Y->block<kB, Width>(kB * elimination_.row(k), first).noalias() -= factor_[elimination_.block(k)].lazyProduct(x);
    }
  }
}

void HessianSolver::ForwardSubstitutePermuted(Eigen::MatrixXd* Y) const {
  // kGroup columns at a time as fixed-size blocks (no allocation, each
  // block of L read once per group), then the rest one by one.
  Eigen::Index first = 0;
  for (; first + kGroup <= Y->cols(); first += kGroup) ForwardSubstituteColumns<kGroup>(Y, first);
  for (; first < Y->cols(); ++first) ForwardSubstituteColumns<1>(Y, first);
}

Eigen::VectorXd HessianSolver::Solve(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd y = P_ * rhs;
  ForwardInPlace(y.data());
  y.array() /= D_.array();
  BackwardInPlace(y.data());
  return P_.transpose() * y;
}

Eigen::MatrixXd HessianSolver::Solve(const Eigen::MatrixXd& rhs) const {
  Eigen::MatrixXd out(rhs.rows(), rhs.cols());
  for (Eigen::Index c = 0; c < rhs.cols(); ++c) out.col(c) = Solve(Eigen::VectorXd(rhs.col(c)));
  return out;
}

Eigen::VectorXd HessianSolver::ForwardSubstitute(const Eigen::VectorXd& v) const {
  Eigen::VectorXd y = P_ * v;
  ForwardInPlace(y.data());
  return y;
}

void HessianSolver::ForwardSubstitute(const SparseColMajor& M, const std::vector<int>& columns,
                                      SparseFactorColumns* out) const {
  const auto& P = P_.indices();
  out->rows.resize(static_cast<size_t>(D_.size()));
  for (auto& row : out->rows) row.clear();
  // kGroup columns at a time over the union of their reaches: each block of
  // L is then read once per group and applied to the group's columns as one
  // 6 x kGroup product. The columns of one control block (a base's x, y,
  // theta) or of F (the end-effector body's rows) share their pattern, so
  // the union costs nothing over one reach on large models, while on small
  // ones, where every column reaches most of L, it saves most of the passes.
  for (size_t first = 0; first < columns.size(); first += kGroup) {
    const int group = static_cast<int>(std::min(columns.size() - first, size_t(kGroup)));
    // The reach: every ancestor in the block elimination tree of the blocks
    // holding the columns' nonzeros; ascending order is a topological order.
    reach_.clear();
    for (int g = 0; g < group; ++g) {
      for (SparseColMajor::InnerIterator it(M, columns[first + g]); it; ++it) {
        const int i = P[it.row()];
        group_work_(i, g) = it.value();
        for (int j = i / kB; j >= 0 && !mark_[j]; j = elimination_.parent(j)) {
          mark_[j] = 1;
          reach_.push_back(j);
        }
      }
    }
    std::sort(reach_.begin(), reach_.end());
    for (int j : reach_) {
      auto x_j = group_work_.middleRows<kB>(kB * j);
      if ((x_j.array() == 0).all()) continue;
      const GroupBlock x = factor_[j].lazyProduct(x_j);
      x_j = x;
      for (int k = elimination_.column_begin(j); k < elimination_.column_end(j); ++k) {
        group_work_.middleRows<kB>(kB * elimination_.row(k)).noalias() -= factor_[elimination_.block(k)].lazyProduct(x);
      }
    }
    for (int j : reach_) {
      for (int r = kB * j; r < kB * (j + 1); ++r) {
        for (int g = 0; g < group; ++g) {
          const double x = group_work_(r, g);
          if (x != 0) out->rows[static_cast<size_t>(r)].emplace_back(static_cast<int>(first) + g, x);
        }
      }
      group_work_.middleRows<kB>(kB * j).setZero();
      mark_[j] = 0;
    }
  }
}

}  // namespace ccma
