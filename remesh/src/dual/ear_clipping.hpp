#pragma once
// A small polygon of mesh vertices cut into triangles ear by ear, the ear
// whose smallest angle is largest first: how the weld's cracks
// (crack_fill.hpp) and the dual's stretches along the boundary
// (boundary_triangles.hpp) are closed.

#include "geodual/mesh/triangle_mesh.hpp"

#include <array>
#include <functional>
#include <limits>
#include <vector>

namespace geodual::remesh::detail {

/// The triangles of `polygon` (vertex indices into `positions`, in the order
/// the triangles run), none closing a diagonal (a, b) for which
/// `is_edge(a, b)` holds, none with an angle of `min_angle` radians or less,
/// and none with a side longer than `max_edge`; empty where no such cut
/// exists. A polygon of three is its own triangle, checked the same way.
std::vector<std::array<Index, 3>> clip_ears(std::vector<Index> polygon, const VertexMatrix& positions,
                                            const std::function<bool(Index, Index)>& is_edge, double min_angle = 0,
                                            double max_edge = std::numeric_limits<double>::infinity());

}  // namespace geodual::remesh::detail
