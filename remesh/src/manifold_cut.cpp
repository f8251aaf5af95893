#include "geodual/remesh/manifold_cut.hpp"

#include "geodual/mesh/detail/vertex_pair_sort.hpp"
#include "geodual/mesh/union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

namespace geodual::remesh {
namespace {

bool proper(const TriangleMesh& mesh, Index f) {
  const Index a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
  return a != b && b != c && c != a;
}

/// The face's area; 0 where it overflows.
double face_area(const TriangleMesh& mesh, Index f) {
  const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0));
  const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1));
  const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2));
  const double area = 0.5 * (b - a).cross(c - a).norm();
  return std::isfinite(area) ? area : 0.0;
}

}  // namespace

ManifoldCut cut_to_manifold(const TriangleMesh& mesh, const ManifoldCutOptions& options) {
  const Index num_faces = static_cast<Index>(mesh.faces.rows());
  const Index num_vertices = static_cast<Index>(mesh.vertices.rows());
  // Corners (face * 3 + k) joined when their faces share an edge with exactly
  // two faces and they sit at the same vertex of it.
  struct HalfEdge {
    Index low, high, corner_low, corner_high;
  };
  std::vector<HalfEdge> edges;
  edges.reserve(static_cast<std::size_t>(3 * num_faces));
  for (Index f = 0; f < num_faces; ++f) {
    if (!proper(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) {
      const Index u = mesh.faces(f, k), v = mesh.faces(f, (k + 1) % 3);
      const Index cu = 3 * f + k, cv = 3 * f + (k + 1) % 3;
      edges.push_back(u < v ? HalfEdge{u, v, cu, cv} : HalfEdge{v, u, cv, cu});
    }
  }
  // By (low, high), then corner_low: equal pairs keep their order, by face.
  sort_by_vertex_pair(edges, num_vertices, [](const HalfEdge& e) { return e.low; },
                      [](const HalfEdge& e) { return e.high; });
  UnionFind fans(static_cast<std::size_t>(3 * num_faces));
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].low == edges[i].low && edges[j].high == edges[i].high) ++j;
    if (j - i == 2) {
      fans.unite(edges[i].corner_low, edges[i + 1].corner_low);
      fans.unite(edges[i].corner_high, edges[i + 1].corner_high);
    }
    i = j;
  }
  // One vertex per fan: the first fan of a vertex keeps its index, further
  // fans get new vertices at the end, in the order of their first corner.
  ManifoldCut cut;
  cut.mesh.faces = mesh.faces;
  std::vector<Index> vertex_of_fan(fans.size(), -1);
  std::vector<std::uint8_t> taken(static_cast<std::size_t>(num_vertices), 0), split(static_cast<std::size_t>(num_vertices), 0);
  std::vector<Index> extra;  // original vertex of each new vertex
  for (Index f = 0; f < num_faces; ++f) {
    if (!proper(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) {
      const Index corner = 3 * f + k, root = fans.find(corner);
      const Index v = mesh.faces(f, k);
      if (vertex_of_fan[root] < 0) {
        if (!taken[v]) {
          taken[v] = 1;
          vertex_of_fan[root] = v;
        } else {
          split[v] = 1;
          vertex_of_fan[root] = num_vertices + static_cast<Index>(extra.size());
          extra.push_back(v);
        }
      }
      cut.mesh.faces(f, k) = vertex_of_fan[root];
    }
  }
  cut.mesh.vertices.resize(num_vertices + static_cast<Index>(extra.size()), 3);
  cut.mesh.vertices.topRows(num_vertices) = mesh.vertices;
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
