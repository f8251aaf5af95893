#pragma once
// Internal: one reader per format, each parsing a whole file already in memory.
// `name` is the file's path, used in every error message (and, for .gltf, to
// resolve relative external buffers). Each returns the mesh exactly as stored
// and fills the parts of ReadInfo it knows.

#include "geodual/io/read_mesh.hpp"

#include <cstddef>
#include <filesystem>
#include <span>

namespace geodual::io::detail {

LoadedMesh read_ply(std::span<const std::byte> data, const std::filesystem::path& name);
LoadedMesh read_obj(std::span<const std::byte> data, const std::filesystem::path& name);
LoadedMesh read_off(std::span<const std::byte> data, const std::filesystem::path& name);
LoadedMesh read_stl(std::span<const std::byte> data, const std::filesystem::path& name);
/// `binary`: GLB container; otherwise JSON glTF.
LoadedMesh read_gltf(std::span<const std::byte> data, bool binary, const std::filesystem::path& name);

}  // namespace geodual::io::detail
