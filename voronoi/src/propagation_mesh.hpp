#pragma once
// The compact, intrinsic view of a triangle mesh that window propagation needs:
// edges with their (at most two) faces and lengths, vertex -> face adjacency,
// and which vertices are pseudo-sources. Built once per mesh; independent of
// the sites.

#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace geodual::voronoi::detail {

/// A face laid out in the plane for one of its edges: the edge runs from the
/// origin (corner k) along the x axis to (length, 0) (corner k + 1), and the
/// opposite corner k + 2 sits at `apex`, with apex.y() >= 0.
struct EdgeLayout {
  double length = 0;
  Eigen::Vector2d apex = Eigen::Vector2d::Zero();
};

/// The length of the edge between vertices a and b (the same either way round).
inline double edge_length(const TriangleMesh& mesh, Index a, Index b) {
  return (mesh.vertices.row(b) - mesh.vertices.row(a)).norm();
}

/// A face laid out for its edge k (see EdgeLayout), from its edge lengths.
/// Law of cosines for the apex's x; its height from the cancellation-free
/// area, which keeps needles and slivers accurate. (Computed where needed
/// rather than stored: a square root costs less than 8 bytes a face.)
inline EdgeLayout layout_on_edge(const std::array<double, 3>& length, int k) {
  EdgeLayout l;
  const double a = length[k];
  l.length = a;
  if (!(a > 0)) return l;
  const double next = length[(k + 1) % 3], prev = length[(k + 2) % 3];
  const double twice_area = twice_area_from_lengths(length[0], length[1], length[2]);
  l.apex = Eigen::Vector2d((a * a + prev * prev - next * next) / (2 * a), twice_area / a);
  return l;
}

/// What propagating a window through a face needs besides its edge lengths
/// (kept per edge): the face's edges and corners, and per edge which side of
/// it the face is on and whether the face runs along it against the edge's
/// direction.
struct FaceRecord {
  static constexpr std::uint32_t kSide1 = std::uint32_t{1} << 30;     ///< the face is edge_faces[e][1]
  static constexpr std::uint32_t kReversed = std::uint32_t{1} << 31;  ///< and runs from v1 to v0
  static constexpr std::uint32_t kEdgeMask = kSide1 - 1;
  static constexpr std::uint32_t kNoEdge = ~std::uint32_t{0};
  std::array<Index, 3> vertex{-1, -1, -1};
  /// Per local edge: the edge's index, with the kSide1 and kReversed flags
  /// in its two top bits (so the record is 24 bytes); kNoEdge for a face
  /// that takes no part.
  std::array<std::uint32_t, 3> edge_bits{kNoEdge, kNoEdge, kNoEdge};

  bool included() const { return edge_bits[0] != kNoEdge; }
  Index edge(int k) const { return static_cast<Index>(edge_bits[k] & kEdgeMask); }
  int side(int k) const { return (edge_bits[k] & kSide1) != 0 ? 1 : 0; }
  /// The face's coordinate along edge k runs against the edge's frame.
  bool flipped(int k) const { return (edge_bits[k] & kReversed) != 0; }
  /// The edge's end vertices in the order of the edge's frame (v0, v1).
  Index edge_start(int k) const { return flipped(k) ? vertex[(k + 1) % 3] : vertex[k]; }
  Index edge_end(int k) const { return flipped(k) ? vertex[k] : vertex[(k + 1) % 3]; }
};
static_assert(sizeof(FaceRecord) == 24);

/// Built from a mesh, it keeps no reference to it: the mesh may go once built.
/// Each fact is stored once: an edge's end vertices are read from the record
/// of its face [0].
struct PropagationMesh {
  PropagationMesh() = default;
  PropagationMesh(PropagationMesh&&) = default;
  PropagationMesh& operator=(PropagationMesh&&) = default;
  PropagationMesh(const PropagationMesh&) = delete;  // a copy's edge_lengths would view the original's
  PropagationMesh& operator=(const PropagationMesh&) = delete;

