#include "geodual/remesh/manifold_cut.hpp"

#include "geodual/mesh/detail/vertex_pair_sort.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/sharp_edges.hpp"
#include "geodual/mesh/union_find.hpp"
#include "geodual/mesh/vertex_copies.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

namespace geodual::remesh {
namespace {

bool proper(const FaceMatrix& faces, Index f) {
  const Index a = faces(f, 0), b = faces(f, 1), c = faces(f, 2);
  return a != b && b != c && c != a;
}

bool proper(const TriangleMesh& mesh, Index f) { return proper(mesh.faces, f); }

/// Per vertex: the smallest index of a vertex at exactly its position (its
/// own for a vertex with a coordinate that is not finite).
std::vector<Index> position_ids(const VertexMatrix& vertices) {
  const Index n = static_cast<Index>(vertices.rows());
  std::vector<Index> id(static_cast<std::size_t>(n));
  std::iota(id.begin(), id.end(), Index{0});
  std::vector<Index> order;
  order.reserve(id.size());
  for (Index v = 0; v < n; ++v) {
    if (vertices.row(v).allFinite()) order.push_back(v);
  }
  auto less = [&](Index a, Index b) {
    for (int d = 0; d < 3; ++d) {
      if (vertices(a, d) != vertices(b, d)) return vertices(a, d) < vertices(b, d);
    }
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t i = 1; i < order.size(); ++i) {
    if (vertices.row(order[i]) == vertices.row(order[i - 1])) id[order[i]] = id[order[i - 1]];
  }
  return id;
}

/// Disables (all corners set to the first) every face whose corners, as
/// positions, are those of an earlier face; fills copy_of and returns how
/// many were disabled.
std::int64_t disable_duplicate_faces(const VertexMatrix& vertices, FaceMatrix& faces, std::vector<Index>& copy_of) {
  const Index num_faces = static_cast<Index>(faces.rows());
  copy_of.assign(static_cast<std::size_t>(num_faces), -1);
  const std::vector<Index> id = position_ids(vertices);
  struct FaceKey {
    std::array<Index, 3> corners;  // position ids, increasing
    Index face;
  };
  std::vector<FaceKey> keys;
  keys.reserve(static_cast<std::size_t>(num_faces));
  for (Index f = 0; f < num_faces; ++f) {
    if (!proper(faces, f)) continue;
    std::array<Index, 3> corners = {id[faces(f, 0)], id[faces(f, 1)], id[faces(f, 2)]};
    std::sort(corners.begin(), corners.end());
    if (corners[0] == corners[1] || corners[1] == corners[2]) continue;  // zero area: no copy of anything
    keys.push_back({corners, f});
  }
  // By corners, equal keys in face order: the first of a run is kept.
  sort_by_vertex_pair(
      keys, static_cast<Index>(vertices.rows()), [](const FaceKey& k) { return k.corners[0]; },
      [](const FaceKey& k) { return k.corners[1]; });
  std::int64_t disabled = 0;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j].corners[0] == keys[i].corners[0] && keys[j].corners[1] == keys[i].corners[1]) ++j;
    if (j - i > 1) {
      std::stable_sort(keys.begin() + static_cast<std::ptrdiff_t>(i), keys.begin() + static_cast<std::ptrdiff_t>(j),
                       [](const FaceKey& a, const FaceKey& b) { return a.corners[2] < b.corners[2]; });
      for (std::size_t k = i + 1, first = i; k < j; ++k) {
        if (keys[k].corners[2] != keys[first].corners[2]) {
          first = k;
          continue;
        }
        const Index f = keys[k].face;
        copy_of[f] = keys[first].face;
        faces(f, 1) = faces(f, 2) = faces(f, 0);
        ++disabled;
      }
    }
    i = j;
  }
  return disabled;
}

/// Two faces that stay joined across a non-manifold edge of the input's
/// topology.
struct FacePair {
  Index edge, first, second;
};

/// A non-manifold edge with more faces than this is cut apart whole.
constexpr std::size_t max_faces_paired = 16;

/// Faces in sets with a relative orientation (union-find with parity): the
/// faces joined so far, each flagged by whether it must be reversed to agree
/// with its set's first face.
class OrientedFaceSets {
 public:
  explicit OrientedFaceSets(std::size_t n) : parent_(n), flipped_(n, 0) {
    std::iota(parent_.begin(), parent_.end(), Index{0});
  }

