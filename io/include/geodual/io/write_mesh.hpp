#pragma once
// Writing meshes: GLB / glTF (positions, normals, indices), binary PLY (with
// optional per-vertex scalar properties), OBJ. Every write is atomic (see
// atomic_file.hpp).

#include "geodual/io/mesh_format.hpp"
#include "geodual/triangle_mesh.hpp"

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

/// Binary little-endian PLY with float64 coordinates and int32 indices.
void write_ply(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::vector<VertexProperty>& vertex_properties = {});

/// Wavefront OBJ, coordinates printed with round-trip precision (max_digits10).
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh);

/// Writes by extension: .ply, .obj, .glb or .gltf (glTF: see gltf.hpp for more).
void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh);

}  // namespace geodual::io
