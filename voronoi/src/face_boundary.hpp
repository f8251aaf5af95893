#pragma once
// Cell boundaries inside single faces: where the nearest site changes along
// each mesh edge, and, inside each face crossed by a boundary, the bisector
// pieces and Voronoi vertices that join those crossings. The pieces of all
// faces form one graph that voronoi_diagram.cpp chains into arcs.
//
// Built for deterministic parallel extraction: the crossings of a mesh edge
// are a pure function of the edge, and a face is traced into a graph of its
// own chunk (node references to edge crossings kept symbolic), so chunks can
// be traced on any thread and merged in face order.

#include "axis_nearest_site.hpp"
#include "cell_moments.hpp"
#include "face_distance.hpp"
#include "plane_nearest_site.hpp"

#include "geodual/mesh/detail/index_hash_map.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_field.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace geodual::voronoi::detail {

/// A point where boundary pieces meet: a crossing of a mesh edge (shared by
/// the faces on both sides), a crossing of an edge between the parts of a
/// refined face, or a Voronoi vertex.
struct BoundaryNode {
  enum class Kind { mesh_edge_crossing, inner_crossing, voronoi_vertex };
  Kind kind = Kind::mesh_edge_crossing;
  SurfacePoint location;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double distance = 0;
  /// Voronoi vertices only: their sites in counter-clockwise order are
  /// vertex_sites[site_begin .. site_begin + degree).
  Index site_begin = 0;
  int degree = 0;
};

/// In a chunk's graph, a piece's `from` or `to` that names a mesh-edge
/// crossing (an index into EdgeCrossingStore::crossings), not a node of the
/// chunk: such references are negative.
constexpr Index edge_crossing_reference(Index crossing) { return -2 - crossing; }
constexpr Index crossing_of_reference(Index reference) { return -2 - reference; }

/// A piece of bisector inside one face, from node `from` to node `to`, with
/// `left`'s cell on its left. Its polyline between the two nodes is
/// points[point_begin .. point_end).
struct BoundaryPiece {
  Index from = -1, to = -1;
  Index left = -1, right = -1;
  Index point_begin = 0, point_end = 0;
  double length = 0;
};

struct BoundaryGraph {
  std::vector<BoundaryNode> nodes;
  std::vector<Index> vertex_sites;
  std::vector<BoundaryPiece> pieces;
  std::vector<Eigen::Vector3d> points;
  std::vector<SurfacePoint> point_locations;
};

/// Where the nearest site changes along a mesh edge, in the edge's frame
/// (x from its end v0); `from` is the site on the side of smaller x.
struct EdgeCrossing {
  double x = 0;
  double distance = 0;  ///< to both sites
  Index from = -1, to = -1;
};

/// The graph node of a crossing of `edge`: located in the edge's first face.
BoundaryNode edge_crossing_node(const TriangleMesh& mesh, const GeodesicField& field, Index edge,
                                const EdgeCrossing& crossing);

/// The crossings of the mesh edges computed so far, each edge's contiguous.
/// Only the edges with crossings are keyed (by hashing): cell boundaries
/// cross edges all over the numbering, so per-edge arrays would be resident
/// whole while holding a few entries per thousand edges.
class EdgeCrossingStore {
 public:
  std::vector<EdgeCrossing> crossings;

  explicit EdgeCrossingStore(std::size_t num_edges) : computed_(num_edges, false) {}
  bool computed(Index edge) const { return computed_[static_cast<std::size_t>(edge)]; }
  /// Records that the crossings of `edge` are crossings[first .. first + n).
  void set(Index edge, Index first, Index n) {
    computed_[static_cast<std::size_t>(edge)] = true;
    if (n > 0) ranges_.insert(edge, {first, n});
  }
  /// The edge's crossings; \pre computed(edge).
  std::span<const EdgeCrossing> of(Index edge) const {
    const Range* range = ranges_.find(edge);
    if (range == nullptr) return {};
    return {crossings.data() + range->first, static_cast<std::size_t>(range->count)};
  }

 private:
  struct Range {
    Index first = 0, count = 0;
  };
  std::vector<bool> computed_;
  IndexHashMap<Range> ranges_;
};

/// One cell piece's area and integrals, added to its site's sums.
struct CellContribution {
  Index site = -1;
  double area = 0;
  CellIntegrals integrals;
};

/// What tracing a run of faces adds: a graph whose nodes are the faces' own
/// (references to edge crossings are edge_crossing_reference()), the cell
/// contributions in face order, and statistics.
struct TracedChunk {
  /// A face whose crossings the tracer used, and the end of its nodes.
  struct Face {
    Index face = -1;
    Index node_end = 0;
  };
  BoundaryGraph graph;
  std::vector<Face> faces;
  std::vector<CellContribution> contributions;
  VoronoiStats stats;

