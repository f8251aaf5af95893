#pragma once
// Writing meshes: GLB / glTF (positions, normals, indices), binary PLY (with
// optional per-vertex scalar properties), OBJ. Every write is atomic (see
// atomic_file.hpp).

#include "geodual/io/mesh_format.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/vertex_attributes.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

namespace geodual::io {

/// One scalar per vertex, written as a PLY vertex property of the matching type.
struct VertexProperty {
  std::string name;
  std::variant<std::vector<double>, std::vector<float>, std::vector<std::int32_t>> values;
};

/// Binary little-endian PLY: float64 x y z, then the vertex properties in the
/// order given (double, float, int32 -> PLY double, float, int), then faces as
/// `list uchar int vertex_indices`. Property names must be single printable
/// words, unique, not x/y/z, with one value per vertex; face indices must be
/// in range. Violations throw geodual::Error naming the path; nothing is written.
void write_ply(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::vector<VertexProperty>& vertex_properties = {});

/// Wavefront OBJ ("v x y z", "f a b c", 1-based). Coordinates are printed in
/// the shortest form that reads back as the same double (std::to_chars: at most
/// max_digits10 = 17 significant digits), so the round trip is exact.
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh);

/// Writes by extension (case-insensitive): .ply, .obj, .glb or .gltf (glTF: see
/// gltf.hpp for more); any other extension is a geodual::Error. The
/// attributes (one row per vertex, or empty) go where the format has room:
/// PLY every one, with the types they carry; OBJ the colours (`v x y z r g b`);
/// glTF COLOR_0 (converted to linear), NORMAL, and each scalar as `_NAME`.
void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh, const VertexAttributes& attributes = {});

}  // namespace geodual::io
