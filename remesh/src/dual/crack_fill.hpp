#pragma once
// The last resort of the weld along sharp features (feature_cut.hpp): a
// crack that the site moves did not close is a small hole of the welded
// remesh, bounded by its own vertices, and is closed with triangles on those
// vertices. The remesh stays a mesh of the sites; only the connectivity at the
// crack is not the dual's.

#include "geodual/mesh/triangle_mesh.hpp"

#include <cstdint>
#include <optional>
#include <span>

namespace geodual::remesh {

struct CrackFill {
  std::int64_t holes = 0;      ///< cracks closed
  std::int64_t triangles = 0;  ///< triangles added
};

/// Closes every boundary loop of `mesh` that passes through one of
/// `crack_vertices` and has at most `max_edges` edges: the loop, a simple
/// cycle, is triangulated by ear clipping, the ear whose smallest angle is
/// largest first, never with an edge or a triangle the mesh already has, and
/// oriented as its neighbours. Returns what was added, or nothing (and `mesh`
/// as it was) where some such loop is longer, not a simple cycle, or cannot
/// be closed so that every edge of the result has at most two triangles.
std::optional<CrackFill> close_cracks(TriangleMesh& mesh, std::span<const Index> crack_vertices, int max_edges = 8);

}  // namespace geodual::remesh
