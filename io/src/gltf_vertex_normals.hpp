#pragma once
// Internal: per-vertex normals for glTF output.

#include "geodual/mesh/triangle_mesh.hpp"

#include <vector>

namespace geodual::io::detail::gltf {

/// Area-weighted vertex normals (the sum of the incident triangles' cross
/// products, normalized) as x, y, z float triples of unit length; (0, 0, 1)
/// for vertices whose incident triangles have no area (or that have none).
/// Every face index must be a valid vertex index.
std::vector<float> area_weighted_vertex_normals(const VertexMatrix& vertices, const FaceMatrix& faces);

}  // namespace geodual::io::detail::gltf
