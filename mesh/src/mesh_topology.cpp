#include "geodual/mesh/mesh_topology.hpp"

#include "geodual/mesh/detail/vertex_pair_sort.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/union_find.hpp"

#include <algorithm>
#include <limits>
#include <string>

namespace geodual {
namespace {

bool takes_part(const TriangleMesh& mesh, Index f) {
  const Index a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
  return a != b && b != c && c != a;
}

void check_indices(const TriangleMesh& mesh) {
  const Index n = mesh.num_vertices();
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (mesh.faces(f, k) < 0 || mesh.faces(f, k) >= n) {
        throw Error("mesh topology: face " + std::to_string(f) + " refers to vertex " +
                    std::to_string(mesh.faces(f, k)) + ", but the mesh has " + std::to_string(n) + " vertices");
      }
    }
  }
  // Corners are numbered in an Index.
  if (mesh.num_faces() > std::numeric_limits<Index>::max() / 3) {
    throw Error("mesh topology: " + std::to_string(mesh.num_faces()) + " faces are more than supported (715 million)");
  }
}

/// Edges, edge faces and face edges from the half-edges sorted by vertex pair.
void build_edges(const TriangleMesh& mesh, MeshTopology& topology) {
  struct HalfEdge {
    Index low, high, corner;
  };
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(3 * static_cast<std::size_t>(mesh.num_faces()));
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!takes_part(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) {
      const Index u = mesh.faces(f, k), w = mesh.faces(f, (k + 1) % 3);
      half_edges.push_back({std::min(u, w), std::max(u, w), 3 * f + k});
    }
  }
  // Stable: the half-edges of one pair stay in corner order, hence face order.
  sort_by_vertex_pair(
      half_edges, mesh.num_vertices(), [](const HalfEdge& h) { return h.low; },
      [](const HalfEdge& h) { return h.high; });
  topology.face_edges.assign(static_cast<std::size_t>(mesh.num_faces()), {-1, -1, -1});
  topology.edge_face_list.reserve(half_edges.size());
  topology.edge_face_begin.push_back(0);
  for (std::size_t i = 0; i < half_edges.size();) {
    const Index e = topology.num_edges();
    topology.edge_vertices.push_back({half_edges[i].low, half_edges[i].high});
    std::size_t j = i;
    for (; j < half_edges.size() && half_edges[j].low == half_edges[i].low && half_edges[j].high == half_edges[i].high;
         ++j) {
      const Index corner = half_edges[j].corner;
      topology.face_edges[corner / 3][corner % 3] = e;
      topology.edge_face_list.push_back(corner / 3);
    }
    topology.edge_face_begin.push_back(static_cast<Index>(topology.edge_face_list.size()));
    i = j;
  }
}

/// The corner of face f at vertex v. \pre v is a corner of f
Index corner_at(const TriangleMesh& mesh, Index f, Index v) {
  return 3 * f + (mesh.faces(f, 0) == v ? 0 : mesh.faces(f, 1) == v ? 1 : 2);
}

void build_fans(const TriangleMesh& mesh, MeshTopology& topology) {
  const auto num_corners = 3 * static_cast<std::size_t>(mesh.num_faces());
  UnionFind fans(num_corners);
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const std::span<const Index> faces = topology.edge_faces(e);
    if (faces.size() != 2) continue;
    for (const Index v : topology.edge_vertices[e])
      fans.unite(corner_at(mesh, faces[0], v), corner_at(mesh, faces[1], v));
  }
  topology.corner_fan.assign(num_corners, -1);
  std::vector<Index> fan_of_root(num_corners, -1);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!takes_part(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) {
      Index& fan = fan_of_root[fans.find(3 * f + k)];
      if (fan < 0) {
        fan = topology.num_fans();
        topology.fan_vertex.push_back(mesh.faces(f, k));
      }
      topology.corner_fan[3 * f + k] = fan;
    }
  }
}

void build_components(const TriangleMesh& mesh, MeshTopology& topology) {
  const auto num_vertices = static_cast<std::size_t>(mesh.num_vertices());
  UnionFind joined(num_vertices);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!takes_part(mesh, f)) continue;
    joined.unite(mesh.faces(f, 0), mesh.faces(f, 1));
    joined.unite(mesh.faces(f, 1), mesh.faces(f, 2));
  }
  std::vector<Index> component_of_root(num_vertices, -1);
  topology.face_component.assign(static_cast<std::size_t>(mesh.num_faces()), -1);
  topology.vertex_component.assign(num_vertices, -1);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!takes_part(mesh, f)) continue;
    Index& c = component_of_root[joined.find(mesh.faces(f, 0))];
    if (c < 0) {
      c = topology.num_components();
      topology.components.emplace_back();
    }
    topology.face_component[f] = c;
    ++topology.components[c].faces;
    for (int k = 0; k < 3; ++k) {
      Index& vertex_component = topology.vertex_component[mesh.faces(f, k)];
      if (vertex_component < 0) ++topology.components[c].vertices;
      vertex_component = c;
    }
  }
  for (Index e = 0; e < topology.num_edges(); ++e)
    ++topology.components[topology.vertex_component[topology.edge_vertices[e][0]]].edges;
}

void build_boundary_loops(const TriangleMesh& mesh, MeshTopology& topology) {
  topology.vertex_on_boundary.assign(static_cast<std::size_t>(mesh.num_vertices()), 0);
  topology.edge_boundary_loop.assign(static_cast<std::size_t>(topology.num_edges()), -1);
  UnionFind loops(static_cast<std::size_t>(mesh.num_vertices()));
  for (Index e = 0; e < topology.num_edges(); ++e) {
    if (!topology.is_boundary_edge(e)) continue;
    const auto [u, w] = topology.edge_vertices[e];
    loops.unite(u, w);
    topology.vertex_on_boundary[u] = topology.vertex_on_boundary[w] = 1;
  }
  std::vector<Index> loop_of_root(static_cast<std::size_t>(mesh.num_vertices()), -1);
  for (Index e = 0; e < topology.num_edges(); ++e) {
    if (!topology.is_boundary_edge(e)) continue;
    const Index u = topology.edge_vertices[e][0];
    Index& loop = loop_of_root[loops.find(u)];
    if (loop < 0) {
      loop = topology.num_boundary_loops++;
      ++topology.components[topology.vertex_component[u]].boundary_loops;
    }
    topology.edge_boundary_loop[e] = loop;
  }
}

}  // namespace

MeshTopology build_mesh_topology(const TriangleMesh& mesh) {
  check_indices(mesh);
  MeshTopology topology;
  build_edges(mesh, topology);
  build_fans(mesh, topology);
  build_components(mesh, topology);
  build_boundary_loops(mesh, topology);
  return topology;
}

Index MeshTopology::find_edge(Index a, Index b) const {
  const std::array<Index, 2> pair = a < b ? std::array<Index, 2>{a, b} : std::array<Index, 2>{b, a};
  const auto it = std::lower_bound(edge_vertices.begin(), edge_vertices.end(), pair);
  return it != edge_vertices.end() && *it == pair ? static_cast<Index>(it - edge_vertices.begin()) : -1;
}

}  // namespace geodual
