// group_vertex_copies: the copies of each original vertex, grouped in
// increasing order, with the copies left out that `keep` drops.

#include "geodual/mesh/vertex_copies.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace geodual {
namespace {

TEST(VertexCopies, GroupsTheCopiesOfEachOriginalInIncreasingOrder) {
  // Copies 0..5 of originals 0..3: original 1 has three copies, 3 none.
  const std::vector<Index> original = {1, 0, 2, 1, 2, 1};
  const VertexCopies copies = group_vertex_copies(original, 4);
  EXPECT_EQ(copies.begin, (std::vector<Index>{0, 1, 4, 6, 6}));
  EXPECT_EQ(std::vector<Index>(copies.of(0).begin(), copies.of(0).end()), (std::vector<Index>{1}));
  EXPECT_EQ(std::vector<Index>(copies.of(1).begin(), copies.of(1).end()), (std::vector<Index>{0, 3, 5}));
  EXPECT_EQ(std::vector<Index>(copies.of(2).begin(), copies.of(2).end()), (std::vector<Index>{2, 4}));
  EXPECT_TRUE(copies.of(3).empty());
}

TEST(VertexCopies, CopiesNotKeptAreLeftOut) {
  const std::vector<Index> original = {1, 0, 2, 1, 2, 1};
  const std::vector<std::uint8_t> keep = {1, 1, 0, 0, 1, 1};
  const VertexCopies copies = group_vertex_copies(original, 3, keep);
  EXPECT_EQ(std::vector<Index>(copies.of(1).begin(), copies.of(1).end()), (std::vector<Index>{0, 5}));
  EXPECT_EQ(std::vector<Index>(copies.of(2).begin(), copies.of(2).end()), (std::vector<Index>{4}));
  EXPECT_EQ(copies.copies.size(), 4u);
}

}  // namespace
}  // namespace geodual
