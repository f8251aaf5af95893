#include "dual/boundary_triangles.hpp"

#include "dual/ear_clipping.hpp"

#include <algorithm>
#include <cstdint>
#include <numbers>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

namespace geodual::remesh::detail {
namespace {

/// A place on a boundary loop: the boundary edge (its index in the walk's
/// order) and how far along it, in [0, 1), in the walk's direction.
struct LoopPlace {
  Index loop = -1;
  Index step = 0;
  double along = 0;
};

/// What the walk passes at a place: a site on the boundary (`site`), or the
/// end of an arc, where the cell `before` gives way to `after`.
struct LoopEvent {
  LoopPlace place;
  Index site = -1;
  Index before = -1;
  Index after = -1;
};

/// The boundary loops of the field's surface, walked with the surface on the
/// left: per boundary edge its loop and step, per loop its edges in order.
struct BoundaryLoops {
  std::vector<Index> loop_of_edge;  // -1: not on a usable loop
  std::vector<Index> step_of_edge;
  std::vector<std::vector<Index>> edges;  // per loop
  std::vector<Index> out_edge;            // per vertex: the boundary edge leaving it (-1: none or several)
};

BoundaryLoops boundary_loops(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology) {
  BoundaryLoops loops;
  const auto num_edges = static_cast<Index>(topology.edge_faces.size());
  loops.loop_of_edge.assign(static_cast<std::size_t>(num_edges), -1);
  loops.step_of_edge.assign(static_cast<std::size_t>(num_edges), -1);
  loops.out_edge.assign(static_cast<std::size_t>(mesh.num_vertices()), -1);
  std::vector<std::uint8_t> several(static_cast<std::size_t>(mesh.num_vertices()), 0);
  std::vector<Index> boundary;
  for (Index e = 0; e < num_edges; ++e) {
    if (topology.edge_faces[e][1] >= 0 || topology.edge_faces[e][0] < 0) continue;
    boundary.push_back(e);
    const Index from = topology.edge_vertices(mesh, e)[0];
    if (loops.out_edge[from] >= 0) several[from] = 1;
    loops.out_edge[from] = e;
  }
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (several[v]) loops.out_edge[v] = -1;
  }
  std::vector<std::uint8_t> walked(static_cast<std::size_t>(num_edges), 0);
  for (const Index first : boundary) {
    if (walked[first]) continue;
    std::vector<Index> loop;
    bool usable = true;
    for (Index e = first; e >= 0 && !walked[e];) {
      walked[e] = 1;
      loop.push_back(e);
      const auto [from, to] = topology.edge_vertices(mesh, e);
      usable = usable && loops.out_edge[from] == e;
      e = loops.out_edge[to];
      if (e < 0) usable = false;
    }
    if (!usable || loops.out_edge[topology.edge_vertices(mesh, loop.back())[1]] != loop.front()) continue;
    const auto id = static_cast<Index>(loops.edges.size());
    for (std::size_t i = 0; i < loop.size(); ++i) {
      loops.loop_of_edge[loop[i]] = id;
      loops.step_of_edge[loop[i]] = static_cast<Index>(i);
    }
    loops.edges.push_back(std::move(loop));
  }
  return loops;
}

/// Where `point` lies on a usable boundary loop, if it does.
std::optional<LoopPlace> place_of(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology,
                                  const BoundaryLoops& loops, const SurfacePoint& point) {
  const auto at_vertex = [&](Index v) -> std::optional<LoopPlace> {
    const Index e = loops.out_edge[v];
    if (e < 0 || loops.loop_of_edge[e] < 0) return std::nullopt;
    return LoopPlace{loops.loop_of_edge[e], loops.step_of_edge[e], 0.0};
  };
  if (point.kind == SurfacePoint::Kind::vertex) return at_vertex(point.element);
  const Index f = point.element;
  const Eigen::Vector3d& b = point.barycentric;
  for (int k = 0; k < 3; ++k) {
    if (b[k] == 1) return at_vertex(mesh.faces(f, k));
  }
  for (int k = 0; k < 3; ++k) {
    if (b[(k + 2) % 3] != 0) continue;  // not on edge k (corners k, k + 1)
    const Index e = topology.face_edges[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)];
    if (e < 0 || loops.loop_of_edge[e] < 0) continue;
    // Boundary edges run as their one face does: from corner k to k + 1.
    const double along = b[(k + 1) % 3];
    if (along >= 1) return at_vertex(mesh.faces(f, (k + 1) % 3));
    return LoopPlace{loops.loop_of_edge[e], loops.step_of_edge[e], along};
  }
  return std::nullopt;
}

}  // namespace

