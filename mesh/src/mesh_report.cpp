#include "geodual/mesh/mesh_report.hpp"
#include "geodual/mesh/face_area.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/random.hpp"
#include "geodual/mesh/union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <span>
#include <string>
#include <utility>
#include <vector>

// The analysis works vertex by vertex on the vertex -> corner incidence
// (compressed rows, built by a counting sort): at each vertex v, the faces
// around it list their edges (v, w); sorting that handful of entries by w
// groups the uses of every edge. Each undirected edge is classified once, at
// its smaller endpoint, and the faces around v are grouped into fans there as
// well. No per-edge map and no global edge sort: time and memory are linear.

namespace geodual {
namespace {

using Corner = std::uint32_t;  // 3 * face + k: corner k of a face

/// For every vertex, the corners (face corners) that sit on it.
struct VertexCorners {
  std::vector<Corner> first;    ///< V + 1 offsets into `corners`
  std::vector<Corner> corners;  ///< grouped by vertex, ascending corner id within a vertex

  std::size_t degree(Index v) const { return first[v + 1] - first[v]; }
};

void check_indices(const TriangleMesh& mesh) {
  const Index n = mesh.num_vertices();
  const Index* index = mesh.faces.data();
  const auto count = static_cast<std::size_t>(mesh.faces.size());
  for (std::size_t i = 0; i < count; ++i) {
    if (index[i] < 0 || index[i] >= n) {
      throw Error("analyze_mesh: face " + std::to_string(i / 3) + " refers to vertex " + std::to_string(index[i]) +
                  ", but the mesh has " + std::to_string(n) + " vertices");
    }
  }
  // Corners are numbered in 32 bits, and positions around a vertex in 31.
  if (count > std::size_t{std::numeric_limits<Index>::max()}) {
    throw Error("analyze_mesh: " + std::to_string(mesh.num_faces()) +
                " faces are more than the analysis supports (715 million)");
  }
}

VertexCorners build_vertex_corners(const TriangleMesh& mesh) {
  VertexCorners result;
  const auto num_vertices = static_cast<std::size_t>(mesh.num_vertices());
  const Index* index = mesh.faces.data();
  const auto count = static_cast<Corner>(mesh.faces.size());
  result.first.assign(num_vertices + 1, 0);
  for (Corner c = 0; c < count; ++c) ++result.first[index[c] + 1];
  std::partial_sum(result.first.begin(), result.first.end(), result.first.begin());
  result.corners.resize(count);
  std::vector<Corner> fill(result.first.begin(), result.first.end() - 1);
  for (Corner c = 0; c < count; ++c) result.corners[fill[index[c]]++] = c;
  return result;
}

/// One use of an edge (v, w) by the face at one of the corners around v,
/// packed into an integer so that sorting groups the uses by neighbor w.
class EdgeUse {
 public:
  EdgeUse(Index neighbor, std::uint32_t slot, bool outgoing)
      : bits_(std::uint64_t{static_cast<std::uint32_t>(neighbor)} << 32 | std::uint64_t{slot} << 1 |
              std::uint64_t{outgoing}) {}

