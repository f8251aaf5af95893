#pragma once
// geodual's seeded random numbers: SplitMix64 (Steele, Lea & Flood 2014) and
// xoshiro256** (Blackman & Vigna 2018) seeded through it. Both give the same
// stream on every platform and compiler, unlike the std:: distributions, so a
// seed always gives the same output.

#include <cstdint>

namespace geodual {

/// SplitMix64's output function: a bijective mix of 64 bits, also a good hash.
constexpr std::uint64_t splitmix64_mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// SplitMix64: a 64-bit counter stepped by the golden gamma, mixed.
class SplitMix64 {
 public:
  static constexpr std::uint64_t kGamma = 0x9e3779b97f4a7c15ULL;

  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() { return splitmix64_mix(state_ += kGamma); }
  /// Value number n (from 0) of the stream seeded with `seed`, without
  /// drawing the ones before: for draws in any order, on any thread.
  static constexpr std::uint64_t nth(std::uint64_t seed, std::uint64_t n) {
    return splitmix64_mix(seed + (n + 1) * kGamma);
  }
  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1p-53; }
  /// Uniform in [0, bound), without modulo bias. \pre bound > 0
  std::uint64_t below(std::uint64_t bound) {
    const std::uint64_t limit = ~std::uint64_t{0} - (~std::uint64_t{0} % bound);
    for (;;) {
      const std::uint64_t x = next();
      if (x < limit) return x % bound;
    }
  }

 private:
  std::uint64_t state_;
};

/// xoshiro256**, its state drawn from SplitMix64: a longer period and
/// independent streams of one seed. `stream` separates the uses of one seed
/// (components, strategies, repairs).
class Xoshiro256 {
 public:
  Xoshiro256(std::uint64_t seed, std::uint64_t stream) {
    SplitMix64 seeder(seed ^ (stream * 0xd1b54a32d192ed03ULL));
    for (auto& word : s_) word = seeder.next();
  }

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1p-53; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

}  // namespace geodual