std::vector<std::array<Index, 3>> boundary_triangles(const TriangleMesh& mesh, const voronoi::VoronoiDiagram& diagram,
                                                     std::span<const std::array<Index, 3>> triangles,
                                                     const VertexMatrix& positions, int max_cells, double min_angle,
                                                     double max_reach) {
  const voronoi::GeodesicField& field = diagram.field;
  const voronoi::SurfaceTopology& topology = *field.topology;
  const BoundaryLoops loops = boundary_loops(mesh, topology);
  std::vector<std::vector<LoopEvent>> events(loops.edges.size());
  for (std::size_t s = 0; s < field.sites.size(); ++s) {
    if (const auto place = place_of(mesh, topology, loops, field.sites[s])) {
      const auto site = static_cast<Index>(s);
      events[static_cast<std::size_t>(place->loop)].push_back({*place, site, site, site});
    }
  }
  // An arc leaving the boundary has its left cell behind (the walk runs with
  // the surface on its left, the arc into it); one arriving, ahead.
  for (const voronoi::VoronoiArc& arc : diagram.arcs) {
    if (arc.closed || arc.point_end <= arc.point_begin) continue;
    if (arc.start_vertex < 0) {
      if (const auto place = place_of(mesh, topology, loops, diagram.point_locations[arc.point_begin])) {
        events[static_cast<std::size_t>(place->loop)].push_back({*place, -1, arc.left_site, arc.right_site});
      }
    }
    if (arc.end_vertex < 0) {
      if (const auto place = place_of(mesh, topology, loops, diagram.point_locations[arc.point_end - 1])) {
        events[static_cast<std::size_t>(place->loop)].push_back({*place, -1, arc.right_site, arc.left_site});
      }
    }
  }
  std::set<std::array<Index, 2>> directed, undirected;
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const Index a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      directed.insert({a, b});
      undirected.insert({std::min(a, b), std::max(a, b)});
    }
  }
  std::vector<std::array<Index, 3>> added;
  for (std::vector<LoopEvent>& loop : events) {
    std::sort(loop.begin(), loop.end(), [](const LoopEvent& a, const LoopEvent& b) {
      return std::tie(a.place.step, a.place.along, a.site) < std::tie(b.place.step, b.place.along, b.site);
    });
    const std::size_t n = loop.size();
    const auto first_site =
        std::find_if(loop.begin(), loop.end(), [](const LoopEvent& e) { return e.site >= 0; }) - loop.begin();
    if (n < 2 || static_cast<std::size_t>(first_site) == n) continue;
    // The cells must follow on from each other all round; ties at one place
    // (arcs ending together) leave the order open.
    bool consistent = true;
    for (std::size_t i = 0; i < n && consistent; ++i) {
      const LoopEvent& a = loop[i];
      const LoopEvent& b = loop[(i + 1) % n];
      consistent = a.after == b.before && (a.place.step != b.place.step || a.place.along != b.place.along);
    }
    if (!consistent) continue;
    // From each site on the loop to the next: the cells passed on the way.
    std::vector<Index> cells;
    Index from = loop[static_cast<std::size_t>(first_site)].site;
    for (std::size_t k = 1; k <= n; ++k) {
      const LoopEvent& event = loop[(static_cast<std::size_t>(first_site) + k) % n];
      if (event.site < 0) {
        cells.push_back(event.after);
        continue;
      }
      const Index to = event.site;
      if (!cells.empty()) cells.pop_back();  // the cell of `to` itself
      if (!cells.empty() && to != from && static_cast<int>(cells.size()) <= max_cells && !directed.count({from, to})) {
        std::vector<Index> polygon = {from, to};
        polygon.insert(polygon.end(), cells.rbegin(), cells.rend());
        std::vector<Index> sorted = polygon;
        std::sort(sorted.begin(), sorted.end());
        const double max_edge = max_reach * (positions.row(from) - positions.row(to)).norm();
        if (std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) {
          const auto is_edge = [&](Index a, Index b) { return undirected.count({std::min(a, b), std::max(a, b)}) > 0; };
          for (const auto& t : clip_ears(polygon, positions, is_edge, min_angle * std::numbers::pi / 180, max_edge)) {
            added.push_back(t);
            for (int c = 0; c < 3; ++c) {
              const Index a = t[static_cast<std::size_t>(c)], b = t[static_cast<std::size_t>((c + 1) % 3)];
              directed.insert({a, b});
              undirected.insert({std::min(a, b), std::max(a, b)});
            }
          }
        }
      }
      cells.clear();
      from = to;
    }
  }
  return added;
}

}  // namespace geodual::remesh::detail
