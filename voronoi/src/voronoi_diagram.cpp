#include "geodual/voronoi/voronoi_diagram.hpp"

#include "face_boundary.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

namespace geodual::voronoi {
namespace {

using detail::BoundaryGraph;
using detail::BoundaryNode;
using detail::BoundaryPiece;

/// Chains the per-face pieces into arcs: through every node where exactly two
/// pieces meet, stopping at Voronoi vertices and at the mesh boundary.
void chain_arcs(const BoundaryGraph& graph, VoronoiDiagram& diagram) {
  const Index num_nodes = static_cast<Index>(graph.nodes.size());
  const Index num_pieces = static_cast<Index>(graph.pieces.size());
  std::vector<Index> begin(num_nodes + 1, 0);
  for (const BoundaryPiece& piece : graph.pieces) {
    ++begin[piece.from + 1];
    ++begin[piece.to + 1];
  }
  for (Index n = 0; n < num_nodes; ++n) begin[n + 1] += begin[n];
  std::vector<Index> incident(begin.back());
  std::vector<Index> fill(begin.begin(), begin.end() - 1);
  for (Index p = 0; p < num_pieces; ++p) {
    incident[fill[graph.pieces[p].from]++] = p;
    incident[fill[graph.pieces[p].to]++] = p;
  }

  std::vector<Index> vertex_of_node(num_nodes, -1);
  for (Index n = 0; n < num_nodes; ++n) {
    const BoundaryNode& node = graph.nodes[n];
    if (node.kind != BoundaryNode::Kind::voronoi_vertex) continue;
    vertex_of_node[n] = static_cast<Index>(diagram.vertices.size());
    VoronoiVertex vertex;
    vertex.location = node.location;
    vertex.position = node.position;
    vertex.distance = node.distance;
    vertex.site_begin = static_cast<Index>(diagram.vertex_sites.size());
    vertex.degree = node.degree;
    diagram.vertex_sites.insert(diagram.vertex_sites.end(), graph.vertex_sites.begin() + node.site_begin,
                                graph.vertex_sites.begin() + node.site_begin + node.degree);
    diagram.vertices.push_back(vertex);
  }
  auto stops_at = [&](Index n) { return vertex_of_node[n] >= 0 || begin[n + 1] - begin[n] != 2; };

  std::vector<std::uint8_t> used(num_pieces, 0);
  auto walk = [&](Index start, Index first_piece) {
    VoronoiArc arc;
    arc.start_vertex = vertex_of_node[start];
    arc.point_begin = static_cast<Index>(diagram.points.size());
    diagram.points.push_back(graph.nodes[start].position);
    diagram.point_locations.push_back(graph.nodes[start].location);
    Index node = start, piece_index = first_piece;
    bool first = true;
    while (true) {
      used[piece_index] = 1;
      const BoundaryPiece& piece = graph.pieces[piece_index];
      const bool forward = piece.from == node;
      if (first) {
        arc.left_site = forward ? piece.left : piece.right;
        arc.right_site = forward ? piece.right : piece.left;
        first = false;
      }
      if (forward) {
        for (Index i = piece.point_begin; i < piece.point_end; ++i) {
          diagram.points.push_back(graph.points[i]);
          diagram.point_locations.push_back(graph.point_locations[i]);
        }
      } else {
        for (Index i = piece.point_end; i-- > piece.point_begin;) {
          diagram.points.push_back(graph.points[i]);
          diagram.point_locations.push_back(graph.point_locations[i]);
        }
      }
      arc.length += piece.length;
      node = forward ? piece.to : piece.from;
      diagram.points.push_back(graph.nodes[node].position);
      diagram.point_locations.push_back(graph.nodes[node].location);
      if (stops_at(node)) {
        arc.end_vertex = vertex_of_node[node];
        break;
      }
      if (node == start) {
        arc.closed = true;
        break;
      }
      Index next = -1;
      for (Index i = begin[node]; i < begin[node + 1]; ++i) {
        if (!used[incident[i]]) next = incident[i];
      }
      if (next < 0) break;
      piece_index = next;
    }
    arc.point_end = static_cast<Index>(diagram.points.size());
    diagram.arcs.push_back(arc);
  };
  for (Index n = 0; n < num_nodes; ++n) {
    if (!stops_at(n)) continue;
    for (Index i = begin[n]; i < begin[n + 1]; ++i) {
      if (!used[incident[i]]) walk(n, incident[i]);
    }
  }
  // What is left are closed loops through crossings only: two cells, one
  // inside the other or around a handle.
  for (Index p = 0; p < num_pieces; ++p) {
    if (!used[p]) walk(graph.pieces[p].from, p);
  }
}

void collect_adjacency(VoronoiDiagram& diagram) {
  std::vector<CellAdjacency> pairs;
  pairs.reserve(diagram.arcs.size());
  for (const VoronoiArc& arc : diagram.arcs) {
    if (arc.left_site < 0 || arc.right_site < 0 || arc.left_site == arc.right_site) continue;
    pairs.push_back({std::min(arc.left_site, arc.right_site), std::max(arc.left_site, arc.right_site), arc.length, 1});
  }
  std::sort(pairs.begin(), pairs.end(), [](const CellAdjacency& a, const CellAdjacency& b) {
    return std::pair(a.site_a, a.site_b) < std::pair(b.site_a, b.site_b);
  });
  for (const CellAdjacency& pair : pairs) {
    if (!diagram.adjacency.empty() && diagram.adjacency.back().site_a == pair.site_a &&
        diagram.adjacency.back().site_b == pair.site_b) {
      diagram.adjacency.back().boundary_length += pair.boundary_length;
      diagram.adjacency.back().arc_count += 1;
    } else {
      diagram.adjacency.push_back(pair);
    }
  }
}

}  // namespace

VoronoiDiagram extract_voronoi(const TriangleMesh& mesh, GeodesicField field, const VoronoiOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  VoronoiDiagram diagram;
  diagram.field = std::move(field);
  const GeodesicField& f = diagram.field;
  diagram.stats.geodesic_seconds = f.stats.total_seconds;
  diagram.cell_area.assign(f.sites.size(), 0.0);

  BoundaryGraph graph;
  detail::CellMoments moments(mesh, f, diagram.cell_energy, diagram.cell_log_moment);
  detail::FaceBoundaryTracer tracer(mesh, f, options, graph, diagram.stats, &moments);
  const Index num_faces = static_cast<Index>(mesh.faces.rows());
  // Faces that may hold a boundary, then those next to an edge a boundary crosses.
  std::vector<std::uint8_t> traced(num_faces, 0);
  for (Index face = 0; face < num_faces; ++face) {
    if (!tracer.may_hold_boundary(face)) continue;
    traced[face] = 1;
    for (const Index e : f.face_edges[face]) tracer.edge_crossings(e);
  }
  for (Index face = 0; face < num_faces; ++face) {
    if (traced[face] || f.face_edges[face][0] < 0) continue;
    for (const Index e : f.face_edges[face]) {
      for (const Index neighbour : f.edge_faces[e]) {
        if (neighbour >= 0 && neighbour != face && traced[neighbour] && !tracer.edge_crossings(e).empty()) {
          traced[face] = 2;
        }
      }
    }
  }
  for (Index face = 0; face < num_faces; ++face) {
    if (f.face_edges[face][0] < 0) continue;
    if (traced[face]) {
      tracer.trace_face(face, diagram.cell_area);
    } else if (const Index site = f.nearest_site[mesh.faces(face, 0)]; site >= 0) {
      const detail::FaceLayout layout = detail::FaceLayout::of(f, face);
      diagram.cell_area[site] += layout.area;
      moments.set_face(face, layout);
      moments.add_face_from_corners(site);
    }
  }

  chain_arcs(graph, diagram);
  collect_adjacency(diagram);
  diagram.stats.extraction_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return diagram;
}

VoronoiDiagram compute_voronoi(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                               const VoronoiOptions& options) {
  return extract_voronoi(mesh, compute_geodesic_field(mesh, sites, options.geodesic), options);
}

}  // namespace geodual::voronoi
