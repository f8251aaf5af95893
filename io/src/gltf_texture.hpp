#pragma once
// Internal: the base colour textures of a glTF file. A texture's sampler and
// image source are checked when a material is planned; the image (PNG or
// JPEG, from a buffer view, a base64 data URI or a file beside the glTF) is
// decoded only when a vertex is first sampled from it, and kept for the rest
// of the read as 8-bit sRGB-encoded RGBA.
//
// Sampling follows the glTF sampler: wrapS / wrapT (REPEAT, CLAMP_TO_EDGE,
// MIRRORED_REPEAT) and magFilter (NEAREST, else bilinear). Texture coordinate
// (0, 0) is the first texel of the image's first row; texel (i, j) has its
// centre at ((i + 0.5) / width, (j + 0.5) / height). Bilinear filtering mixes
// texels in linear space, as a GPU does with an sRGB texture.

#include "geodual/mesh/texture_image.hpp"
#include "gltf_buffers.hpp"
#include "gltf_json.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace geodual::io::detail::gltf {

enum class WrapMode : std::uint8_t { repeat, clamp_to_edge, mirrored_repeat };

struct TextureSampler {
  WrapMode wrap_s = WrapMode::repeat;
  WrapMode wrap_t = WrapMode::repeat;
  bool nearest = false;  ///< magFilter NEAREST; otherwise bilinear
};

/// A decoded image: width x height texels, 4 bytes each (sRGB-encoded RGB, linear alpha), rows top first.
struct DecodedImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
};

/// Linear RGBA (each in [0, 1]) of `image` at texture coordinates (u, v).
std::array<float, 4> sample_texture(const DecodedImage& image, const TextureSampler& sampler, double u, double v);

/// The image as geodual keeps it: RGB where every alpha is 255, else RGBA.
TextureImage texture_image(const DecodedImage& image);

/// Decodes PNG or JPEG bytes; throws geodual::Error("<where>: ...") naming the problem.
DecodedImage decode_image(std::span<const std::byte> bytes, const std::string& where);

class TextureStore {
 public:
  /// `root` and `buffers` must outlive the store; `file` is the glTF file's
  /// path (empty: read from memory, where external images cannot be found).
  TextureStore(const Json& root, BufferStore& buffers, std::filesystem::path file, std::string where);

  struct Texture {
    std::size_t image = 0;
    TextureSampler sampler;
  };

  /// Texture `index` (< the number of textures), its sampler and image source
  /// checked, nothing decoded; nullopt when the texture has no "source" (its
  /// image is in a format only an extension defines, e.g. KTX2 or WebP).
  std::optional<Texture> texture(std::size_t index, const std::string& where);

  /// Image `index`, decoded on first use.
  const DecodedImage& image(std::size_t index);

 private:
  std::string image_where(std::size_t index) const;

  const Json& root_;
  BufferStore& buffers_;
  std::filesystem::path file_;
  std::string where_;
  std::map<std::size_t, DecodedImage> images_;
};

}  // namespace geodual::io::detail::gltf
