#include "propagation_mesh.hpp"

#include "geodual/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace geodual::voronoi::detail {
namespace {

/// Twice the area of a triangle with side lengths a, b, c, by Kahan's
/// cancellation-free form of Heron's formula (0 for impossible lengths).
double twice_area_from_lengths(double a, double b, double c) {
  if (a < b) std::swap(a, b);
  if (b < c) std::swap(b, c);
  if (a < b) std::swap(a, b);
  const double product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return product > 0 ? 0.5 * std::sqrt(product) : 0.0;
}

/// Interior angle at each corner of a face, from its planar layout.
std::array<double, 3> corner_angles(const PropagationMesh& pm, Index face) {
  const EdgeLayout l = pm.layout(face, 0);
  const double at0 = std::atan2(l.apex.y(), l.apex.x());
  const double at1 = std::atan2(l.apex.y(), l.length - l.apex.x());
  return {at0, at1, std::max(0.0, std::numbers::pi - at0 - at1)};
}

/// Faces reachable from `start` by turning around `v` across shared edges.
Index fan_size(const PropagationMesh& pm, Index v, Index start) {
  Index visited = 1;
  for (int direction = 0; direction < 2; ++direction) {
    Index face = start;
    int corner = 0;
    while (pm.vertex(face, corner) != v) ++corner;
    // The two local edges at corner c are c (c -> c+1) and c+2 (c+2 -> c).
    int exit_edge_local = direction == 0 ? corner : (corner + 2) % 3;
    for (;;) {
      const Index e = pm.face_edges(face)[exit_edge_local];
      const int side = pm.side_of(e, face);
      const Index next = pm.edge_faces[e][1 - side];
      if (next < 0) break;
      if (next == start) return visited;  // closed fan: each face counted once
      ++visited;
      // In `next`, leave through its other edge incident to v.
      const int entry_local = pm.edge_local[e][1 - side];
      int next_corner = 0;
      while (pm.vertex(next, next_corner) != v) ++next_corner;
      exit_edge_local = entry_local == next_corner ? (next_corner + 2) % 3 : next_corner;
      face = next;
    }
  }
  return visited;
}

}  // namespace

PropagationMesh build_propagation_mesh(const TriangleMesh& mesh) {
  PropagationMesh pm;
  const Index num_vertices = mesh.num_vertices();
  const Index num_faces = mesh.num_faces();

  // Half-edges of the included faces, sorted by their undirected vertex pair.
  struct HalfEdge {
    std::uint64_t key;
    Index face;
    std::int32_t local;
  };
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(static_cast<std::size_t>(num_faces) * 3);
  for (Index f = 0; f < num_faces; ++f) {
    const Index a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    if (a == b || b == c || c == a) continue;
    ++pm.num_included_faces;
    for (int k = 0; k < 3; ++k) {
      const auto u = static_cast<std::uint64_t>(mesh.faces(f, k));
      const auto w = static_cast<std::uint64_t>(mesh.faces(f, (k + 1) % 3));
      half_edges.push_back({std::min(u, w) << 32 | std::max(u, w), f, k});
    }
  }
  std::sort(half_edges.begin(), half_edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.key != y.key ? x.key < y.key : (x.face != y.face ? x.face < y.face : x.local < y.local);
  });
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
  pm.edge_local.reserve(num_edges);
  pm.edge_lengths.reserve(num_edges);

  if (num_edges > FaceRecord::kEdgeMask) {
    throw Error("meshes of more than 2^30 edges are not supported");
  }
  pm.face_records.assign(num_faces, FaceRecord{});
  auto add_edge = [&](const HalfEdge& first, const HalfEdge* second) {
    const Index e = static_cast<Index>(pm.edge_faces.size());
    const Index v0 = mesh.faces(first.face, first.local);
    const Index v1 = mesh.faces(first.face, (first.local + 1) % 3);
    const double length = (mesh.vertices.row(v1) - mesh.vertices.row(v0)).norm();
    auto attach = [&](const HalfEdge& half, std::uint32_t flags) {
      pm.face_records[half.face].edge_bits[half.local] = static_cast<std::uint32_t>(e) | flags;
    };
    pm.edge_lengths.push_back(length);
    attach(first, 0);
    if (second != nullptr) {
      const bool reversed = mesh.faces(second->face, second->local) == v1;
      attach(*second, FaceRecord::kSide1 | (reversed ? FaceRecord::kReversed : 0));
      pm.edge_faces.push_back({first.face, second->face});
      pm.edge_local.push_back({static_cast<std::uint8_t>(first.local), static_cast<std::uint8_t>(second->local)});
    } else {
      pm.edge_faces.push_back({first.face, -1});
      pm.edge_local.push_back({static_cast<std::uint8_t>(first.local), 0});
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
  half_edges.clear();
  half_edges.shrink_to_fit();

  for (Index f = 0; f < num_faces; ++f) {
    if (!pm.included(f)) continue;
    FaceRecord& r = pm.face_records[f];
    for (int k = 0; k < 3; ++k) r.vertex[k] = mesh.faces(f, k);
    const std::array<double, 3> lengths = pm.face_lengths(r);
    r.twice_area = twice_area_from_lengths(lengths[0], lengths[1], lengths[2]);
  }

  // Vertex -> faces, by counting sort (faces in increasing order).
  pm.vertex_face_begin.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (Index f = 0; f < num_faces; ++f) {
    if (!pm.included(f)) continue;
    for (int k = 0; k < 3; ++k) ++pm.vertex_face_begin[mesh.faces(f, k) + 1];
  }
  for (Index v = 0; v < num_vertices; ++v) pm.vertex_face_begin[v + 1] += pm.vertex_face_begin[v];
  pm.vertex_faces.resize(pm.vertex_face_begin.back());
  {
    std::vector<Index> fill(pm.vertex_face_begin.begin(), pm.vertex_face_begin.end() - 1);
    for (Index f = 0; f < num_faces; ++f) {
      if (!pm.included(f)) continue;
      for (int k = 0; k < 3; ++k) pm.vertex_faces[fill[mesh.faces(f, k)]++] = f;
    }
  }

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
  for (Index v = 0; v < num_vertices; ++v) {
    const Index begin = pm.vertex_face_begin[v], end = pm.vertex_face_begin[v + 1];
    if (begin == end) continue;
    const bool saddle = angle_sum[v] > 2 * std::numbers::pi - kSaddleTolerance;
    const bool several_fans = !on_boundary[v] && fan_size(pm, v, pm.vertex_faces[begin]) < end - begin;
    pm.is_pseudo_source[v] = saddle || on_boundary[v] || several_fans;
  }
  return pm;
}

}  // namespace geodual::voronoi::detail
