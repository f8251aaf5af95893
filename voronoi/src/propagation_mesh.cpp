#include "propagation_mesh.hpp"

#include "geodual/mesh/detail/vertex_pair_sort.hpp"
#include "geodual/mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace geodual::voronoi::detail {
namespace {

/// Interior angle at each corner of a face, from its planar layout.
std::array<double, 3> corner_angles(const PropagationMesh& pm, Index face) {
  const EdgeLayout l = pm.layout(face, 0);
  const double at0 = std::atan2(l.apex.y(), l.apex.x());
  const double at1 = std::atan2(l.apex.y(), l.length - l.apex.x());
  return {at0, at1, std::max(0.0, std::numbers::pi - at0 - at1)};
}

}  // namespace

void PropagationMesh::faces_around(Index v, std::vector<Index>& faces) const {
  faces.clear();
  const Index first = vertex_face[v];
  if (first < 0) return;
  const std::array<std::uint8_t, kFanOffsets>& offsets = fan_offsets[v];
  if (offsets[0] != kFanWalked) {
    faces.push_back(first);
    for (const std::uint8_t offset : offsets) {
      if (offset == 0) break;
      faces.push_back(first + offset);
    }
    return;
  }
  auto add = [&](Index f) { faces.push_back(f); };
  walk_fan(v, first, add);
  if (!extra_fans.empty()) {
    auto it = std::lower_bound(extra_fans.begin(), extra_fans.end(), std::array<Index, 2>{v, -1});
    for (; it != extra_fans.end() && (*it)[0] == v; ++it) walk_fan(v, (*it)[1], add);
  }
  // Insertion sort: a vertex has a handful of faces.
  for (std::size_t i = 1; i < faces.size(); ++i) {
    const Index f = faces[i];
    std::size_t j = i;
    for (; j > 0 && faces[j - 1] > f; --j) faces[j] = faces[j - 1];
    faces[j] = f;
  }
}