  /// Per face, the data propagation reads (see FaceRecord); faces with a
  /// repeated vertex index take no part and keep default records (edges -1).
  std::vector<FaceRecord> face_records;
  /// Per edge: the faces on its y > 0 side ([0]) and its y < 0 side ([1], or
  /// -1). The edge runs from v0 to v1 in the direction of face [0].
  std::vector<std::array<Index, 2>> edge_faces;
  /// Per edge: its length. A view of edge_length_storage, or of the array
  /// that took that storage over (moving a vector keeps its elements in
  /// place): a GeodesicSurface hands it to the topology its fields share.
  std::span<const double> edge_lengths;
  std::vector<double> edge_length_storage;

  /// Per vertex, one of its faces (-1: used by no face that takes part); the
  /// others follow by turning around the vertex (for_each_face_around).
  std::vector<Index> vertex_face;
  /// Per vertex, its other faces as offsets from vertex_face[v], the
  /// smallest (increasing; 0 ends the list), where they fit: up to
  /// kFanOffsets faces within kFanMaxOffset of it (valence 7 or less covers
  /// 99 % of a scan's vertices; faces are in locality order). kFanWalked in
  /// the first byte where they do not: those fans are walked (walk_fan).
  /// Half the memory of a vertex -> faces table, and read as fast.
  static constexpr int kFanOffsets = 6;
  static constexpr std::uint8_t kFanMaxOffset = 254;
  static constexpr std::uint8_t kFanWalked = 255;
  std::vector<std::array<std::uint8_t, kFanOffsets>> fan_offsets;
  /// (vertex, face), sorted: where several fans of faces meet at a vertex
  /// (a pinch, or boundary and non-manifold edges), a face of each fan
  /// after the one of vertex_face. Rare: a table of all the faces around
  /// every vertex would be the size of the face records' corners.
  std::vector<std::array<Index, 2>> extra_fans;

  /// Saddle (angle sum > 2 pi - tol), boundary or non-manifold vertices: paths
  /// may bend around them, so they emit windows once their distance is final.
  std::vector<std::uint8_t> is_pseudo_source;

  Index num_included_faces = 0;

  Index num_vertices() const { return static_cast<Index>(vertex_face.size()); }
  Index num_faces() const { return static_cast<Index>(face_records.size()); }
  Index num_edges() const { return static_cast<Index>(edge_faces.size()); }
  bool included(Index face) const { return face_records[face].included(); }

  /// The face's three edges (edge k joins corners k and k + 1); all -1 for a
  /// face that takes no part.
  std::array<Index, 3> face_edges(Index face) const {
    const FaceRecord& r = face_records[face];
    if (!r.included()) return {-1, -1, -1};
    return {r.edge(0), r.edge(1), r.edge(2)};
  }
  Index vertex(Index face, int corner) const { return face_records[face].vertex[corner]; }
  double edge_length(Index edge) const { return edge_lengths[edge]; }
  /// The lengths of the face's edges, by local edge.
  std::array<double, 3> face_lengths(const FaceRecord& face) const {
    return {edge_lengths[face.edge(0)], edge_lengths[face.edge(1)], edge_lengths[face.edge(2)]};
  }
  /// The local index (0, 1, 2) of `edge` in `face`, one of its faces.
  static int local_edge(const FaceRecord& face, Index edge) {
    return face.edge(0) == edge ? 0 : face.edge(1) == edge ? 1 : 2;
  }
  int local_edge(Index face, Index edge) const { return local_edge(face_records[face], edge); }
  /// End vertices v0, v1 of the edge's frame.
  std::array<Index, 2> edge_vertices(Index edge) const {
    const FaceRecord& face = face_records[edge_faces[edge][0]];
    const int k = local_edge(face, edge);
    return {face.vertex[k], face.vertex[(k + 1) % 3]};
  }
  /// True where face [1] runs along the edge from v1 to v0 (consistent
  /// orientation); false where it runs v0 -> v1 like face [0].
  bool edge_reversed_in_face1(Index edge) const {
    const Index face = edge_faces[edge][1];
    return face >= 0 && face_records[face].flipped(local_edge(face, edge));
  }

