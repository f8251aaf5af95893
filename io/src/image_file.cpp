// PNG and JPEG encoding with stb_image_write (Debian libstb-dev), compiled
// into this translation unit rather than linked from libstb:
//  - STB_IMAGE_WRITE_STATIC gives every stb function and global internal
//    linkage, so nothing clashes with another copy of stb in the process
//    (tinygltf carries its own) and stb's process-wide settings (compression
//    level, vertical flip) stay private to this file and at their defaults;
//  - no new link dependency or CMake change: the header is all we need;
//  - the header lives in /usr/include (libstb-dev), a system header
//    directory, so its own warnings do not reach -Werror: no pragmas needed,
//    here or where geodual includes stb elsewhere.
//  - STBI_WRITE_NO_STDIO: we only encode to memory (files are written
//    atomically by atomic_file.cpp).

#include "geodual/io/image_file.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/mesh/error.hpp"
#include "preview_png.hpp"

#include <cstdint>
#include <ostream>
#include <string>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace geodual::io {
namespace {

constexpr int jpeg_quality = 90;

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::byte>*>(context);
  const auto* bytes = static_cast<const std::byte*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

// Encodes width x height texels of `channels` bytes each; false where stb fails (out of memory).
bool encode(const std::uint8_t* texels, int width, int height, int channels, ImageFormat format,
            std::vector<std::byte>& out) {
  if (format == ImageFormat::png) {
    return stbi_write_png_to_func(append_bytes, &out, width, height, channels, texels, width * channels) != 0;
  }
  return stbi_write_jpg_to_func(append_bytes, &out, width, height, channels, texels, jpeg_quality) != 0;
}

}  // namespace

std::string_view image_format_name(ImageFormat format) { return format == ImageFormat::png ? "png" : "jpeg"; }
std::string_view image_mime_type(ImageFormat format) { return format == ImageFormat::png ? "image/png" : "image/jpeg"; }
std::string_view image_extension(ImageFormat format) { return format == ImageFormat::png ? ".png" : ".jpg"; }

std::vector<std::byte> encode_image(const TextureImage& image, ImageFormat format) {
  if (image.width <= 0 || image.height <= 0 || (image.channels != 3 && image.channels != 4) ||
      image.texels.size() != image.offset(0, image.height)) {
    throw Error("image: " + std::to_string(image.texels.size()) + " bytes do not make a " +
                std::to_string(image.width) + " x " + std::to_string(image.height) + " image of " +
                std::to_string(image.channels) + " channels (3 or 4)");
  }
  std::vector<std::byte> out;
  // JPEG has no alpha: stb writes the first three channels of each texel.
  if (!encode(image.texels.data(), image.width, image.height, image.channels, format, out)) {
    throw Error("image: " + std::string(image_format_name(format)) + " encoding failed (out of memory?)");
  }
  return out;
}

void write_image(const std::filesystem::path& path, const TextureImage& image, ImageFormat format) {
  std::vector<std::byte> bytes;
  try {
    bytes = encode_image(image, format);
  } catch (const Error& error) {
    throw Error(path.string() + ": " + error.what());
  }
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  });
}

namespace detail {

std::vector<std::uint8_t> encode_png_rgb(const std::vector<std::uint8_t>& rgb, int width, int height) {
  constexpr int channels = 3;
  if (width <= 0 || height <= 0 ||
      rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channels) {
    throw Error("preview: internal error: pixel buffer does not match the picture size");
  }
  std::vector<std::byte> png;
  if (!encode(rgb.data(), width, height, channels, ImageFormat::png, png)) {
    throw Error("preview: PNG encoding failed (out of memory?)");
  }
  const auto* first = reinterpret_cast<const std::uint8_t*>(png.data());
  return {first, first + png.size()};
}

}  // namespace detail
}  // namespace geodual::io