namespace {

/// The edges of `mesh`'s included faces into `pm` (edge_faces, the faces'
/// edge records, num_included_faces): its half-edges sorted by their
/// undirected vertex pair, two of a pair one edge. Returns their lengths.
std::vector<double> build_edges(const TriangleMesh& mesh, PropagationMesh& pm) {
  const Index num_vertices = mesh.num_vertices();
  const Index num_faces = mesh.num_faces();
  struct HalfEdge {
    std::uint64_t key;
    Index face;
    std::int32_t local;
  };
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(static_cast<std::size_t>(num_faces) * 3);
  for (Index f = 0; f < num_faces; ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    ++pm.num_included_faces;
    for (int k = 0; k < 3; ++k) {
      const auto u = static_cast<std::uint64_t>(mesh.faces(f, k));
      const auto w = static_cast<std::uint64_t>(mesh.faces(f, (k + 1) % 3));
      half_edges.push_back({std::min(u, w) << 32 | std::max(u, w), f, k});
    }
  }
  // By vertex pair; equal pairs keep their order (the input's, by face and corner).
  sort_by_vertex_pair(
      half_edges, num_vertices, [](const HalfEdge& h) { return static_cast<Index>(h.key >> 32); },
      [](const HalfEdge& h) { return static_cast<Index>(h.key & 0xffffffffu); });
  // Runs of equal keys: two half-edges make one edge; a boundary or
  // non-manifold edge gives each of its faces its own copy.
  auto run_end = [&](std::size_t i) {
    std::size_t j = i + 1;
    while (j < half_edges.size() && half_edges[j].key == half_edges[i].key) ++j;
    return j;
  };
  std::size_t num_edges = 0;
  for (std::size_t i = 0; i < half_edges.size();) {
    const std::size_t j = run_end(i);
    num_edges += j - i == 2 ? 1 : j - i;
    i = j;
  }
  pm.edge_faces.reserve(num_edges);
  std::vector<double> lengths;
  lengths.reserve(num_edges);

  if (num_edges > FaceRecord::kEdgeMask) {
    throw Error("meshes of more than 2^30 edges are not supported");
  }
  pm.face_records.assign(num_faces, FaceRecord{});
  auto add_edge = [&](const HalfEdge& first, const HalfEdge* second) {
    const Index e = static_cast<Index>(pm.edge_faces.size());
    const Index v0 = mesh.faces(first.face, first.local);
    const Index v1 = mesh.faces(first.face, (first.local + 1) % 3);
    const double length = edge_length(mesh, v0, v1);
    auto attach = [&](const HalfEdge& half, std::uint32_t flags) {
      pm.face_records[half.face].edge_bits[half.local] = static_cast<std::uint32_t>(e) | flags;
    };
    lengths.push_back(length);
    attach(first, 0);
    if (second != nullptr) {
      const bool reversed = mesh.faces(second->face, second->local) == v1;
      attach(*second, FaceRecord::kSide1 | (reversed ? FaceRecord::kReversed : 0));
      pm.edge_faces.push_back({first.face, second->face});
    } else {
      pm.edge_faces.push_back({first.face, -1});
    }
  };
  for (std::size_t i = 0; i < half_edges.size();) {
    const std::size_t j = run_end(i);
    if (j - i == 2) {
      add_edge(half_edges[i], &half_edges[i + 1]);
    } else {
      for (std::size_t h = i; h < j; ++h) add_edge(half_edges[h], nullptr);
    }
    i = j;
  }
  return lengths;
}

/// Edges renumbered in the order the faces first use them: the faces are in
/// locality order, and propagation reads the edges of nearby faces together
/// (their windows, lengths and faces), so their data shares cache lines.
void renumber_edges_by_first_use(PropagationMesh& pm, const std::vector<double>& lengths) {
  constexpr Index kUnnumbered = -1;
  std::vector<Index> new_edge(pm.edge_faces.size(), kUnnumbered);
  Index next = 0;
  for (FaceRecord& record : pm.face_records) {
    if (!record.included()) continue;
    for (int k = 0; k < 3; ++k) {
      Index& id = new_edge[record.edge(k)];
      if (id == kUnnumbered) id = next++;
      record.edge_bits[k] = static_cast<std::uint32_t>(id) | (record.edge_bits[k] & ~FaceRecord::kEdgeMask);
    }
  }
  std::vector<std::array<Index, 2>> edge_faces(pm.edge_faces.size());
  std::vector<double> edge_lengths(lengths.size());
  for (std::size_t e = 0; e < new_edge.size(); ++e) {
    edge_faces[new_edge[e]] = pm.edge_faces[e];
    edge_lengths[new_edge[e]] = lengths[e];
  }
  pm.edge_faces = std::move(edge_faces);
  pm.edge_length_storage = std::move(edge_lengths);
  pm.edge_lengths = pm.edge_length_storage;
}

/// One face per vertex (its first), and a start for each further fan of a
/// vertex where several fans meet, found with a vertex -> faces table that
/// goes again once they are known.
void build_vertex_fans(const TriangleMesh& mesh, PropagationMesh& pm) {
  const Index num_vertices = mesh.num_vertices();
  const Index num_faces = mesh.num_faces();
  std::vector<Index> begin(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (Index f = 0; f < num_faces; ++f) {
    if (!pm.included(f)) continue;
    for (int k = 0; k < 3; ++k) ++begin[mesh.faces(f, k) + 1];
  }
  for (Index v = 0; v < num_vertices; ++v) begin[v + 1] += begin[v];
  std::vector<Index> faces(static_cast<std::size_t>(begin.back()));
  {
    std::vector<Index> fill(begin.begin(), begin.end() - 1);
    for (Index f = 0; f < num_faces; ++f) {
      if (!pm.included(f)) continue;
      for (int k = 0; k < 3; ++k) faces[fill[mesh.faces(f, k)]++] = f;
    }
  }
  pm.vertex_face.assign(static_cast<std::size_t>(num_vertices), -1);
  pm.fan_offsets.assign(static_cast<std::size_t>(num_vertices), {});
  for (Index v = 0; v < num_vertices; ++v) {
    const Index count = begin[v + 1] - begin[v];
    if (count == 0) continue;
    std::array<std::uint8_t, PropagationMesh::kFanOffsets>& offsets = pm.fan_offsets[v];
    const Index base = faces[begin[v]];
    if (count - 1 > PropagationMesh::kFanOffsets || faces[begin[v + 1] - 1] - base > PropagationMesh::kFanMaxOffset) {
      offsets[0] = PropagationMesh::kFanWalked;
      continue;
    }
    for (Index i = 1; i < count; ++i) offsets[i - 1] = static_cast<std::uint8_t>(faces[begin[v] + i] - base);
  }
  std::vector<Index> reached_from(static_cast<std::size_t>(num_faces), -1);  // the vertex whose fans reached the face
  for (Index v = 0; v < num_vertices; ++v) {
    if (begin[v] == begin[v + 1]) continue;
    pm.vertex_face[v] = faces[begin[v]];
    for (Index i = begin[v]; i < begin[v + 1]; ++i) {
      const Index start = faces[i];
      if (reached_from[start] == v) continue;
      if (i > begin[v]) pm.extra_fans.push_back({v, start});
      pm.walk_fan(v, start, [&](Index f) { reached_from[f] = v; });
    }
  }
}

/// The pseudo-sources of `pm`: vertices where shortest paths may bend.
void mark_pseudo_sources(const TriangleMesh& mesh, PropagationMesh& pm) {
  const Index num_vertices = mesh.num_vertices();
  const Index num_faces = mesh.num_faces();
  // Longest edge per face; angle sums; boundary vertices.
  std::vector<double> angle_sum(num_vertices, 0.0);
  std::vector<std::uint8_t> on_boundary(num_vertices, 0);
  for (Index f = 0; f < num_faces; ++f) {
    if (!pm.included(f)) continue;
    const auto angles = corner_angles(pm, f);
    for (int k = 0; k < 3; ++k) {
      angle_sum[mesh.faces(f, k)] += angles[k];
      if (pm.edge_faces[pm.face_edges(f)[k]][1] < 0) {
        on_boundary[mesh.faces(f, k)] = 1;
        on_boundary[mesh.faces(f, (k + 1) % 3)] = 1;
      }
    }
  }

  // A vertex is a pseudo-source when shortest paths may bend around it: a
  // saddle (angle sum > 2 pi), a boundary vertex, or a vertex where several
  // fans meet. Flat vertices (within 1e-9 rad) count as saddles: an extra
  // pseudo-source costs a little time but never accuracy.
  constexpr double kSaddleTolerance = 1e-9;
  pm.is_pseudo_source.assign(num_vertices, 0);
  for (const auto& [v, face] : pm.extra_fans) pm.is_pseudo_source[v] = 1;
  for (Index v = 0; v < num_vertices; ++v) {
    if (pm.vertex_face[v] < 0) continue;
    const bool saddle = angle_sum[v] > 2 * std::numbers::pi - kSaddleTolerance;
    pm.is_pseudo_source[v] |= static_cast<std::uint8_t>(saddle || on_boundary[v]);
  }
}

}  // namespace

PropagationMesh build_propagation_mesh(const TriangleMesh& mesh) {
  PropagationMesh pm;
  const std::vector<double> lengths = build_edges(mesh, pm);
  renumber_edges_by_first_use(pm, lengths);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!pm.included(f)) continue;
    for (int k = 0; k < 3; ++k) pm.face_records[f].vertex[k] = mesh.faces(f, k);
  }
  build_vertex_fans(mesh, pm);
  mark_pseudo_sources(mesh, pm);
  return pm;
}

}  // namespace geodual::voronoi::detail
