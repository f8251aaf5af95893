// PNG encoding with stb_image_write (Debian libstb-dev), compiled into this
// translation unit rather than linked from libstb:
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

#include "preview_png.hpp"

#include "geodual/mesh/error.hpp"

#include <cstddef>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace geodual::io::detail {
namespace {

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

std::vector<std::uint8_t> encode_png_rgb(const std::vector<std::uint8_t>& rgb, int width, int height) {
  constexpr int kChannels = 3;
  if (width <= 0 || height <= 0 ||
      rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * kChannels) {
    throw Error("preview: internal error: pixel buffer does not match the picture size");
  }
  std::vector<std::uint8_t> png;
  if (stbi_write_png_to_func(append_bytes, &png, width, height, kChannels, rgb.data(), width * kChannels) == 0) {
    throw Error("preview: PNG encoding failed (out of memory?)");
  }
  return png;
}

}  // namespace geodual::io::detail