  /// Joins the sets of f and g with g's orientation relative to f's `flip`;
  /// false (and nothing changed) when they are in one set already with the
  /// other relative orientation: the join would make it non-orientable.
  bool join(Index f, Index g, bool flip) {
    const auto [root_f, flip_f] = find(f);
    const auto [root_g, flip_g] = find(g);
    const bool relative = flip_f != flip_g;
    if (root_f == root_g) return relative == flip;
    parent_[root_g] = root_f;
    flipped_[root_g] = relative != flip;
    return true;
  }

 private:
  /// The root of f's set and whether f is reversed relative to it.
  std::pair<Index, bool> find(Index f) {
    bool flip = false;
    Index root = f;
    while (parent_[root] != root) {
      flip = flip != (flipped_[root] != 0);
      root = parent_[root];
    }
    // Path compression: every face on the path points at the root.
    bool rest = flip;
    while (parent_[f] != root) {
      const Index next = parent_[f];
      const bool own = flipped_[f] != 0;
      parent_[f] = root;
      flipped_[f] = rest;
      rest = rest != own;
      f = next;
    }
    return {root, flip};
  }

  std::vector<Index> parent_;
  std::vector<std::uint8_t> flipped_;
};

/// The faces joined across non-manifold edges (the two faces of an edge with
/// two are always joined, and not listed): pairs of faces that run the edge
/// in opposite directions, the most nearly coplanar pair first, each face in
/// at most one pair, and no pair that would leave its piece with no
/// consistent orientation (a remesh must be orientable wherever the input's
/// pieces are). A flap glued onto a surface along an edge (a T-junction of a
/// CAD assembly) leaves the surface whole and gets a boundary there; two
/// sheets crossing at an edge each stay whole.
std::vector<FacePair> joined_face_pairs(const TriangleMesh& mesh, const MeshTopology& topology) {
  std::vector<FacePair> joined;
  OrientedFaceSets orientation(static_cast<std::size_t>(mesh.num_faces()));
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto faces = topology.edge_faces(e);
    if (faces.size() != 2) continue;
    const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(e)];
    orientation.join(faces[0], faces[1], face_runs_edge(mesh, faces[0], a, b) == face_runs_edge(mesh, faces[1], a, b));
  }
  struct Candidate {
    double coplanarity;  // cosine of the angle between the unit normals
    std::size_t i, j;    // indices into the edge's faces
  };
  std::vector<Candidate> candidates;
  std::vector<Eigen::Vector3d> normal;
  std::vector<std::uint8_t> forward, paired;
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto faces = topology.edge_faces(e);
    if (faces.size() < 3 || faces.size() > max_faces_paired) continue;
    const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(e)];
    normal.clear();
    forward.clear();
    for (const Index f : faces) {
      normal.push_back(face_unit_normal(mesh, f));
      forward.push_back(face_runs_edge(mesh, f, a, b) ? 1 : 0);
    }
    candidates.clear();
    for (std::size_t i = 0; i < faces.size(); ++i) {
      for (std::size_t j = i + 1; j < faces.size(); ++j) {
        if (forward[i] != forward[j]) candidates.push_back({normal[i].dot(normal[j]), i, j});
      }
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& x, const Candidate& y) { return x.coplanarity > y.coplanarity; });
    paired.assign(faces.size(), 0);
    for (const Candidate& c : candidates) {
      if (paired[c.i] || paired[c.j] || !orientation.join(faces[c.i], faces[c.j], false)) continue;
      paired[c.i] = paired[c.j] = 1;
      joined.push_back({e, faces[c.i], faces[c.j]});
    }
  }
  return joined;
}

/// Per corner (3 * face + k): its fan, the corners at one vertex whose faces
/// are joined around it (across edges with two faces, and the `joined` pairs),
/// numbered in the order of their first corner (-1 for corners of faces with
/// a repeated corner).
std::vector<Index> corner_fans(const FaceMatrix& faces, const MeshTopology& topology,
                               const std::vector<FacePair>& joined) {
  const Index num_corners = 3 * static_cast<Index>(faces.rows());
  UnionFind fan(static_cast<std::size_t>(num_corners));
  const auto corner_at = [&](Index f, Index v) {
    for (Index k = 0; k < 3; ++k) {
      if (faces(f, k) == v) return 3 * f + k;
    }
    return Index{-1};
  };
  const auto join = [&](Index edge, Index f, Index g) {
    for (const Index v : topology.edge_vertices[static_cast<std::size_t>(edge)])
      fan.unite(corner_at(f, v), corner_at(g, v));
  };
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto both = topology.edge_faces(e);
    if (both.size() == 2) join(e, both[0], both[1]);
  }
  for (const FacePair& pair : joined) join(pair.edge, pair.first, pair.second);
  std::vector<Index> corner_fan(static_cast<std::size_t>(num_corners), -1);
  Index count = 0;
  for (Index c = 0; c < num_corners; ++c) {
    if (!proper(faces, c / 3)) continue;
    const Index root = fan.find(c);  // the set's smallest corner: numbered first
    corner_fan[c] = root == c ? count++ : corner_fan[root];
  }
  return corner_fan;
}

