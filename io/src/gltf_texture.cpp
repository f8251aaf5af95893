// Image decoding with stb_image (Debian libstb-dev), compiled into this
// translation unit as preview_png.cpp does with stb_image_write:
// STB_IMAGE_STATIC keeps every stb symbol internal (tinygltf carries its own
// copy), only the PNG and JPEG decoders are compiled (the two formats glTF
// 2.0 allows without extensions), nothing reads files (we hand it bytes), and
// STBI_MAX_DIMENSIONS bounds what a hostile header can make it allocate.

#include "gltf_texture.hpp"

#include "geodual/mesh/vertex_attributes.hpp"
#include "gltf_accessor.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <memory>
#include <utility>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#define STBI_MAX_DIMENSIONS (1 << 15)
#include <stb/stb_image.h>

namespace geodual::io::detail::gltf {
namespace {

// At most 2^28 texels (1 GiB decoded): more than any texture a scan carries.
constexpr long long max_texels = 1LL << 28;

// The glTF sampler codes (OpenGL enums).
constexpr std::uint64_t gl_nearest = 9728;
constexpr std::uint64_t gl_linear = 9729;
constexpr std::uint64_t gl_clamp_to_edge = 33071;
constexpr std::uint64_t gl_mirrored_repeat = 33648;
constexpr std::uint64_t gl_repeat = 10497;

WrapMode wrap_mode(const Json& sampler, std::string_view key, const std::string& where) {
  const std::uint64_t code = optional_uint(sampler, key, where).value_or(gl_repeat);
  switch (code) {
    case gl_repeat: return WrapMode::repeat;
    case gl_clamp_to_edge: return WrapMode::clamp_to_edge;
    case gl_mirrored_repeat: return WrapMode::mirrored_repeat;
    default: fail(where, "invalid '" + std::string(key) + "' " + std::to_string(code));
  }
}

// sRGB-encoded byte -> linear value, for every byte.
const std::array<float, 256>& linear_of_byte() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (std::size_t i = 0; i < t.size(); ++i) t[i] = linear_from_srgb(static_cast<float>(i) / 255.0f);
    return t;
  }();
  return table;
}

// `u` moved by whole wrap periods (or clamped) into a small range, so that
// u * size fits an integer; non-finite coordinates read as 0.
double reduced(double u, WrapMode mode) {
  if (!std::isfinite(u)) return 0.0;
  switch (mode) {
    case WrapMode::repeat: return u - std::floor(u);
    case WrapMode::mirrored_repeat: return u - 2.0 * std::floor(u / 2.0);
    case WrapMode::clamp_to_edge: return std::clamp(u, -1.0, 2.0);
  }
  return 0.0;
}

// Texel index `i` (any integer) wrapped into 0 .. size - 1.
long long wrapped(long long i, long long size, WrapMode mode) {
  switch (mode) {
    case WrapMode::clamp_to_edge: return std::clamp(i, 0LL, size - 1);
    case WrapMode::repeat: {
      const long long r = i % size;
      return r < 0 ? r + size : r;
    }
    case WrapMode::mirrored_repeat: {
      long long r = i % (2 * size);
      if (r < 0) r += 2 * size;
      return r < size ? r : 2 * size - 1 - r;
    }
  }
  return 0;
}

struct StbFree {
  void operator()(stbi_uc* pixels) const { stbi_image_free(pixels); }
};

}  // namespace

std::array<float, 4> sample_texture(const DecodedImage& image, const TextureSampler& sampler, double u, double v) {
  const std::array<float, 256>& linear = linear_of_byte();
  const long long width = image.width;
  const long long height = image.height;
  const auto texel = [&](long long i, long long j) {
    const std::uint8_t* t =
        image.rgba.data() + 4 * (wrapped(j, height, sampler.wrap_t) * width + wrapped(i, width, sampler.wrap_s));
    return std::array<float, 4>{linear[t[0]], linear[t[1]], linear[t[2]], static_cast<float>(t[3]) / 255.0f};
  };
  const double x = reduced(u, sampler.wrap_s) * static_cast<double>(width);
  const double y = reduced(v, sampler.wrap_t) * static_cast<double>(height);
  if (sampler.nearest) return texel(static_cast<long long>(std::floor(x)), static_cast<long long>(std::floor(y)));

  // Bilinear between the four texel centres around (x, y).
  const double x0 = std::floor(x - 0.5);
  const double y0 = std::floor(y - 0.5);
  const auto fx = static_cast<float>(x - 0.5 - x0);
  const auto fy = static_cast<float>(y - 0.5 - y0);
  const auto i = static_cast<long long>(x0);
  const auto j = static_cast<long long>(y0);
  const std::array<float, 4> a = texel(i, j);
  const std::array<float, 4> b = texel(i + 1, j);
  const std::array<float, 4> c = texel(i, j + 1);
  const std::array<float, 4> d = texel(i + 1, j + 1);
  std::array<float, 4> out{};
  for (std::size_t k = 0; k < 4; ++k) {
    out[k] = (1 - fy) * ((1 - fx) * a[k] + fx * b[k]) + fy * ((1 - fx) * c[k] + fx * d[k]);
  }
  return out;
}

