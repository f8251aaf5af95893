#pragma once
// Internal: unsigned arithmetic that sticks at the maximum instead of wrapping,
// for lower bounds on file sizes computed from counts a header claims.

#include <concepts>
#include <limits>

namespace geodual::io::detail {

template <std::unsigned_integral T>
constexpr T saturating_add(T a, T b) {
  const T max = std::numeric_limits<T>::max();
  return a > max - b ? max : static_cast<T>(a + b);
}

template <std::unsigned_integral T>
constexpr T saturating_mul(T a, T b) {
  const T max = std::numeric_limits<T>::max();
  return (a != 0 && b > max / a) ? max : static_cast<T>(a * b);
}

}  // namespace geodual::io::detail
