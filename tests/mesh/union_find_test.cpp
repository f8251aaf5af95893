// UnionFind: roots are the smallest element of their set, whatever the order
// of the unions (the determinism every user of it relies on).

#include "geodual/mesh/union_find.hpp"

#include <gtest/gtest.h>

namespace geodual {
namespace {

TEST(UnionFind, RootIsTheSmallestElement) {
  UnionFind sets(10);
  EXPECT_TRUE(sets.unite(9, 7));
  EXPECT_TRUE(sets.unite(7, 8));
  EXPECT_TRUE(sets.unite(8, 4));
  EXPECT_FALSE(sets.unite(9, 4));
  for (const Index x : {4, 7, 8, 9}) EXPECT_EQ(sets.find(x), 4);
  EXPECT_EQ(sets.find(5), 5);
  EXPECT_EQ(sets.merges(), 3U);
  EXPECT_EQ(sets.sets(), 7U);
}

TEST(UnionFind, OrderOfUnionsDoesNotMatter) {
  UnionFind forward(100), backward(100);
  for (Index i = 0; i + 3 < 100; i += 3) forward.unite(i, i + 3);
  for (Index i = 99; i >= 3; i -= 3) backward.unite(i, i - 3);
  for (Index x = 0; x < 100; ++x) EXPECT_EQ(forward.find(x), backward.find(x)) << x;
  EXPECT_EQ(forward.find(99), 0);
  EXPECT_EQ(forward.find(98), 98);
}

TEST(UnionFind, ResetGivesSingletons) {
  UnionFind sets(4);
  sets.unite(0, 3);
  sets.reset(6);
  EXPECT_EQ(sets.size(), 6U);
  EXPECT_EQ(sets.sets(), 6U);
  EXPECT_EQ(sets.find(3), 3);
}

}  // namespace
}  // namespace geodual