/// Where the cut (faces of `cut_mesh`) still has an edge with three or more
/// faces, the input edge it copies is cut apart whole: its pairs leave
/// `joined`. False when no such edge had a pair left (nothing to undo).
bool unjoin_edges_left_nonmanifold(const TriangleMesh& cut_mesh, const std::vector<Index>& original_vertex,
                                   const MeshTopology& topology, std::vector<FacePair>& joined) {
  const MeshTopology after = build_mesh_topology(cut_mesh);
  std::vector<std::uint8_t> apart(static_cast<std::size_t>(topology.num_edges()), 0);
  for (Index e = 0; e < after.num_edges(); ++e) {
    if (after.is_manifold_edge(e)) continue;
    const Index at = topology.find_edge(original_vertex[static_cast<std::size_t>(after.edge_vertices[e][0])],
                                        original_vertex[static_cast<std::size_t>(after.edge_vertices[e][1])]);
    if (at >= 0) apart[static_cast<std::size_t>(at)] = 1;
  }
  const auto before = joined.size();
  std::erase_if(joined, [&](const FacePair& pair) { return apart[static_cast<std::size_t>(pair.edge)] != 0; });
  return joined.size() < before;
}

}  // namespace

std::vector<SurfacePoint> points_on_cut(const ManifoldCut& cut, std::vector<SurfacePoint> points) {
  const auto is_vertex = [](const SurfacePoint& p) { return p.kind == SurfacePoint::Kind::vertex; };
  if (std::none_of(points.begin(), points.end(), is_vertex)) return points;
  // Per input vertex, the first corner (face, k) of the cut at one of its copies.
  std::vector<std::array<Index, 2>> corner_of(cut.original_vertex.size(), {-1, 0});
  for (Index f = cut.mesh.num_faces(); f-- > 0;) {
    if (has_repeated_corner(cut.mesh, f)) continue;
    for (int k = 0; k < 3; ++k) corner_of[static_cast<std::size_t>(cut.original_vertex[cut.mesh.faces(f, k)])] = {f, k};
  }
  for (SurfacePoint& p : points) {
    if (!is_vertex(p) || p.element < 0 || static_cast<std::size_t>(p.element) >= corner_of.size()) continue;
    const auto [f, k] = corner_of[static_cast<std::size_t>(p.element)];
    if (f >= 0) p = SurfacePoint::in_face(f, k == 0, k == 1, k == 2);
  }
  return points;
}

