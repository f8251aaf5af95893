#pragma once
// Writing meshes: GLB / glTF (positions, normals, indices), binary PLY (with
// optional per-vertex scalar properties), OBJ. Every write is atomic (see
// atomic_file.hpp).

#include "geodual/io/mesh_format.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/vertex_attributes.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace geodual::io {

/// Binary little-endian PLY: float64 x y z, then the attributes as vertex
/// properties -- nx ny nz, red green blue [alpha], the scalars in order --
/// each of the type it carries (colours of a float type as float in [0, 1],
/// uint8 and uint16 scaled to their range; integer scalars rounded), then
/// faces as `list uchar int vertex_indices`. Scalar names must be single
/// printable words, unique, not taken by the coordinates, normals or colours
/// written; each attribute has one row per vertex; face indices must be in
/// range. Violations throw geodual::Error naming the path; nothing is written.
/// `texture_file` (empty: none) is named in a "comment TextureFile NAME" line,
/// as MeshLab reads a texture (with per-vertex texture_u, texture_v scalars).
void write_ply(const std::filesystem::path& path, const TriangleMesh& mesh, const VertexAttributes& attributes = {},
               const std::string& texture_file = {});

/// Why write_ply would refuse the names of `attributes` (e.g. "vertex property
/// 'x' is taken by the coordinates"), or an empty string: to check before
/// the work whose result is written.
std::string ply_attribute_problem(const VertexAttributes& attributes);

/// Wavefront OBJ ("v x y z", "f a b c", 1-based). Coordinates are printed in
/// the shortest form that reads back as the same double (std::to_chars: at most
/// max_digits10 = 17 significant digits), so the round trip is exact. With
/// colours (one row per vertex, RGB first), vertices are "v x y z r g b" (alpha is dropped).
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh, const ColorMatrix& colors = {});

/// What a textured OBJ adds: "mtllib LIBRARY" and "usemtl MATERIAL" before the
/// faces, a "vt u v" per vertex (OBJ's v points up: 1 minus glTF's), and faces
/// "f a/a b/b c/c".
struct ObjTexturing {
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> texcoords{};  ///< per vertex, glTF's (v down)
  std::string material_library{};                                         ///< the .mtl file's name, relative to the OBJ
  std::string material{};
};
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh, const ColorMatrix& colors,
               const ObjTexturing& texturing);

/// Writes by extension (case-insensitive): .ply, .obj, .glb or .gltf (glTF: see
/// gltf.hpp for more); any other extension is a geodual::Error. The
/// attributes (one row per vertex, or empty) go where the format has room:
/// PLY every one, with the types they carry; OBJ the colours (`v x y z r g b`);
/// glTF COLOR_0 (converted to linear), NORMAL, and each scalar as `_NAME`.
void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh, const VertexAttributes& attributes = {});

}  // namespace geodual::io
