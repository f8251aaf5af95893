#include "geodual/remesh/features.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/sharp_edges.hpp"
#include "geodual/mesh/union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace geodual::remesh {
namespace {

/// The graph of feature edges: per vertex, its edges (CSR over `edges`).
struct FeatureGraph {
  std::vector<std::array<Index, 2>> edges;
  std::vector<std::uint8_t> edge_on_boundary;
  std::vector<Index> begin;      // per vertex + 1
  std::vector<Index> incidence;  // edge indices
  std::span<const Index> edges_at(Index v) const {
    return {incidence.data() + begin[v], incidence.data() + begin[v + 1]};
  }
  Index degree(Index v) const { return begin[v + 1] - begin[v]; }
  Index other_end(Index e, Index v) const { return edges[e][0] == v ? edges[e][1] : edges[e][0]; }
};

FeatureGraph build_graph(Index num_vertices, std::vector<std::array<Index, 2>> edges,
                         std::vector<std::uint8_t> on_boundary) {
  FeatureGraph graph;
  graph.edges = std::move(edges);
  graph.edge_on_boundary = std::move(on_boundary);
  graph.begin.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (const auto& [a, b] : graph.edges) {
    ++graph.begin[a + 1];
    ++graph.begin[b + 1];
  }
  for (Index v = 0; v < num_vertices; ++v) graph.begin[v + 1] += graph.begin[v];
  graph.incidence.resize(2 * graph.edges.size());
  std::vector<Index> next(graph.begin.begin(), graph.begin.end() - 1);
  for (Index e = 0; e < static_cast<Index>(graph.edges.size()); ++e) {
    for (const Index v : graph.edges[e]) graph.incidence[next[v]++] = e;
  }
  return graph;
}

double edge_length(const TriangleMesh& mesh, Index a, Index b) {
  return (mesh.vertices.row(a) - mesh.vertices.row(b)).norm();
}

/// The angle in degrees between the directions a -> v and v -> b (0: straight on).
double turn_degrees(const TriangleMesh& mesh, Index a, Index v, Index b) {
  const Eigen::Vector3d in = mesh.vertices.row(v) - mesh.vertices.row(a);
  const Eigen::Vector3d out = mesh.vertices.row(b) - mesh.vertices.row(v);
  return std::atan2(in.cross(out).norm(), in.dot(out)) * 180 / std::numbers::pi;
}

}  // namespace

FeatureSet detect_features(const TriangleMesh& surface, const FeatureOptions& options) {
  FeatureSet features;
  if (!(options.sharp_angle > 0)) return features;
  const MeshTopology topology = build_mesh_topology(surface);
  const std::vector<Index> sharp = sharp_edges(surface, topology, options.sharp_angle);
  if (sharp.empty()) return features;
  const Index num_vertices = static_cast<Index>(surface.vertices.rows());

  // Networks of sharp edges joined at vertices; the short ones are dropped.
  UnionFind network(static_cast<std::size_t>(num_vertices));
  for (const Index e : sharp) network.unite(topology.edge_vertices[e][0], topology.edge_vertices[e][1]);
  std::vector<double> network_length(static_cast<std::size_t>(num_vertices), 0.0);
  for (const Index e : sharp) {
    const auto [a, b] = topology.edge_vertices[e];
    network_length[network.find(a)] += edge_length(surface, a, b);
  }
  std::vector<std::array<Index, 2>> edges;
  std::vector<std::uint8_t> on_boundary;
  std::vector<std::uint8_t> touched(static_cast<std::size_t>(num_vertices), 0);
  for (const Index e : sharp) {
    const auto [a, b] = topology.edge_vertices[e];
    if (network_length[network.find(a)] < options.min_chain_length) continue;
    edges.push_back({a, b});
    on_boundary.push_back(0);
    touched[a] = touched[b] = 1;
    features.sharp_length += edge_length(surface, a, b);
  }
  if (edges.empty()) return features;
  features.sharp_edges = edges;  // in edge order: sorted by vertex pair

  // The boundary loops that the kept chains run into join the graph.
  std::vector<std::uint8_t> loop_touched(static_cast<std::size_t>(topology.num_boundary_loops), 0);
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const Index loop = topology.edge_boundary_loop[e];
    if (loop < 0) continue;
    const auto [a, b] = topology.edge_vertices[e];
    if (touched[a] || touched[b]) loop_touched[loop] = 1;
  }
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const Index loop = topology.edge_boundary_loop[e];
    if (loop < 0 || !loop_touched[loop]) continue;
    edges.push_back(topology.edge_vertices[e]);
    on_boundary.push_back(1);
  }
  const FeatureGraph graph = build_graph(num_vertices, std::move(edges), std::move(on_boundary));

  // Corners: ends and junctions (degree other than 2), and sharp turns.
  std::vector<std::uint8_t> corner(static_cast<std::size_t>(num_vertices), 0);
  for (Index v = 0; v < num_vertices; ++v) {
    const Index degree = graph.degree(v);
    if (degree == 0) continue;
    if (degree != 2) {
      corner[v] = 1;
    } else {
      const auto at = graph.edges_at(v);
      corner[v] =
          turn_degrees(surface, graph.other_end(at[0], v), v, graph.other_end(at[1], v)) >= options.corner_angle;
    }
    if (corner[v]) features.corners.push_back(v);
  }

  // Chains: walks from each corner along each of its edges to the next
  // corner; what is left are closed loops without one.
  std::vector<std::uint8_t> walked(graph.edges.size(), 0);
  auto walk = [&](Index start, Index first_edge) {
    FeatureChain chain;
    chain.on_boundary = graph.edge_on_boundary[first_edge] != 0;
    chain.vertices.push_back(start);
    Index v = start, e = first_edge;
    while (true) {
      walked[e] = 1;
      const Index next = graph.other_end(e, v);
      chain.length += edge_length(surface, v, next);
      chain.vertices.push_back(next);
      v = next;
      if (corner[v] || v == start) break;
      // Degree 2 and no corner: go on along its other edge.
      const auto at = graph.edges_at(v);
      e = at[0] == e ? at[1] : at[0];
      if (walked[e]) break;
    }
    chain.closed = chain.vertices.front() == chain.vertices.back();
    if (!chain.on_boundary) ++features.sharp_chains;
    features.chains.push_back(std::move(chain));
  };
  for (const int boundary : {0, 1}) {  // sharp chains first
    for (const Index v : features.corners) {
      for (const Index e : graph.edges_at(v)) {
        if (!walked[e] && graph.edge_on_boundary[e] == boundary) walk(v, e);
      }
    }
    for (Index e = 0; e < static_cast<Index>(graph.edges.size()); ++e) {
      if (!walked[e] && graph.edge_on_boundary[e] == boundary) walk(graph.edges[e][0], e);
    }
  }
  return features;
}

}  // namespace geodual::remesh
