#pragma once
// Reading meshes exactly as the file stores them: vertex order and count kept,
// polygons triangulated in their best-fit plane, nothing cleaned. Every failure is a geodual::Error
// whose message names the file and the problem.

#include "geodual/io/mesh_format.hpp"
#include "geodual/mesh/texture_image.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/vertex_attributes.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace geodual::io {

/// What the reader saw besides the mesh itself.
struct ReadInfo {
  MeshFormat format = MeshFormat::ply;
  /// PLY: the format line's encoding and the x type, e.g. "binary_little_endian
  /// float32", "ascii float64"; STL: "binary" or "ascii"; OBJ, OFF: "ascii".
  std::string encoding;
  std::uintmax_t file_bytes = 0;
  std::int64_t polygons_split = 0;  ///< polygons with more than 3 corners split into triangles
  std::int64_t welded_corners = 0;  ///< STL: triangle corners merged into shared vertices
  std::vector<std::string> notes;   ///< human-readable remarks: welding, what was ignored
  /// Files read besides the mesh file itself: an OBJ's material libraries and
  /// images (glTF's external buffers and images are not listed), so that no
  /// output overwrites them.
  std::vector<std::filesystem::path> companion_files;
};

struct LoadedMesh {
  TriangleMesh mesh;
  /// What the file stores per vertex besides positions (colours, normals,
  /// other scalars); each member empty when the file has none.
  VertexAttributes attributes;
  /// The base colour texture (glTF's baseColorTexture with TEXCOORD_0) at full
  /// resolution, for baking; empty when the file has none.
  SurfaceTexture texture;
  ReadInfo info;
};

/// Reads OBJ, PLY, OFF, STL, glTF or GLB, chosen by the file's extension
/// (case-insensitive). The file is read whole with one read, then decoded.
/// Every mesh read has at least one triangle, finite coordinates and vertex
/// indices in range; a file that breaks any of that is an error, whose
/// message starts with the path and names the line (text formats) or the
/// element and its index (binary ones).
LoadedMesh read_mesh(const std::filesystem::path& path);

/// Reads from a buffer already in memory. `name` is used in error messages and,
/// for .gltf, to resolve relative external buffers (empty: none may be external).
LoadedMesh read_mesh_from_memory(std::span<const std::byte> data, MeshFormat format, const std::filesystem::path& name);

}  // namespace geodual::io
