#include "dual/crack_fill.hpp"

#include "dual/ear_clipping.hpp"

#include "geodual/mesh/mesh_topology.hpp"

#include <algorithm>
#include <array>
#include <span>
#include <vector>

namespace geodual::remesh {
namespace {

/// The hole bounded by the boundary edges `loop_edges` (one loop of
/// `topology`), as its vertices in the order a triangle filling it runs
/// (opposite to the faces beside it), or empty where the loop is longer than
/// `max_edges` or no simple cycle.
std::vector<Index> hole_polygon(const TriangleMesh& mesh, const MeshTopology& topology,
                                std::span<const Index> loop_edges, int max_edges) {
  if (static_cast<int>(loop_edges.size()) > max_edges) return {};
  std::vector<std::array<Index, 2>> steps;  // from, to, in the filling's order
  for (const Index e : loop_edges) {
    const Index f = topology.edge_faces(e)[0];
    const int k = static_cast<int>(std::find(topology.face_edges[f].begin(), topology.face_edges[f].end(), e) -
                                   topology.face_edges[f].begin());
    steps.push_back({mesh.faces(f, (k + 1) % 3), mesh.faces(f, k)});
  }
  std::vector<Index> polygon;
  if (steps.size() < 3) return polygon;
  polygon.push_back(steps.front()[0]);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const Index from = polygon.back();
    if (std::count_if(steps.begin(), steps.end(), [&](const auto& s) { return s[0] == from; }) != 1) return {};
    polygon.push_back(std::find_if(steps.begin(), steps.end(), [&](const auto& s) { return s[0] == from; })->at(1));
  }
  if (polygon.back() != polygon.front()) return {};
  polygon.pop_back();
  std::vector<Index> sorted = polygon;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return {};  // through a vertex twice
  return polygon;
}

}  // namespace

std::optional<CrackFill> close_cracks(TriangleMesh& mesh, std::span<const Index> crack_vertices, int max_edges) {
  const MeshTopology topology = build_mesh_topology(mesh);
  std::vector<std::uint8_t> crack(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (const Index v : crack_vertices) crack[static_cast<std::size_t>(v)] = 1;
  std::vector<std::uint8_t> loop_cracked(static_cast<std::size_t>(topology.num_boundary_loops), 0);
  std::vector<std::vector<Index>> loop_edges(static_cast<std::size_t>(topology.num_boundary_loops));
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const Index loop = topology.edge_boundary_loop[e];
    if (loop < 0) continue;
    const auto [a, b] = topology.edge_vertices[e];
    if (crack[a] && crack[b]) loop_cracked[static_cast<std::size_t>(loop)] = 1;
    loop_edges[static_cast<std::size_t>(loop)].push_back(e);
  }
  std::vector<std::array<Index, 3>> added;
  std::vector<std::array<Index, 2>> new_edges;  // smaller end first
  const auto is_edge = [&](Index a, Index b) {
    const std::array<Index, 2> edge{std::min(a, b), std::max(a, b)};
    return topology.find_edge(a, b) >= 0 || std::find(new_edges.begin(), new_edges.end(), edge) != new_edges.end();
  };
  const auto is_face = [&](Index a, Index b, Index c) {  // a face on these three vertices, either way round
    const Index e = topology.find_edge(a, b);
    if (e < 0) return false;
    for (const Index f : topology.edge_faces(e)) {
      if (mesh.faces(f, 0) == c || mesh.faces(f, 1) == c || mesh.faces(f, 2) == c) return true;
    }
    return false;
  };
  CrackFill fill;
  for (Index loop = 0; loop < topology.num_boundary_loops; ++loop) {
    if (!loop_cracked[static_cast<std::size_t>(loop)]) continue;
    const std::vector<Index> polygon =
        hole_polygon(mesh, topology, loop_edges[static_cast<std::size_t>(loop)], max_edges);
    if (polygon.empty()) return std::nullopt;
    const std::vector<std::array<Index, 3>> ears = detail::clip_ears(polygon, mesh.vertices, is_edge);
    if (ears.empty() || is_face(ears.back()[0], ears.back()[1], ears.back()[2])) return std::nullopt;
    for (std::size_t i = 0; i < ears.size(); ++i) {
      added.push_back(ears[i]);
      if (i + 1 < ears.size()) {  // its closing side, a side of the next
        new_edges.push_back({std::min(ears[i][0], ears[i][2]), std::max(ears[i][0], ears[i][2])});
      }
    }
    ++fill.holes;
  }
  if (added.empty()) return fill;
  TriangleMesh closed = mesh;
  const Index first = closed.num_faces();
  closed.faces.conservativeResize(first + static_cast<Index>(added.size()), 3);
  for (std::size_t i = 0; i < added.size(); ++i) {
    for (int k = 0; k < 3; ++k) closed.faces(first + static_cast<Index>(i), k) = added[i][static_cast<std::size_t>(k)];
  }
  const MeshTopology after = build_mesh_topology(closed);
  for (Index e = 0; e < after.num_edges(); ++e) {
    if (!after.is_manifold_edge(e)) return std::nullopt;
  }
  fill.triangles = static_cast<std::int64_t>(added.size());
  mesh = std::move(closed);
  return fill;
}

}  // namespace geodual::remesh
