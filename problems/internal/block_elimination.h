// The symbolic part of a block factorisation (Cholesky LL^T or LDL^T) of a
// symmetric matrix of dense 6 x 6 blocks, in a given elimination order:
// which blocks of the factor are nonzero (with the fill), the list of block
// updates each column makes, and the block elimination tree. Computed once
// per model; the numeric factorisations (SparseLevenbergMarquardt's LL^T of
// J^T J, HessianSolver's LDL^T of dG/ds) then run over fixed lists with no
// search in a sparse structure.
#ifndef CCMA_PROBLEMS_INTERNAL_BLOCK_ELIMINATION_H_
#define CCMA_PROBLEMS_INTERNAL_BLOCK_ELIMINATION_H_

#include <utility>
#include <vector>

namespace ccma {

class BlockElimination {
 public:
  // One update of a right-looking factorisation by column j:
  // F[target] -= F[a] (something) F[b]^T, a and b blocks of column j.
  struct Update {
    int target, a, b;
  };

  // `num_columns` block columns in elimination order; `couplings`: pairs of
  // positions (i, j), i != j, whose block is structurally nonzero (either
  // order, repeats allowed; the diagonal always is).
  BlockElimination(int num_columns, const std::vector<std::pair<int, int>>& couplings);

  int num_columns() const { return num_columns_; }
  // Blocks of the factor: 0 .. num_columns-1 the diagonal ones by position,
  // then the blocks (i, j), i > j, column by column, rows ascending.
  int num_blocks() const { return static_cast<int>(column_row_.size()) + num_columns_; }
  // The block (i, j), i >= j, or -1 if it is zero in the factor.
  int Block(int i, int j) const;

  // Column j's blocks below the diagonal: rows row(k), blocks block(k), for
  // k in [column_begin(j), column_end(j)).
  int column_begin(int j) const { return column_start_[j]; }
  int column_end(int j) const { return column_start_[j + 1]; }
  int row(int k) const { return column_row_[k]; }
  int block(int k) const { return num_columns_ + k; }
  // Column j's updates: F(a, b) for every pair of its rows a >= b.
  const Update* updates_begin(int j) const { return updates_.data() + update_start_[j]; }
  const Update* updates_end(int j) const { return updates_.data() + update_start_[j + 1]; }
  // The elimination tree: the first row below the diagonal of column j, -1
  // for a root. Ascending positions are a topological order (parent > child).
  int parent(int j) const { return column_start_[j] < column_start_[j + 1] ? column_row_[column_start_[j]] : -1; }

 private:
  int num_columns_ = 0;
  std::vector<int> column_start_, column_row_;
  std::vector<int> update_start_;
  std::vector<Update> updates_;
};

}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_BLOCK_ELIMINATION_H_
