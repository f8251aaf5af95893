#pragma once
// Texture images as PNG or JPEG files (stb_image_write): the same image and
// format always give the same bytes. Files are written atomically.

#include "geodual/mesh/texture_image.hpp"

#include <cstddef>
#include <filesystem>
#include <string_view>
#include <vector>

namespace geodual::io {

enum class ImageFormat {
  png,   ///< lossless, RGB or RGBA
  jpeg,  ///< baseline JPEG at quality 90, RGB (an alpha channel is dropped)
};

/// "png" or "jpeg".
std::string_view image_format_name(ImageFormat format);
/// "image/png" or "image/jpeg".
std::string_view image_mime_type(ImageFormat format);
/// ".png" or ".jpg".
std::string_view image_extension(ImageFormat format);

/// The bytes of the file. \throw geodual::Error where the image is empty or
/// its texels do not match its size and channels (3 or 4).
std::vector<std::byte> encode_image(const TextureImage& image, ImageFormat format);

/// Writes encode_image's bytes to `path` atomically; errors name the path.
void write_image(const std::filesystem::path& path, const TextureImage& image, ImageFormat format);

}  // namespace geodual::io