namespace {

/// cut_to_manifold, with the cut mesh's topology in `*cut_topology` where that is given.
ManifoldCut cut_with_topology(const TriangleMesh& mesh, const ManifoldCutOptions& options, MeshTopology* cut_topology) {
  const Index num_faces = static_cast<Index>(mesh.faces.rows());
  const Index num_vertices = static_cast<Index>(mesh.vertices.rows());
  ManifoldCut cut;
  cut.mesh.faces = mesh.faces;
  if (options.disable_duplicate_faces) {
    cut.duplicates_disabled = disable_duplicate_faces(mesh.vertices, cut.mesh.faces, cut.copy_of);
    cut.faces_disabled = cut.duplicates_disabled;
  }
  // The fans of the input, copies disabled: corners at one vertex whose faces
  // are joined around it across edges (joined_face_pairs).
  cut.mesh.vertices = mesh.vertices;
  MeshTopology topology = build_mesh_topology(cut.mesh);
  std::vector<FacePair> joined = joined_face_pairs(cut.mesh, topology);
  const FaceMatrix faces = cut.mesh.faces;  // the input's corners, copies disabled
  std::vector<std::uint8_t> split;
  for (;;) {
    const std::vector<Index> corner_fan = corner_fans(faces, topology, joined);
    // One vertex per fan: the first fan of a vertex keeps its index, further
    // fans get new vertices at the end, in the order of their first corner.
    std::vector<Index> vertex_of_fan(corner_fan.size(), -1);
    std::vector<std::uint8_t> taken(static_cast<std::size_t>(num_vertices), 0);
    split.assign(static_cast<std::size_t>(num_vertices), 0);
    cut.original_vertex.resize(static_cast<std::size_t>(num_vertices));
    std::iota(cut.original_vertex.begin(), cut.original_vertex.end(), Index{0});
    for (Index f = 0; f < num_faces; ++f) {
      if (!proper(faces, f)) continue;
      for (int k = 0; k < 3; ++k) {
        const auto fan = static_cast<std::size_t>(corner_fan[static_cast<std::size_t>(3 * f + k)]);
        const Index v = faces(f, k);
        if (vertex_of_fan[fan] < 0) {
          if (!taken[v]) {
            taken[v] = 1;
            vertex_of_fan[fan] = v;
          } else {
            split[v] = 1;
            vertex_of_fan[fan] = static_cast<Index>(cut.original_vertex.size());
            cut.original_vertex.push_back(v);
          }
        }
        cut.mesh.faces(f, k) = vertex_of_fan[fan];
      }
    }
    const auto num_copies = static_cast<Index>(cut.original_vertex.size());
    cut.mesh.vertices.resize(num_copies, 3);
    for (Index v = 0; v < num_copies; ++v) {
      cut.mesh.vertices.row(v) = mesh.vertices.row(cut.original_vertex[static_cast<std::size_t>(v)]);
    }
    // Pairs joined at non-manifold edges can join the fans round a vertex so
    // that a third face shares both ends of such an edge again: those edges
    // are cut apart whole and the fans made again.
    if (joined.empty() || !unjoin_edges_left_nonmanifold(cut.mesh, cut.original_vertex, topology, joined)) break;
  }
  cut.vertices_split = std::count(split.begin(), split.end(), std::uint8_t{1});

  // Scraps: pieces (faces joined through shared vertices) too small to
  // remesh, both in faces and in their share of the surface's area; never
  // every piece.
  if (options.min_component_faces > 0) {
    const Index n = static_cast<Index>(cut.mesh.vertices.rows());
    UnionFind piece(static_cast<std::size_t>(n));
    for (Index f = 0; f < num_faces; ++f) {
      if (!proper(cut.mesh, f)) continue;
      piece.unite(cut.mesh.faces(f, 0), cut.mesh.faces(f, 1));
      piece.unite(cut.mesh.faces(f, 1), cut.mesh.faces(f, 2));
    }
    std::vector<Index> faces_in(static_cast<std::size_t>(n), 0);
    std::vector<double> area_of(static_cast<std::size_t>(n), 0.0);
    double total_area = 0;
    for (Index f = 0; f < num_faces; ++f) {
      if (!proper(cut.mesh, f)) continue;
      const Index p = piece.find(cut.mesh.faces(f, 0));
      ++faces_in[p];
      const double area = face_area(cut.mesh, f);
      area_of[p] += area;
      total_area += area;
    }
    auto is_scrap = [&](Index p) {
      return faces_in[p] < options.min_component_faces && area_of[p] <= options.max_scrap_area_share * total_area;
    };
    std::int64_t kept = 0;
    for (Index f = 0; f < num_faces; ++f) {
      if (proper(cut.mesh, f) && !is_scrap(piece.find(cut.mesh.faces(f, 0)))) ++kept;
    }
    for (Index f = 0; f < num_faces && kept > 0; ++f) {
      if (!proper(cut.mesh, f) || !is_scrap(piece.find(cut.mesh.faces(f, 0)))) continue;
      cut.mesh.faces(f, 1) = cut.mesh.faces(f, 2) = cut.mesh.faces(f, 0);
      ++cut.faces_disabled;
    }
  }
  if (cut_topology) {
    const bool unchanged = cut.vertices_split == 0 && cut.faces_disabled == cut.duplicates_disabled;
    *cut_topology = unchanged ? std::move(topology) : build_mesh_topology(cut.mesh);
  }
  return cut;
}

}  // namespace

ManifoldCut cut_to_manifold(const TriangleMesh& mesh, const ManifoldCutOptions& options) {
  return cut_with_topology(mesh, options, nullptr);
}

ManifoldCut cut_to_manifold(const TriangleMesh& mesh, const ManifoldCutOptions& options, MeshTopology& topology) {
  return cut_with_topology(mesh, options, &topology);
}

std::vector<std::array<Index, 2>> edges_on_cut(const ManifoldCut& cut, Index num_input_vertices,
                                               std::span<const std::array<Index, 2>> edges) {
  if (edges.empty()) return {};
  const VertexCopies copies = group_vertex_copies(cut.original_vertex, num_input_vertices);
  std::vector<std::array<Index, 2>> on_cut;
  for (const auto& [a, b] : edges) {
    for (const Index i : copies.of(a)) {
      for (const Index j : copies.of(b)) on_cut.push_back({i, j});
    }
  }
  return on_cut;
}

}  // namespace geodual::remesh
