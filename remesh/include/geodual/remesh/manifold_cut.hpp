#pragma once
// Scans come with non-manifold edges (three or more faces) and pinch vertices
// (several fans of faces meeting at one point). A remesh can only be a
// 2-manifold, so the remesher first cuts the input apart there, as CGAL's
// duplicate_non_manifold_vertices does for vertices: every vertex gets one
// copy per fan of faces joined around it. Faces stay joined across an edge
// with two faces; at a non-manifold edge, in pairs that continue each other
// (opposite directions along it, most nearly coplanar first, the piece kept
// orientable), and the faces left over get a boundary there. Face indices
// and positions stay the same (so face-and-barycentric sites keep their
// meaning).
// Before the cut, duplicate faces (a CAD soup's second copy of a triangle)
// are disabled, so that they neither cut the surface apart nor count twice.

#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace geodual::remesh {

struct ManifoldCutOptions {
  /// A face whose corners are those of an earlier face, in either
  /// orientation, adds no surface: it is disabled (corners set to the first)
  /// and the first one kept. Corners count as the same when they are the
  /// same vertex or vertices at exactly the same position (an unwelded soup);
  /// the vertices themselves are not welded, so pieces that merely touch stay
  /// apart.
  bool disable_duplicate_faces = true;
  /// Connected pieces (after the cut) with fewer faces than this, and at most
  /// max_scrap_area_share of the surface's area, are scraps below any
  /// remesh's resolution (a flap of two faces glued back to back, a lone
  /// triangle, a few faces left as a star of flaps where pinch vertices were
  /// cut; a remesh puts at least 4 sites on every piece): their faces are
  /// disabled (all three corners set to the first), so that every later
  /// stage ignores them. Scraps are never the whole surface: if every piece
  /// is one, none is disabled. 0 keeps everything. (With 4, ogre's four-face
  /// star got no valid dual at any site count.)
  Index min_component_faces = 8;
  double max_scrap_area_share = 1e-3;
};

struct ManifoldCut {
  TriangleMesh mesh;                     ///< same faces, vertices split per fan
  std::vector<Index> original_vertex;    ///< per vertex of `mesh`, the input vertex it copies
  std::int64_t vertices_split = 0;       ///< input vertices that got more than one copy
  std::int64_t faces_disabled = 0;       ///< faces of scraps and duplicates (see ManifoldCutOptions)
  std::int64_t duplicates_disabled = 0;  ///< of faces_disabled, the copies of an earlier face
  /// Per face: the earlier face it copies (and was disabled for), -1 for the
  /// others; empty when duplicates are kept.
  std::vector<Index> copy_of;
};

/// Faces with a repeated vertex index keep their indices and join no fan.
ManifoldCut cut_to_manifold(const TriangleMesh& mesh, const ManifoldCutOptions& options = {});
/// The same, and the topology of the cut's mesh in `topology`: the input's,
/// built for the cut, where the cut changed nothing (no vertex split, no
/// scrap), so that a remesh builds it once.
ManifoldCut cut_to_manifold(const TriangleMesh& mesh, const ManifoldCutOptions& options, MeshTopology& topology);

/// Points of the input as points of the cut surface: a vertex becomes the
/// corner of the first face of `cut.mesh` that takes part and has a copy of
/// it there (the cut may have split the vertex or disabled its faces); face
/// points, and vertices with no such face, are kept as they are.
std::vector<SurfacePoint> points_on_cut(const ManifoldCut& cut, std::vector<SurfacePoint> points);

/// Edges of the input (vertex pairs, `num_input_vertices` vertices) on the
/// cut: every pair of copies of their ends (those that are edges of
/// cut.mesh are the edge's copies).
std::vector<std::array<Index, 2>> edges_on_cut(const ManifoldCut& cut, Index num_input_vertices,
                                               std::span<const std::array<Index, 2>> edges);

}  // namespace geodual::remesh