  Index neighbor() const { return static_cast<Index>(bits_ >> 32); }
  /// Position of the corner among the corners around v (a local face id).
  std::uint32_t slot() const { return static_cast<std::uint32_t>(bits_ & 0xffff'ffffU) >> 1; }
  /// The face runs v -> w (otherwise w -> v).
  bool outgoing() const { return (bits_ & 1U) != 0; }

  auto operator<=>(const EdgeUse&) const = default;

 private:
  std::uint64_t bits_;
};

/// The faces around one vertex v: the uses of its edges grouped by neighbor,
/// and the faces for which v is the smallest vertex (to find duplicate faces).
class VertexStar {
 public:
  void gather(const TriangleMesh& mesh, const VertexCorners& incidence, Index v) {
    uses_.clear();
    owned_faces_.clear();
    edgeless_corners_ = 0;
    const Index* index = mesh.faces.data();
    corners_ = std::span<const Corner>(incidence.corners.data() + incidence.first[v], incidence.degree(v));
    for (std::uint32_t slot = 0; slot < corners_.size(); ++slot) {
      const Corner c = corners_[slot];
      const Corner face = c / 3;
      const Corner k = c - 3 * face;
      const Index next = index[3 * face + (k + 1) % 3];
      const Index prev = index[3 * face + (k + 2) % 3];
      // Edges of a face with a repeated index that would join v to itself are skipped.
      if (next != v) uses_.emplace_back(next, slot, true);
      if (prev != v) uses_.emplace_back(prev, slot, false);
      if (next == v && prev == v) ++edgeless_corners_;
      // Each face is owned by the first of its corners that holds its smallest index.
      const bool first_minimum =
          v <= next && v <= prev && (k == 0 || (k == 1 && prev != v) || (k == 2 && prev != v && next != v));
      if (first_minimum) owned_faces_.emplace_back(std::min(next, prev), std::max(next, prev));
    }
    std::sort(uses_.begin(), uses_.end());
  }

  /// Calls f(uses) for each edge (v, w), with the uses of that edge.
  template <typename F>
  void for_each_edge(F&& f) const {
    for (std::size_t i = 0; i < uses_.size();) {
      std::size_t j = i + 1;
      while (j < uses_.size() && uses_[j].neighbor() == uses_[i].neighbor()) ++j;
      f(std::span<const EdgeUse>(uses_.data() + i, j - i));
      i = j;
    }
  }

  Corner face(std::uint32_t slot) const { return corners_[slot] / 3; }

  /// Corners of faces (v, v, v), which touch no edge.
  std::size_t edgeless_corners() const { return edgeless_corners_; }

  /// Faces owned by v with the same vertex set as another one owned by v:
  /// a face's owner is its smallest vertex, so this finds every duplicate once.
  std::int64_t duplicate_owned_faces() {
    std::sort(owned_faces_.begin(), owned_faces_.end());
    return owned_faces_.end() - std::unique(owned_faces_.begin(), owned_faces_.end());
  }

 private:
  std::span<const Corner> corners_;
  std::vector<EdgeUse> uses_;
  std::vector<std::pair<Index, Index>> owned_faces_;  ///< the other two indices, sorted
  std::size_t edgeless_corners_ = 0;
};

/// What the pass over all vertex stars finds.
struct StarSummary {
  std::int64_t referenced_vertices = 0;
  std::int64_t edges = 0;
  std::int64_t boundary_edges = 0;
  std::int64_t boundary_loops = 0;
  std::int64_t nonmanifold_edges = 0;
  std::int64_t nonmanifold_vertices = 0;
  std::int64_t duplicate_faces = 0;
  std::int64_t components = 0;
  bool oriented = true;  ///< no directed edge used twice
};

/// Edges, fans, components, boundary loops and duplicate faces, one vertex
/// star at a time.
///
/// Components connect referenced vertices through edges, so two pieces that
/// touch at a single (pinch) vertex are one component.
///
/// Fans: the faces around v are in one fan when they share an edge (v, w),
/// whatever the number of faces on that edge; a referenced vertex with more
/// than one fan is a pinch (non-manifold) vertex. A vertex on a non-manifold
/// edge is therefore not counted unless its faces also split into fans
/// (dragon_100k.ply: 1 non-manifold edge, no non-manifold vertex). Faces
/// (v, v, v), which have no edge, form no fan.
///
/// Boundary loops: the groups of boundary edges joined at shared vertices. On
/// a manifold every vertex has at most one open fan, so each group is exactly
/// one traced loop. Where loops touch at a pinch vertex, the trace crosses over
/// from one to the other there (a figure eight) and counts them once, as it
/// counts components; this is the data set manifest's convention (ogre.ply:
/// 12 loops, 13 if loops were kept apart at its 3 pinch vertices).
StarSummary summarize_stars(const TriangleMesh& mesh, const VertexCorners& incidence) {
  StarSummary summary;
  const auto num_vertices = static_cast<std::size_t>(mesh.num_vertices());
  UnionFind connected(num_vertices);
  std::vector<std::pair<Index, Index>> boundary;  // one entry per boundary edge
  std::int64_t boundary_vertices = 0;
  VertexStar star;
  UnionFind fans(0);

  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const std::size_t degree = incidence.degree(v);
    if (degree == 0) continue;
    ++summary.referenced_vertices;
    star.gather(mesh, incidence, v);
    fans.reset(degree);
    bool on_boundary = false;

    star.for_each_edge([&](std::span<const EdgeUse> uses) {
      for (const EdgeUse& use : uses) fans.unite(static_cast<Index>(uses[0].slot()), static_cast<Index>(use.slot()));
      if (uses.size() == 1) on_boundary = true;
      const Index w = uses[0].neighbor();
      if (w < v) return;  // classified at its smaller endpoint
      ++summary.edges;
      connected.unite(v, w);
      if (uses.size() == 1) boundary.emplace_back(v, w);
      if (uses.size() > 2) ++summary.nonmanifold_edges;
      const auto outgoing = std::count_if(uses.begin(), uses.end(), [](const EdgeUse& use) { return use.outgoing(); });
      const auto incoming = static_cast<std::ptrdiff_t>(uses.size()) - outgoing;
      if (outgoing > 1 || incoming > 1) summary.oriented = false;
    });

    if (fans.sets() - star.edgeless_corners() > 1) ++summary.nonmanifold_vertices;
    if (on_boundary) ++boundary_vertices;
    summary.duplicate_faces += star.duplicate_owned_faces();
  }
  summary.components = summary.referenced_vertices - static_cast<std::int64_t>(connected.merges());

  summary.boundary_edges = static_cast<std::int64_t>(boundary.size());
  if (!boundary.empty()) {
    connected.reset(num_vertices);
    for (const auto& [v, w] : boundary) {
      connected.unite(v, w);
    }
    summary.boundary_loops = boundary_vertices - static_cast<std::int64_t>(connected.merges());
  }
  return summary;
}

/// Whether the faces can be oriented consistently (for a mesh whose stored
/// orientation is not): face f has two states, kept (2f) and flipped (2f+1);
/// each interior edge ties the states of its two faces, and the mesh is
/// orientable unless some face ends up tied to its own flip.
bool is_orientable(const TriangleMesh& mesh, const VertexCorners& incidence) {
  UnionFind states(2 * static_cast<std::size_t>(mesh.num_faces()));
  VertexStar star;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    star.gather(mesh, incidence, v);
    star.for_each_edge([&](std::span<const EdgeUse> uses) {
      if (uses.size() != 2 || uses[0].neighbor() < v) return;
      const Corner f = star.face(uses[0].slot());
      const Corner g = star.face(uses[1].slot());
      // Same direction on the shared edge: one of the two faces must flip.
      const Corner flip = uses[0].outgoing() == uses[1].outgoing() ? 1 : 0;
      states.unite(static_cast<Index>(2 * f), static_cast<Index>(2 * g + flip));
      states.unite(static_cast<Index>(2 * f + 1), static_cast<Index>(2 * g + 1 - flip));
    });
  }
  for (Corner f = 0; f < static_cast<Corner>(mesh.num_faces()); ++f) {
    if (states.find(static_cast<Index>(2 * f)) == states.find(static_cast<Index>(2 * f + 1))) return false;
  }
  return true;
}

bool is_degenerate(const TriangleMesh& mesh, Index f) { return !has_positive_area(mesh, f); }

/// A vertex position as bits, with -0 taken as +0, so that equal positions
/// give equal keys (and a NaN coordinate matches only the same NaN bits).
using PositionKey = std::array<std::uint64_t, 3>;

PositionKey position_key(const TriangleMesh& mesh, Index v) {
  PositionKey key;
  for (int axis = 0; axis < 3; ++axis) {
    key[axis] = std::bit_cast<std::uint64_t>(mesh.vertices(v, axis) + 0.0);
  }
  return key;
}

/// Vertices at exactly the position of an earlier vertex, found with an
/// open-addressing hash set of vertex ids (linear probing, at most half full).
std::int64_t count_duplicate_vertices(const TriangleMesh& mesh) {
  constexpr std::uint32_t empty = std::numeric_limits<std::uint32_t>::max();
  const std::size_t table_size = std::bit_ceil(2 * static_cast<std::size_t>(mesh.num_vertices()) + 1);
  const std::size_t mask = table_size - 1;
  std::vector<std::uint32_t> table(table_size, empty);
  std::int64_t duplicates = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const PositionKey key = position_key(mesh, v);
    std::size_t slot = splitmix64_mix(key[0] ^ splitmix64_mix(key[1] ^ splitmix64_mix(key[2]))) & mask;
    while (table[slot] != empty && position_key(mesh, static_cast<Index>(table[slot])) != key) {
      slot = (slot + 1) & mask;
    }
    if (table[slot] == empty) {
      table[slot] = static_cast<std::uint32_t>(v);
    } else {
      ++duplicates;
    }
  }
  return duplicates;
}

}  // namespace

