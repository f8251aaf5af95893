#pragma once
// The connectivity of a triangle mesh, built once and shared by the stages:
// edges, the faces of each edge and the edges of each face, boundary flags,
// vertex fans, components and boundary loops.

#include "geodual/mesh/triangle_mesh.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace geodual {

/// Element counts of one connected component.
struct ComponentCounts {
  std::int64_t vertices = 0;  ///< referenced by its faces
  std::int64_t edges = 0;
  std::int64_t faces = 0;
  std::int64_t boundary_loops = 0;
  std::int64_t euler_characteristic() const { return vertices - edges + faces; }
};

/// Faces with a repeated vertex index take no part: they have no edges, no
/// fans and no component (-1 everywhere). Numbering is deterministic: edges
/// by (smaller, larger) vertex, everything else in the order of first use.
struct MeshTopology {
  /// Per edge: its end vertices, [0] < [1]; edges sorted by that pair.
  std::vector<std::array<Index, 2>> edge_vertices;
  /// Per edge: its faces, in increasing order (CSR: edge e's faces are
  /// edge_face_list[edge_face_begin[e] .. edge_face_begin[e + 1])). One
  /// face: a boundary edge; two: interior; three or more: non-manifold.
  std::vector<Index> edge_face_begin;
  std::vector<Index> edge_face_list;
  /// Per face: edge k joins corners k and k + 1.
  std::vector<std::array<Index, 3>> face_edges;
  /// Per vertex: an end of a boundary edge.
  std::vector<std::uint8_t> vertex_on_boundary;

  /// Per corner (3 * face + k): its fan. The corners at one vertex are in one
  /// fan when their faces are joined, around the vertex, across edges with
  /// exactly two faces (a manifold vertex has one fan; a pinch vertex or a
  /// vertex of a non-manifold edge has several). Fans are numbered in the
  /// order of their first corner.
  std::vector<Index> corner_fan;
  /// Per fan: its vertex.
  std::vector<Index> fan_vertex;

  /// Components: faces joined through shared vertices, numbered in the
  /// order of their first face. Per face and per vertex (-1: unreferenced).
  std::vector<Index> face_component;
  std::vector<Index> vertex_component;
  std::vector<ComponentCounts> components;

  /// Boundary loops: the groups of boundary edges joined at shared vertices
  /// (loops touching at a pinch vertex count once, as in MeshReport),
  /// numbered in edge order. Per edge, -1 for an edge that is not boundary.
  std::vector<Index> edge_boundary_loop;
  Index num_boundary_loops = 0;

  Index num_edges() const { return static_cast<Index>(edge_vertices.size()); }
  Index num_fans() const { return static_cast<Index>(fan_vertex.size()); }
  Index num_components() const { return static_cast<Index>(components.size()); }
  std::span<const Index> edge_faces(Index edge) const {
    return {edge_face_list.data() + edge_face_begin[edge], edge_face_list.data() + edge_face_begin[edge + 1]};
  }
  bool is_boundary_edge(Index edge) const { return edge_face_begin[edge + 1] - edge_face_begin[edge] == 1; }
  bool is_manifold_edge(Index edge) const { return edge_face_begin[edge + 1] - edge_face_begin[edge] <= 2; }
  /// The edge joining vertices a and b (either order), or -1.
  Index find_edge(Index a, Index b) const;
};

/// Linear time and memory. \throw Error if a face refers to a vertex that
/// does not exist.
MeshTopology build_mesh_topology(const TriangleMesh& mesh);

}  // namespace geodual