  void clear();
};

/// Traces the cell boundaries face by face. Not thread-safe; one per thread.
class FaceBoundaryTracer {
 public:
  /// `crossings` must hold every edge of the faces traced; `site_normals`
  /// (from site_normals()) serve the cell integrals.
  FaceBoundaryTracer(const TriangleMesh& mesh, const GeodesicField& field, const VoronoiOptions& options,
                     const EdgeCrossingStore& crossings, std::span<const Eigen::Vector3d> site_normals);

  /// True if `face` may hold a boundary: the engine marked it valid, its
  /// corners have different nearest sites, or a site lies in it.
  bool may_hold_boundary(Index face) const;
  /// Appends the crossings of a mesh edge, ordered along it, and their nodes.
  void find_edge_crossings(Index edge, std::vector<EdgeCrossing>& crossings);
  /// Adds the face's boundary pieces and Voronoi vertices to `out`'s graph
  /// and its area and integrals, split among the cells, to its contributions.
  void trace_face(Index face, TracedChunk& out);
  /// Adds a face inside the cell of `site` to `out`'s contributions.
  void add_inner_face(Index face, Index site, TracedChunk& out);

 private:
  struct Crossing {
    Eigen::Vector2d point;
    Index from = -1, to = -1;
    Index node = -1;
  };
  struct Side {
    Eigen::Vector2d start, end;
    Index start_site = -1, end_site = -1;
    Index crossing_begin = 0, crossing_end = 0;  ///< into crossings_, ordered from start to end
    std::array<Index, 2> halves{-1, -1};
    Eigen::Vector2d split = Eigen::Vector2d::Zero();  ///< where the halves meet, once split
  };
  struct SideUse {
    Index side = -1;
    bool reversed = false;
  };
  struct SubTriangle {
    std::array<Eigen::Vector2d, 3> corner;
    std::array<Index, 3> site;    ///< nearest site at each corner
    std::array<SideUse, 3> side;  ///< side k runs from corner k to corner k + 1
  };
  /// A crossing met walking a sub-triangle's boundary counter-clockwise, with
  /// its orientation along the walk, and the corner it comes after.
  struct SiteChange {
    double t = 0;
    Index from = -1, to = -1;
  };
  struct CycleCrossing {
    Crossing crossing;
    int after_corner = 0;
  };

