#pragma once
// A triangle mesh prepared for exact geodesics: everything window propagation
// needs that depends on the mesh alone (the propagation mesh in locality
// order, edge lengths, pseudo-sources, the topology every GeodesicField
// exposes), built once and shared by every field and diagram computed on it,
// as geometry-central's HeatMethodDistanceSolver and libigl's *_precompute
// keep theirs.
//
//   const geodual::voronoi::GeodesicSurface surface(mesh);  // mesh must outlive it
//   auto a = geodual::voronoi::compute_voronoi(surface, sites);
//   auto b = geodual::voronoi::compute_voronoi(surface, moved_sites);  // no setup again

#include "geodual/mesh/triangle_mesh.hpp"

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

namespace geodual::voronoi {

namespace detail {
struct PreparedSurface;
}

/// The surface's edges, in the mesh's numbering of vertices and faces. An
/// edge has at most two faces: a boundary edge, or an edge of three or more
/// faces, is split into one edge per face.
struct SurfaceTopology {
  /// Per edge, its faces: [0], which every edge has, on the y > 0 side of
  /// the edge's frame (see edge_vertices); [1] on the other, -1 where absent
  /// (boundary, non-manifold, or degenerate neighbour).
  std::vector<std::array<Index, 2>> edge_faces;
  std::vector<double> edge_length;
  /// Per face, its edges: edge k joins corners k and (k + 1) mod 3; all -1
  /// for faces that take no part (a repeated vertex index).
  std::vector<std::array<Index, 3>> face_edges;

  /// The edge's end vertices, v0 then v1: its frame runs from v0 to v1 as
  /// its face [0] runs along it (corners k and k + 1 of that face, whose
  /// edge k it is). Read from `mesh`, the surface's, rather than stored.
  std::array<Index, 2> edge_vertices(const TriangleMesh& mesh, Index edge) const {
    const Index face = edge_faces[static_cast<std::size_t>(edge)][0];
    const int k = side_of(face, edge);
    return {mesh.faces(face, k), mesh.faces(face, (k + 1) % 3)};
  }
  /// Which edge k (0, 1, 2) of `face` `edge` is; \pre it is one of them.
  int side_of(Index face, Index edge) const {
    const std::array<Index, 3>& sides = face_edges[static_cast<std::size_t>(face)];
    return sides[0] == edge ? 0 : sides[1] == edge ? 1 : 2;
  }
};

/// Immutable once built, so fields may be computed on it from several threads
/// at once. Cheap to copy (the copies share the prepared data).
class GeodesicSurface {
 public:
  /// \pre `mesh` outlives the surface and stays unchanged: it is referred
  /// to, not copied. Faces must index existing vertices.
  explicit GeodesicSurface(const TriangleMesh& mesh);

  const TriangleMesh& mesh() const { return *mesh_; }
  /// Shared with (and kept alive by) every field computed on the surface.
  const std::shared_ptr<const SurfaceTopology>& topology() const { return topology_; }
  /// Bytes held by the prepared data, the topology included.
  std::size_t memory_bytes() const;
  /// Seconds the preparation took.
  double preparation_seconds() const { return preparation_seconds_; }

  /// The engine's view (voronoi/src/prepared_surface.hpp).
  const detail::PreparedSurface& prepared() const { return *prepared_; }

 private:
  const TriangleMesh* mesh_;
  std::shared_ptr<const detail::PreparedSurface> prepared_;
  std::shared_ptr<const SurfaceTopology> topology_;
  double preparation_seconds_ = 0;
};

}  // namespace geodual::voronoi
