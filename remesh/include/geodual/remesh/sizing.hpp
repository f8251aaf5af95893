#pragma once
// Sizing: the site count (the remesh's vertex count) that gives a remesh of
// a target edge length or face count on `surface`, the surface remeshed (the
// input cut to a manifold, ManifoldCut::mesh). Faces with a repeated corner
// take no part. The count is rounded to the nearest integer, at least 1.

#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/remesh_surface.hpp"

#include <cstdint>

namespace geodual::remesh {

/// The most sites a sizing may ask for (each costs memory in every stage).
inline constexpr std::int64_t max_sized_sites = 100'000'000;

/// What the sizing reads off the surface.
struct SizingMeasures {
  double area = 0;                        ///< total face area
  double boundary_length = 0;             ///< total length of the boundary edges
  std::int64_t euler_characteristic = 0;  ///< summed over the connected pieces
};

SizingMeasures sizing_measures(const TriangleMesh& surface);
SizingMeasures sizing_measures(const RemeshSurface& surface);

/// Sites for near-equilateral triangles of side `edge_length`.
/// \throw UsageError unless edge_length is finite and > 0, or when the count
/// would be above max_sized_sites.
std::int64_t sites_for_edge_length(const TriangleMesh& surface, double edge_length);
std::int64_t sites_for_edge_length(const RemeshSurface& surface, double edge_length);

/// Sites for a remesh of about `faces` near-equilateral triangles.
/// \throw UsageError unless 1 <= faces, or when the count would be above
/// max_sized_sites.
std::int64_t sites_for_faces(const TriangleMesh& surface, std::int64_t faces);
std::int64_t sites_for_faces(const RemeshSurface& surface, std::int64_t faces);

}  // namespace geodual::remesh
