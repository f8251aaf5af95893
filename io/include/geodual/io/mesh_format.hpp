#pragma once

#include <filesystem>
#include <string_view>

namespace geodual::io {

enum class MeshFormat { obj, ply, off, stl, gltf, glb };

/// The format a path's extension names (case-insensitive); throws
/// geodual::Error naming the path for an unknown or missing extension.
MeshFormat format_from_extension(const std::filesystem::path& path);

std::string_view format_name(MeshFormat format);

}  // namespace geodual::io
