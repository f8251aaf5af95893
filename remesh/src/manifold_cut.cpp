#include "geodual/remesh/manifold_cut.hpp"

#include "geodual/mesh/detail/vertex_pair_sort.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
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

ManifoldCut cut_to_manifold(const TriangleMesh& mesh, const ManifoldCutOptions& options) {
  const Index num_faces = static_cast<Index>(mesh.faces.rows());
  const Index num_vertices = static_cast<Index>(mesh.vertices.rows());
  ManifoldCut cut;
  cut.mesh.faces = mesh.faces;
  if (options.disable_duplicate_faces) {
    cut.duplicates_disabled = disable_duplicate_faces(mesh.vertices, cut.mesh.faces, cut.copy_of);
    cut.faces_disabled = cut.duplicates_disabled;
  }
  // The fans of the input, copies disabled: corners at one vertex whose faces
  // are joined around it across edges with exactly two faces.
  cut.mesh.vertices = mesh.vertices;
  const std::vector<Index> corner_fan = build_mesh_topology(cut.mesh).corner_fan;
  // One vertex per fan: the first fan of a vertex keeps its index, further
  // fans get new vertices at the end, in the order of their first corner.
  std::vector<Index> vertex_of_fan;
  std::vector<std::uint8_t> taken(static_cast<std::size_t>(num_vertices), 0),
      split(static_cast<std::size_t>(num_vertices), 0);
  std::vector<Index> extra;  // original vertex of each new vertex
  for (Index f = 0; f < num_faces; ++f) {
    if (!proper(cut.mesh, f)) continue;
    for (int k = 0; k < 3; ++k) {
      const auto fan = static_cast<std::size_t>(corner_fan[static_cast<std::size_t>(3 * f + k)]);
      const Index v = cut.mesh.faces(f, k);
      if (fan == vertex_of_fan.size()) {  // fans are numbered in the order of their first corner
        if (!taken[v]) {
          taken[v] = 1;
          vertex_of_fan.push_back(v);
        } else {
          split[v] = 1;
          vertex_of_fan.push_back(num_vertices + static_cast<Index>(extra.size()));
          extra.push_back(v);
        }
      }
      cut.mesh.faces(f, k) = vertex_of_fan[fan];
    }
  }
  cut.mesh.vertices.conservativeResize(num_vertices + static_cast<Index>(extra.size()), 3);
  cut.original_vertex.resize(static_cast<std::size_t>(num_vertices) + extra.size());
  std::iota(cut.original_vertex.begin(), cut.original_vertex.begin() + num_vertices, Index{0});
  for (std::size_t i = 0; i < extra.size(); ++i) {
    cut.mesh.vertices.row(num_vertices + static_cast<Index>(i)) = mesh.vertices.row(extra[i]);
    cut.original_vertex[static_cast<std::size_t>(num_vertices) + i] = extra[i];
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
  return cut;
}

}  // namespace geodual::remesh
