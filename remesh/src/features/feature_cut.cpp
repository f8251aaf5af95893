#include "geodual/remesh/feature_cut.hpp"

#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/sorted_edges.hpp"
#include "geodual/mesh/union_find.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <vector>

namespace geodual::remesh {
namespace {

SurfaceOutline surface_outline(const MeshTopology& topology, const FeatureSet& features) {
  SurfaceOutline outline;
  outline.sharp_edge_faces.assign(features.sharp_edges.size(), {-1, -1});
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const std::array<Index, 2>& ends = topology.edge_vertices[static_cast<std::size_t>(e)];
    if (topology.is_boundary_edge(e)) {
      outline.boundary_edges.push_back(ends);  // sorted, as the edges are
      outline.boundary_edge_loop.push_back(topology.edge_boundary_loop[static_cast<std::size_t>(e)]);
    }
    const Index sharp = features.find_sharp_edge(ends[0], ends[1]);
    if (sharp < 0) continue;
    const auto faces = topology.edge_faces(e);
    std::array<Index, 2>& kept = outline.sharp_edge_faces[static_cast<std::size_t>(sharp)];
    for (std::size_t k = 0; k < std::min<std::size_t>(2, faces.size()); ++k) kept[k] = faces[k];
  }
  outline.vertex_on_boundary = topology.vertex_on_boundary;
  outline.face_component = topology.face_component;
  outline.vertex_component = topology.vertex_component;
  outline.components = topology.components;
  return outline;
}

}  // namespace

FeatureCut cut_along_features(const TriangleMesh& surface, const FeatureSet& features) {
  return cut_along_features(RemeshSurface(surface), features);
}

FeatureCut cut_along_features(const RemeshSurface& prepared, const FeatureSet& features) {
  const TriangleMesh& surface = prepared.mesh();
  const MeshTopology& topology = prepared.topology();
  const Index num_faces = surface.num_faces(), num_vertices = static_cast<Index>(surface.vertices.rows());
  // Corners at one vertex stay together across every edge with two faces
  // that is not sharp: one class per sector between the chains.
  UnionFind sector(static_cast<std::size_t>(3 * num_faces));
  const auto corner_at = [&](Index f, Index v) {
    for (int k = 0; k < 3; ++k) {
      if (surface.faces(f, k) == v) return 3 * f + k;
    }
    return Index{-1};
  };
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto faces = topology.edge_faces(e);
    const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(e)];
    if (faces.size() != 2 || features.is_sharp(a, b)) continue;
    for (const Index v : {a, b}) sector.unite(corner_at(faces[0], v), corner_at(faces[1], v));
  }
  FeatureCut cut;
  cut.mesh.faces = surface.faces;
  std::vector<Index> vertex_of_sector(static_cast<std::size_t>(3 * num_faces), -1);
  std::vector<std::uint8_t> taken(static_cast<std::size_t>(num_vertices), 0);
  std::vector<Index> extra;
  for (Index f = 0; f < num_faces; ++f) {
    if (has_repeated_corner(surface, f)) continue;
    for (int k = 0; k < 3; ++k) {
      const Index root = sector.find(3 * f + k), v = surface.faces(f, k);
      if (vertex_of_sector[root] < 0) {
        if (!taken[v]) {
          taken[v] = 1;
          vertex_of_sector[root] = v;
        } else {
          vertex_of_sector[root] = num_vertices + static_cast<Index>(extra.size());
          extra.push_back(v);
        }
      }
      cut.mesh.faces(f, k) = vertex_of_sector[root];
    }
  }
  cut.mesh.vertices.resize(num_vertices + static_cast<Index>(extra.size()), 3);
  cut.mesh.vertices.topRows(num_vertices) = surface.vertices;
  cut.original_vertex.resize(static_cast<std::size_t>(num_vertices) + extra.size());
  std::iota(cut.original_vertex.begin(), cut.original_vertex.begin() + num_vertices, Index{0});
  for (std::size_t i = 0; i < extra.size(); ++i) {
    cut.mesh.vertices.row(num_vertices + static_cast<Index>(i)) = surface.vertices.row(extra[i]);
    cut.original_vertex[static_cast<std::size_t>(num_vertices) + i] = extra[i];
  }
  cut.surface = surface_outline(topology, features);
  return cut;
}

bool SurfaceOutline::is_boundary_edge(Index a, Index b) const { return find_sorted_edge(boundary_edges, a, b) >= 0; }
}  // namespace geodual::remesh