MeshReport analyze_mesh(const TriangleMesh& mesh) {
  check_indices(mesh);
  MeshReport report;
  report.vertices = mesh.num_vertices();
  report.faces = mesh.num_faces();

  const VertexCorners incidence = build_vertex_corners(mesh);
  const StarSummary stars = summarize_stars(mesh, incidence);
  report.edges = stars.edges;
  report.components = stars.components;
  report.nonmanifold_edges = stars.nonmanifold_edges;
  report.nonmanifold_vertices = stars.nonmanifold_vertices;
  report.duplicate_faces = stars.duplicate_faces;
  report.oriented = stars.oriented;
  report.boundary_edges = stars.boundary_edges;
  report.boundary_loops = stars.boundary_loops;
  report.unreferenced_vertices = report.vertices - stars.referenced_vertices;
  report.euler_characteristic = stars.referenced_vertices - stars.edges + report.faces;

  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (is_degenerate(mesh, f)) ++report.degenerate_faces;
  }
  report.duplicate_vertices = count_duplicate_vertices(mesh);

  bool any = false;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (incidence.degree(v) == 0) continue;
    const Eigen::Vector3d p = mesh.vertices.row(v);
    report.bbox_min = any ? report.bbox_min.cwiseMin(p) : p;
    report.bbox_max = any ? report.bbox_max.cwiseMax(p) : p;
    any = true;
  }
  report.bbox_diagonal = (report.bbox_max - report.bbox_min).norm();

  const bool manifold = report.faces > 0 && report.nonmanifold_edges == 0 && report.nonmanifold_vertices == 0;
  if (manifold && (report.oriented || is_orientable(mesh, incidence))) {
    report.genus =
        static_cast<double>(2 * report.components - report.boundary_loops - report.euler_characteristic) / 2.0;
  }
  return report;
}

}  // namespace geodual
