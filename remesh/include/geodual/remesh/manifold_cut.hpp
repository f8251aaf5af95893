#pragma once
// Scans come with non-manifold edges (three or more faces) and pinch vertices
// (several fans of faces meeting at one point). A remesh can only be a
// 2-manifold, so the remesher first cuts the input apart there, as CGAL's
// duplicate_non_manifold_vertices does for vertices: every vertex gets one
// copy per fan of faces joined through edges with exactly two faces. Face
// indices and positions stay the same (so face-and-barycentric sites keep
// their meaning); a non-manifold edge becomes a boundary of each of its faces.

#include "geodual/triangle_mesh.hpp"

#include <cstdint>

namespace geodual::remesh {

struct ManifoldCut {
  TriangleMesh mesh;                    ///< same faces, vertices split per fan
  std::vector<Index> original_vertex;   ///< per vertex of `mesh`, the input vertex it copies
  std::int64_t vertices_split = 0;      ///< input vertices that got more than one copy
};

/// Faces with a repeated vertex index keep their indices and join no fan.
ManifoldCut cut_to_manifold(const TriangleMesh& mesh);

}  // namespace geodual::remesh
