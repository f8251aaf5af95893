#include "geodual/mesh/detail/index_hash_map.hpp"

#include <gtest/gtest.h>

#include <array>
#include <map>
#include <random>

namespace geodual {
namespace {

TEST(IndexHashMap, FindsWhatWasInsertedAndNothingElse) {
  // Keys scattered over a large range, many times the first capacity, with
  // repeats: the map must agree with std::map throughout its growth.
  IndexHashMap<std::array<Index, 2>> map;
  std::map<Index, std::array<Index, 2>> reference;
  std::mt19937 random(7);
  std::uniform_int_distribution<Index> key(0, 50'000'000);
  for (int i = 0; i < 20'000; ++i) {
    const Index k = key(random);
    const std::array<Index, 2> value{i, -i};
    EXPECT_EQ(map.insert(k, value), reference.emplace(k, value).second);
  }
  EXPECT_EQ(map.size(), reference.size());
  for (const auto& [k, value] : reference) {
    const std::array<Index, 2>* found = map.find(k);
    ASSERT_NE(found, nullptr) << k;
    EXPECT_EQ(*found, value);  // the first value inserted stays
  }
  int absent = 0;
  for (Index k = 0; k < 200'000; ++k) {
    if (reference.count(k) == 0) {
      EXPECT_EQ(map.find(k), nullptr) << k;
      ++absent;
    }
  }
  EXPECT_GT(absent, 0);
}

TEST(IndexHashMap, ClearEmptiesItForReuse) {
  IndexHashSet set;
  EXPECT_EQ(set.find(3), nullptr);  // empty, never grown
  for (Index k = 0; k < 1000; ++k) EXPECT_TRUE(set.insert(k * 64));
  EXPECT_FALSE(set.insert(64));
  set.clear();
  EXPECT_EQ(set.size(), 0u);
  EXPECT_EQ(set.find(64), nullptr);
  EXPECT_TRUE(set.insert(64));
  EXPECT_NE(set.find(64), nullptr);
}

}  // namespace
}  // namespace geodual
