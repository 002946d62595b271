#include "problems/internal/block_elimination.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace ccma {

BlockElimination::BlockElimination(int num_columns, const std::vector<std::pair<int, int>>& couplings)
    : num_columns_(num_columns) {
  // The rows of every column of the factor: the couplings with later
  // positions, then the fill (eliminating column j couples all its rows).
  std::vector<std::set<int>> rows(static_cast<size_t>(num_columns));
  for (const auto& [a, b] : couplings) {
    if (a < 0 || b < 0 || a >= num_columns || b >= num_columns) {
      throw std::logic_error("BlockElimination: a coupling outside the matrix");
    }
    if (a != b) rows[static_cast<size_t>(std::min(a, b))].insert(std::max(a, b));
  }
  for (int j = 0; j < num_columns; ++j) {
    const std::set<int>& column = rows[static_cast<size_t>(j)];
    if (column.empty()) continue;
    // Eliminating j couples every pair of its rows; its first row (its
    // parent) eliminates later than the others, so adding the rest to the
    // parent's column spreads the same fill, transitively (the elimination
    // tree's symbolic factorisation).
    const int parent = *column.begin();
    rows[static_cast<size_t>(parent)].insert(std::next(column.begin()), column.end());
  }
  column_start_.push_back(0);
  for (int j = 0; j < num_columns; ++j) {
    column_row_.insert(column_row_.end(), rows[static_cast<size_t>(j)].begin(), rows[static_cast<size_t>(j)].end());
    column_start_.push_back(static_cast<int>(column_row_.size()));
  }
  // Right-looking updates of column j: F(a, b) -= L(a, j) (.) L(b, j)^T for
  // every pair of rows a >= b of column j; F(a, b) is in the pattern by
  // construction of the fill.
  update_start_.push_back(0);
  for (int j = 0; j < num_columns; ++j) {
    for (int x = column_start_[j]; x < column_start_[j + 1]; ++x) {
      for (int y = column_start_[j]; y <= x; ++y) {
        updates_.push_back({Block(column_row_[x], column_row_[y]), block(x), block(y)});
      }
    }
    update_start_.push_back(static_cast<int>(updates_.size()));
  }
}

int BlockElimination::Block(int i, int j) const {
  if (i == j) return j;
  if (i < j) return -1;
  const auto begin = column_row_.begin() + column_start_[j], end = column_row_.begin() + column_start_[j + 1];
  const auto it = std::lower_bound(begin, end, i);
  return it != end && *it == i ? block(static_cast<int>(it - column_row_.begin())) : -1;
}

}  // namespace ccma