  /// Face `face` laid out for its local edge `k` using intrinsic edge lengths.
  EdgeLayout layout(Index face, int k) const { return layout_on_edge(face_lengths(face_records[face]), k); }
  /// Which side of edge e face `face` is on: 0 or 1.
  int side_of(Index edge, Index face) const { return edge_faces[edge][0] == face ? 0 : 1; }
  /// The corner of `face` at vertex v (which must be one of its corners).
  int corner_of(Index face, Index v) const {
    const FaceRecord& r = face_records[face];
    return r.vertex[0] == v ? 0 : r.vertex[1] == v ? 1 : 2;
  }

  /// The faces around vertex v that take part, into `faces`, in increasing
  /// order: propagation visits them in that order, and where distances tie
  /// exactly (sites co-circular about a vertex) the order decides which
  /// windows stay.
  void faces_around(Index v, std::vector<Index>& faces) const;

  /// Calls visit(face) for `start` and every face reached from it by turning
  /// around v across shared edges: one way until the fan closes or ends at a
  /// boundary edge, then the other way. (Each edge has at most two faces and
  /// each face one corner at v, so the walk is a path or a cycle.)
  template <class Visit>
  void walk_fan(Index v, Index start, Visit&& visit) const {
    visit(start);
    for (int direction = 0; direction < 2; ++direction) {
      Index face = start;
      const int corner = corner_of(face, v);
      // The two local edges at corner c are c (c -> c+1) and c+2 (c+2 -> c).
      int exit = direction == 0 ? corner : (corner + 2) % 3;
      for (;;) {
        const FaceRecord& record = face_records[face];
        const Index e = record.edge(exit);
        const int side = record.side(exit);
        const Index next = edge_faces[e][1 - side];
        if (next < 0) break;
        if (next == start) return;  // a closed fan
        visit(next);
        const int entry = local_edge(next, e);
        const int next_corner = corner_of(next, v);
        exit = entry == next_corner ? (next_corner + 2) % 3 : next_corner;
        face = next;
      }
    }
  }
};

PropagationMesh build_propagation_mesh(const TriangleMesh& mesh);

/// A whole face laid out in the plane: corner positions by corner index, in
/// the frame of one of its edges (see EdgeLayout); counter-clockwise.
struct FaceInPlane {
  std::array<Eigen::Vector2d, 3> corner;
};

inline FaceInPlane lay_out_face(const PropagationMesh& pm, Index face, int k) {
  const EdgeLayout l = pm.layout(face, k);
  FaceInPlane plane;
  plane.corner[k] = Eigen::Vector2d::Zero();
  plane.corner[(k + 1) % 3] = Eigen::Vector2d(l.length, 0);
  plane.corner[(k + 2) % 3] = l.apex;
  return plane;
}

/// Coordinates of q (given in `plane`) in the frame of the face's local edge
/// j: origin at corner j, x towards corner j + 1, the face on the y > 0 side.
inline Eigen::Vector2d to_local_edge_frame(const FaceInPlane& plane, int j, const Eigen::Vector2d& q) {
  const Eigen::Vector2d origin = plane.corner[j];
  Eigen::Vector2d u = plane.corner[(j + 1) % 3] - origin;
  const double n = u.norm();
  if (n > 0) u /= n;
  const Eigen::Vector2d r = q - origin;
  return {r.dot(u), u.x() * r.y() - u.y() * r.x()};
}

/// Position of a point given in a face's frame for its local edge k (see
/// EdgeLayout), expressed in the canonical frame of that edge.
inline Eigen::Vector2d face_frame_to_edge_frame(const PropagationMesh& pm, Index edge, int side,
                                                const Eigen::Vector2d& p) {
  const bool flip_x = side == 1 && pm.edge_reversed_in_face1(edge);
  const double x = flip_x ? pm.edge_length(edge) - p.x() : p.x();
  const double y = side == 0 ? p.y() : -p.y();
  return {x, y};
}

}  // namespace geodual::voronoi::detail
