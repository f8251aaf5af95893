#pragma once
// Morton (Z-order) codes: sorting 3D cells by them keeps cells that are close
// in space mostly close in the order.

#include <cstdint>

namespace geodual {

/// The Morton code of the cell (x, y, z): the low 21 bits of each coordinate
/// interleaved, x in bit 0, y in bit 1, z in bit 2, then x in bit 3, ...
inline std::uint64_t morton_code(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  // Spreads the low 21 bits of v to every third bit.
  auto spread = [](std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  return spread(x) | spread(y) << 1 | spread(z) << 2;
}

}  // namespace geodual
