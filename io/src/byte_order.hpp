#pragma once
// Internal: loading and storing arithmetic values of a given byte order from
// unaligned memory (binary PLY and STL). memcpy + bit_cast: no aliasing or
// alignment UB, and compilers turn it into a plain (byte-swapping) load.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace geodual::io::detail {

template <class T>
concept Arithmetic = std::is_arithmetic_v<T>;

namespace byte_order_internal {

template <std::size_t Size>
struct UnsignedOfSize;
template <>
struct UnsignedOfSize<1> {
  using type = std::uint8_t;
};
template <>
struct UnsignedOfSize<2> {
  using type = std::uint16_t;
};
template <>
struct UnsignedOfSize<4> {
  using type = std::uint32_t;
};
template <>
struct UnsignedOfSize<8> {
  using type = std::uint64_t;
};

template <class U>
constexpr U reverse_bytes(U value) {
  if constexpr (sizeof(U) == 1) {
    return value;
  } else if constexpr (sizeof(U) == 2) {
    return __builtin_bswap16(value);
  } else if constexpr (sizeof(U) == 4) {
    return __builtin_bswap32(value);
  } else {
    return __builtin_bswap64(value);
  }
}

}  // namespace byte_order_internal

/// The value of type T stored at `at` in byte order `Order`.
template <Arithmetic T, std::endian Order>
T load(const std::byte* at) {
  using Bits = typename byte_order_internal::UnsignedOfSize<sizeof(T)>::type;
  Bits bits;
  std::memcpy(&bits, at, sizeof bits);
  if constexpr (Order != std::endian::native) {
    bits = byte_order_internal::reverse_bytes(bits);
  }
  return std::bit_cast<T>(bits);
}

/// Stores `value` at `at` in byte order `Order`.
template <std::endian Order, Arithmetic T>
void store(std::byte* at, T value) {
  using Bits = typename byte_order_internal::UnsignedOfSize<sizeof(T)>::type;
  auto bits = std::bit_cast<Bits>(value);
  if constexpr (Order != std::endian::native) {
    bits = byte_order_internal::reverse_bytes(bits);
  }
  std::memcpy(at, &bits, sizeof bits);
}

}  // namespace geodual::io::detail
