// The symbolic block elimination (problems/internal/block_elimination.h)
// on patterns whose fill is known by hand.
#include <stdexcept>

#include <gtest/gtest.h>

#include "problems/internal/block_elimination.h"

namespace ccma {
namespace block_elimination_test {

// An arrow (every column coupled to the last one only): no fill.
TEST(BlockElimination, ArrowHasNoFill) {
  const BlockElimination e(4, {{3, 0}, {1, 3}, {2, 3}, {3, 2}});
  EXPECT_EQ(e.num_blocks(), 4 + 3);
  for (int j = 0; j < 3; ++j) {
    EXPECT_GE(e.Block(3, j), 4);
    EXPECT_EQ(e.parent(j), 3);
    for (int i = j + 1; i < 3; ++i) EXPECT_EQ(e.Block(i, j), -1);
  }
  EXPECT_EQ(e.parent(3), -1);
  EXPECT_EQ(e.Block(2, 2), 2);
  EXPECT_EQ(e.Block(0, 3), -1);  // above the diagonal
  // Column j's only update: the last diagonal block by L(3, j) L(3, j)^T.
  for (int j = 0; j < 3; ++j) {
    ASSERT_EQ(e.updates_end(j) - e.updates_begin(j), 1);
    EXPECT_EQ(e.updates_begin(j)->target, 3);
    EXPECT_EQ(e.updates_begin(j)->a, e.Block(3, j));
    EXPECT_EQ(e.updates_begin(j)->b, e.Block(3, j));
  }
}

// A star eliminated from its centre first: every pair of the others fills,
// transitively through the elimination tree (0 -> 1 -> 2 -> 3).
TEST(BlockElimination, StarCentreFirstFillsEveryPair) {
  const BlockElimination e(4, {{0, 1}, {0, 2}, {0, 3}});
  EXPECT_EQ(e.num_blocks(), 4 + 6);  // the whole lower triangle
  for (int j = 0; j < 4; ++j) {
    for (int i = j + 1; i < 4; ++i) EXPECT_GE(e.Block(i, j), 4) << i << "," << j;
    EXPECT_EQ(e.parent(j), j < 3 ? j + 1 : -1);
  }
  // Column 0 has rows 1, 2, 3: 6 updates (pairs a >= b), each into the
  // block (a, b) of the factor.
  ASSERT_EQ(e.updates_end(0) - e.updates_begin(0), 6);
  for (const BlockElimination::Update* up = e.updates_begin(0); up != e.updates_end(0); ++up) {
    EXPECT_GE(up->target, 1);
  }
}

TEST(BlockElimination, RejectsACouplingOutsideTheMatrix) {
  EXPECT_THROW(BlockElimination(3, {{0, 3}}), std::logic_error);
  EXPECT_THROW(BlockElimination(3, {{-1, 0}}), std::logic_error);
}

}  // namespace
}  // namespace ccma
