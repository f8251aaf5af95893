#pragma once
// Internal: PNG encoding for the preview (image_file.cpp, with the texture images).

#include <cstdint>
#include <vector>

namespace geodual::io::detail {

/// The bytes of a PNG file holding `rgb`: width x height pixels, 3 bytes each,
/// rows top to bottom. Deterministic (fixed zlib level and filter heuristic).
std::vector<std::uint8_t> encode_png_rgb(const std::vector<std::uint8_t>& rgb, int width, int height);

}  // namespace geodual::io::detail