TextureImage texture_image(const DecodedImage& image) {
  bool opaque = true;
  for (std::size_t t = 3; t < image.rgba.size(); t += 4) opaque = opaque && image.rgba[t] == 255;
  TextureImage kept{.width = image.width, .height = image.height, .channels = opaque ? 3 : 4};
  kept.texels.reserve(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) *
                      static_cast<std::size_t>(kept.channels));
  for (std::size_t t = 0; t < image.rgba.size(); t += 4) {
    kept.texels.insert(kept.texels.end(), image.rgba.begin() + static_cast<std::ptrdiff_t>(t),
                       image.rgba.begin() + static_cast<std::ptrdiff_t>(t + static_cast<std::size_t>(kept.channels)));
  }
  return kept;
}

DecodedImage decode_image(std::span<const std::byte> bytes, const std::string& where) {
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) fail(where, "is larger than 2 GiB; cannot decode it");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const auto length = static_cast<int>(bytes.size());
  int width = 0;
  int height = 0;
  int channels = 0;
  if (stbi_info_from_memory(data, length, &width, &height, &channels) == 0) {
    fail(where, std::string("cannot be decoded as PNG or JPEG (") + stbi_failure_reason() + ")");
  }
  if (static_cast<long long>(width) * height > max_texels) {
    fail(where,
         "is " + std::to_string(width) + " x " + std::to_string(height) + " texels, more than geodual decodes (2^28)");
  }
  const std::unique_ptr<stbi_uc, StbFree> pixels(stbi_load_from_memory(data, length, &width, &height, &channels, 4));
  if (!pixels) fail(where, std::string("cannot be decoded as PNG or JPEG (") + stbi_failure_reason() + ")");
  DecodedImage image;
  image.width = width;
  image.height = height;
  image.rgba.assign(pixels.get(),
                    pixels.get() + 4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  return image;
}

TextureStore::TextureStore(const Json& root, BufferStore& buffers, std::filesystem::path file, std::string where)
    : root_(root), buffers_(buffers), file_(std::move(file)), where_(std::move(where)) {}

std::optional<TextureStore::Texture> TextureStore::texture(std::size_t index, const std::string& user) {
  const Json& textures = array_member(root_, "textures", where_);
  const Json& texture = textures[index];
  const std::string where = user + ": " + describe("texture", index, texture);
  if (!texture.is_object()) fail(where, "must be a JSON object");
  const Json& images = array_member(root_, "images", where_);
  const std::optional<std::size_t> source = optional_index(texture, "source", images.size(), "image", where);
  if (!source) return std::nullopt;

  Texture result;
  result.image = *source;
  const std::string image_where = this->image_where(*source);
  const Json& image = images[*source];
  if (!image.is_object()) fail(image_where, "must be a JSON object");
  const bool has_uri = find_member(image, "uri") != nullptr;
  const bool has_view = find_member(image, "bufferView") != nullptr;
  if (has_uri == has_view) fail(image_where, "must have exactly one of 'uri' and 'bufferView'");

  const Json& samplers = array_member(root_, "samplers", where_);
  if (const auto s = optional_index(texture, "sampler", samplers.size(), "sampler", where)) {
    const Json& sampler = samplers[*s];
    const std::string sampler_where = where + ": " + describe("sampler", *s, sampler);
    if (!sampler.is_object()) fail(sampler_where, "must be a JSON object");
    result.sampler.wrap_s = wrap_mode(sampler, "wrapS", sampler_where);
    result.sampler.wrap_t = wrap_mode(sampler, "wrapT", sampler_where);
    const std::optional<std::uint64_t> mag = optional_uint(sampler, "magFilter", sampler_where);
    if (mag && *mag != gl_nearest && *mag != gl_linear) {
      fail(sampler_where, "invalid 'magFilter' " + std::to_string(*mag));
    }
    result.sampler.nearest = mag == gl_nearest;
  }
  return result;
}

std::string TextureStore::image_where(std::size_t index) const {
  return where_ + ": " + describe("image", index, array_member(root_, "images", where_)[index]);
}

const DecodedImage& TextureStore::image(std::size_t index) {
  if (const auto found = images_.find(index); found != images_.end()) return found->second;
  const Json& image = array_member(root_, "images", where_)[index];
  const std::string where = image_where(index);
  DecodedImage decoded;
  if (const std::optional<std::string> uri = optional_string(image, "uri", where)) {
    if (is_data_uri(*uri)) {
      decoded = decode_image(decode_data_uri(*uri, where), where);
    } else {
      if (file_.empty()) {
        fail(where, "external image '" + uri->substr(0, 80) +
                        "' cannot be found: the glTF data was read from memory without a file name");
      }
      const std::filesystem::path path = resolve_relative_uri(*uri, file_, where);
      decoded = decode_image(read_external_file(path, "external image '" + uri->substr(0, 80) + "'", where),
                             where + ": '" + path.string() + "'");
    }
  } else {
    const std::size_t view =
        required_index(image, "bufferView", array_member(root_, "bufferViews", where).size(), "bufferView", where);
    decoded = decode_image(buffer_view_bytes(root_, buffers_, view, where), where);
  }
  return images_.emplace(index, std::move(decoded)).first->second;
}

}  // namespace geodual::io::detail::gltf
