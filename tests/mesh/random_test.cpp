// The seeded generators: reference values (a changed stream changes every
// seeded output of geodual), and the properties their users rely on.

#include "geodual/mesh/random.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace geodual {
namespace {

TEST(SplitMix64, GivesTheReferenceStream) {
  // The first values of SplitMix64 from state 0 (Vigna's reference code).
  SplitMix64 rng(0);
  EXPECT_EQ(rng.next(), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(rng.next(), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ(rng.next(), 0x06c45d188009454fULL);
}

TEST(SplitMix64, NthIsTheNthDraw) {
  SplitMix64 rng(12345);
  for (std::uint64_t n = 0; n < 100; ++n) EXPECT_EQ(SplitMix64::nth(12345, n), rng.next()) << "n = " << n;
}

TEST(SplitMix64, DrawsStayInRange) {
  SplitMix64 rng(99);
  for (int i = 0; i < 10000; ++i) {
    const double u = rng.uniform();
    EXPECT_GE(u, 0.0);
    EXPECT_LT(u, 1.0);
    EXPECT_LT(rng.below(7), 7U);
  }
}

TEST(Xoshiro256, GivesTheStreamSamplingIsBuiltOn) {
  // Seed 7, stream 3: the values the site sampling has drawn since it was written.
  Xoshiro256 rng(7, 3);
  EXPECT_EQ(rng.next(), 0xd88d886bb833247cULL);
  EXPECT_EQ(rng.next(), 0xcae3895e9c256b2dULL);
  EXPECT_EQ(rng.next(), 0x1d572d315b1ec89fULL);
}

TEST(Xoshiro256, StreamsOfOneSeedDiffer) {
  Xoshiro256 a(7, 0), b(7, 1), c(7, 0);
  const std::uint64_t first = a.next();
  EXPECT_NE(first, b.next());
  EXPECT_EQ(first, c.next());
}

}  // namespace
}  // namespace geodual