  void trace(const SubTriangle& triangle, int depth);
  void subdivide(const SubTriangle& triangle, int depth);
  void collect_cycle(const SubTriangle& triangle);
  bool holds_island(const SubTriangle& triangle) const;
  /// The part of a side from its corner `which` (0: start, 1: end as used) to
  /// its split point (its midpoint, unless a crossing lies there).
  SideUse half_of(const SideUse& use, int which);
  Index midpoint_site(const SideUse& use);
  /// The point where a side is split into its halves (half_of).
  Eigen::Vector2d split_point(const SideUse& use);
  Index inner_side(const Eigen::Vector2d& start, const Eigen::Vector2d& end, Index start_site, Index end_site);
  Index add_node(const Eigen::Vector2d& p, BoundaryNode::Kind kind);
  Eigen::Vector3d to_space(const Eigen::Vector2d& p) const;
  /// Appends to changes_ every change of nearest site along p + t (q - p)
  /// for t from t0 (where site0 is nearest) to t1 (site1), in order.
  /// `nearest_site(x)` answers envelope.nearest_site(x) (from an index).
  template <class NearestSite>
  void find_site_changes(const ConeEnvelope& envelope, const NearestSite& nearest_site, const Eigen::Vector2d& p,
                         const Eigen::Vector2d& q, double t0, double t1, Index site0, Index site1);
  /// envelope_.nearest_site(p), from face_index_ when the face holds many cones.
  Index nearest_in_face(const Eigen::Vector2d& p) const {
    return face_indexed_ ? face_index_.nearest_site(p) : envelope_.nearest_site(p);
  }
  /// Removes from changes_ the pairs A -> B -> A that enclose no length.
  void drop_zero_width_stretches();
  /// The u in [0, 1] where sites `from` and `to` are equally far at
  /// a + u (b - a), given g = d_from - d_to at a and b (of opposite signs).
  static double equal_distance_parameter(const ConeEnvelope& envelope, const Eigen::Vector2d& a,
                                         const Eigen::Vector2d& b, Index from, Index to, double g_a, double g_b);
  /// Appends the polyline strictly between p and q that follows the bisector of
  /// `left` and `right` within the tolerance; returns its length.
  double trace_bisector(const Eigen::Vector2d& p, const Eigen::Vector2d& q, Index left, Index right,
                        const SubTriangle& triangle, int depth);
  /// Resolves a sub-triangle whose boundary it can explain: caps (a site
  /// entered and left again, cut off by one arc) and at most one Voronoi
  /// vertex. False, with nothing added, if it needs refining.
  bool resolve(const SubTriangle& triangle, bool at_limit);
  // resolve's steps, on the crossings of the sub-triangle's boundary (cycle_):
  /// 1. Caps peeled off (caps_), the rest in remaining_.
  void peel_caps();
  /// 2. Whether the rest is empty or one Voronoi vertex (more than three
  /// sites there only at the refinement limit).
  bool at_most_one_vertex(bool at_limit) const;
  /// 3. The pieces traced into scratch space (piece_points_), and the
  /// vertex solved for; false where the sub-triangle needs refining.
  bool trace_pieces(const SubTriangle& triangle, bool at_limit, Eigen::Vector2d& vertex, double& spread);
  /// 4. The vertex and the pieces added to the graph.
  void commit_pieces(const Eigen::Vector2d& vertex, double spread);
  /// 5. Every site's part of the sub-triangle given to its cell.
  void add_parts(const SubTriangle& triangle, const Eigen::Vector2d& vertex);
  /// Piece `piece` of piece_points_.
  std::span<const Eigen::Vector2d> piece_span(std::size_t piece) const;
  bool inside(const SubTriangle& triangle, const Eigen::Vector2d& p) const;
  /// Gives a site's part of a sub-triangle (a polygon) to its cell.
  void add_part(Index site, std::span<const Eigen::Vector2d> polygon);
  /// Adds the piece from node `from` at p to node `to` at q with the 2D
  /// polyline `line` between them.
  void commit_piece(Index from, Index to, Index left, Index right, const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                    std::span<const Eigen::Vector2d> line);
  /// The point where the sites are equally far (Gauss-Newton from `start`);
  /// `spread` receives the largest difference of their distances there.
  Eigen::Vector2d solve_vertex(std::span<const Index> sites, const SubTriangle& triangle, const Eigen::Vector2d& start,
                               double& spread);

  const TriangleMesh& mesh_;
  const GeodesicField& field_;
  const VoronoiOptions& options_;
  const EdgeCrossingStore& store_;
  CellMoments moments_;
  double tolerance_ = 0;         ///< polyline deviation allowed
  double vertex_tolerance_ = 0;  ///< spread of site distances accepted at a Voronoi vertex

  // Where the face being traced goes.
  BoundaryGraph* graph_ = nullptr;
  TracedChunk* out_ = nullptr;

  ConeEnvelope edge_envelope_;
  AxisNearestSite edge_index_;  ///< edge_envelope_'s, when it holds many cones
  ConeEnvelope face_scratch_;
  std::vector<double> samples_;
  std::vector<SiteChange> changes_;

  // The face being traced.
  Index face_ = -1;
  FaceLayout layout_;
  ConeEnvelope envelope_;
  PlaneNearestSite face_index_;  ///< envelope_'s, when it holds many cones
  bool face_indexed_ = false;
  struct FaceSite {
    Eigen::Vector2d point;
    Index site = -1;
  };
  std::vector<FaceSite> face_sites_;  ///< the sites in the face, by x
  std::vector<Side> sides_;
  std::vector<Crossing> crossings_;
  std::vector<CycleCrossing> cycle_;           ///< scratch: the boundary walk of one sub-triangle
  std::vector<Eigen::Vector2d> piece_points_;  ///< scratch: polylines of the pieces being traced
  std::vector<Index> piece_offsets_;
  std::vector<Eigen::Vector2d> polygon_;    ///< scratch: one cell's part of a sub-triangle
  std::vector<Index> remaining_;            ///< scratch: crossings not explained by caps
  std::vector<std::array<Index, 2>> caps_;  ///< scratch: (into, out of) crossing pairs
  std::vector<Index> star_sites_;           ///< scratch: the sites of a Voronoi vertex
  struct VertexTerm {
    double distance = 0;
    Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  };
  std::vector<VertexTerm> at_x_, trial_;    ///< scratch: solve_vertex's site distances
  std::vector<std::array<Index, 3>> jump_;  ///< scratch: per crossing, the inside path from it
  std::vector<std::uint8_t> visited_;
  int max_depth_ = 0;  ///< how many times the face's sub-triangles may be split
  bool trace_valid_ = true;
  bool face_refined_ = false;
};

}  // namespace geodual::voronoi::detail
