#pragma once
// An 8-bit image as textures store it: texels row by row, the top row first,
// channels interleaved (RGB or RGBA). Colour channels are sRGB-encoded, alpha
// linear -- as in glTF's base colour textures and in PNG files.

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace geodual {

struct TextureImage {
  int width = 0;
  int height = 0;
  int channels = 0;                    ///< 3 (RGB) or 4 (RGBA)
  std::vector<std::uint8_t> texels{};  ///< width x height x channels bytes

  bool empty() const { return texels.empty(); }
  std::size_t offset(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
           static_cast<std::size_t>(channels);
  }
};

/// A surface's base colour texture: texture coordinates at every face corner
/// (glTF's convention: (0, 0) the top-left corner of the image, v down) and
/// the images they address -- one per material, a face in one of them --
/// sampled bilinearly with the coordinates wrapped (glTF's default sampler,
/// REPEAT).
struct SurfaceTexture {
  /// Three rows per face: face f's corner c at row 3 f + c.
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> corner_uvs{};
  std::vector<TextureImage> images{};
  /// Per face, the image its coordinates address; empty: image 0 for every face.
  std::vector<std::int32_t> face_image{};

  bool empty() const { return images.empty(); }
  /// The image face f's coordinates address.
  const TextureImage& image_of(std::int64_t f) const {
    return images[face_image.empty() ? 0 : static_cast<std::size_t>(face_image[static_cast<std::size_t>(f)])];
  }
};

}  // namespace geodual
