#include "sampling/sampling_surface.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

namespace geodual::remesh::detail {
namespace {

/// Groups `items` (face indices) by `key` (component) into CSR arrays, keeping
/// the items' order within a group.
void group_by_component(const std::vector<Index>& items, const std::vector<Index>& face_component, Index num_components,
                        std::vector<Index>& begin, std::vector<Index>& grouped) {
  begin.assign(static_cast<std::size_t>(num_components) + 1, 0);
  for (const Index f : items) ++begin[face_component[f] + 1];
  for (Index c = 0; c < num_components; ++c) begin[c + 1] += begin[c];
  grouped.resize(items.size());
  std::vector<Index> fill(begin.begin(), begin.end() - 1);
  for (const Index f : items) grouped[fill[face_component[f]]++] = f;
}

void find_boundary_loops(SamplingSurface& surface, const MeshTopology& topology) {
  const TriangleMesh& mesh = *surface.mesh;
  // Boundary edges (one face) as the corner of their face they start at, in
  // edge order.
  struct HalfEdge {
    Index face;
    int corner;
  };
  std::vector<HalfEdge> boundary;
  for (Index e = 0; e < topology.num_edges(); ++e) {
    if (!topology.is_boundary_edge(e)) continue;
    const Index face = topology.edge_faces(e)[0];
    const std::array<Index, 3>& edges = topology.face_edges[static_cast<std::size_t>(face)];
    boundary.push_back({face, edges[0] == e ? 0 : edges[1] == e ? 1 : 2});
  }
  if (boundary.empty()) return;

  // Boundary edges around each vertex (CSR, edges in increasing order).
  auto from = [&](const HalfEdge& e) { return mesh.faces(e.face, e.corner); };
  auto to = [&](const HalfEdge& e) { return mesh.faces(e.face, (e.corner + 1) % 3); };
  const auto num_vertices = static_cast<std::size_t>(mesh.num_vertices());
  std::vector<Index> begin(num_vertices + 1, 0);
  for (const HalfEdge& e : boundary) {
    ++begin[from(e) + 1];
    ++begin[to(e) + 1];
  }
  for (std::size_t v = 0; v < num_vertices; ++v) begin[v + 1] += begin[v];
  std::vector<Index> incident(static_cast<std::size_t>(begin.back()));
  {
    std::vector<Index> fill(begin.begin(), begin.end() - 1);
    for (Index e = 0; e < static_cast<Index>(boundary.size()); ++e) {
      incident[fill[from(boundary[e])]++] = e;
      incident[fill[to(boundary[e])]++] = e;
    }
  }
  std::vector<Index> cursor(begin.begin(), begin.end() - 1);  // first incident edge not yet tried
  std::vector<std::uint8_t> used(boundary.size(), 0);
  auto next_unused = [&](Index v) -> Index {
    while (cursor[v] < begin[v + 1]) {
      const Index e = incident[cursor[v]];
      if (!used[e]) return e;
      ++cursor[v];
    }
    return -1;
  };

  // Walks that use every boundary edge once. Loops of a 2-manifold close;
  // loops that touch at a pinch vertex may be walked as one figure eight;
  // on broken meshes (a vertex with an odd number of boundary edges) walks
  // start at such a vertex and end at another, and are sampled as open
  // chains.
  std::vector<std::pair<Index, bool>> walk;  // (edge, run against its direction)
  auto add_walk = [&](bool closed) {
    BoundaryLoop loop;
    loop.closed = closed;
    for (const auto& [e, reversed] : walk) {
      const HalfEdge& h = boundary[e];
      if (!(surface.face_area[h.face] > 0)) continue;
      const Index a = mesh.faces(h.face, h.corner), b = mesh.faces(h.face, (h.corner + 1) % 3);
      const double length = (mesh.vertices.row(b) - mesh.vertices.row(a)).norm();
      loop.edges.push_back({h.face, h.corner, length, reversed});
      loop.length += length;
    }
    if (!loop.edges.empty() && loop.length > 0) {
      loop.component = surface.face_component[loop.edges.front().face];
      surface.boundary_loops.push_back(std::move(loop));
    }
    walk.clear();
  };
  auto walk_from = [&](Index v) {
    for (Index e = next_unused(v); e >= 0; e = next_unused(v)) {
      used[e] = 1;
      const bool reversed = from(boundary[e]) != v;
      walk.emplace_back(e, reversed);
      v = reversed ? from(boundary[e]) : to(boundary[e]);
    }
  };
  for (Index v = 0; v < static_cast<Index>(num_vertices); ++v) {
    if ((begin[v + 1] - begin[v]) % 2 == 1 && next_unused(v) >= 0) {
      walk_from(v);
      add_walk(false);
    }
  }
  for (Index e = 0; e < static_cast<Index>(boundary.size()); ++e) {
    if (used[e]) continue;
    // Start along the edge's own direction, so that closed loops run the way
    // their faces orient them.
    // Every vertex has an even number of unused edges left, so the walk
    // comes back to where it started.
    used[e] = 1;
    walk.emplace_back(e, false);
    walk_from(to(boundary[e]));
    add_walk(true);
  }
  // Loops of components without area are of no use (they get no sites).
  std::erase_if(surface.boundary_loops,
                [&](const BoundaryLoop& loop) { return !(surface.component_area[loop.component] > 0); });
}

}  // namespace

std::uint64_t Rng::lattice_interior() {
  for (;;) {
    const std::uint64_t x = next() >> 32;
    if (x != 0) return x;
  }
}

SurfacePoint point_in_face_from_square(Index face, std::uint64_t a, std::uint64_t b) {
  // Folding the half a + b > 2^32 of the lattice square onto the other
  // (a, b -> 2^32 - a, 2^32 - b) maps it onto the triangle, two to one and
  // area-preserving; the diagonal a + b = 2^32 would give a point on an edge.
  if (a + b == kLattice) b > 1 ? --b : --a;
  if (a + b > kLattice) {
    a = kLattice - a;
    b = kLattice - b;
  }
  const std::uint64_t c = kLattice - a - b;
  return SurfacePoint::in_face(face, static_cast<double>(a) * kLatticeUnit, static_cast<double>(b) * kLatticeUnit,
                               static_cast<double>(c) * kLatticeUnit);
}

SurfacePoint random_point_in_face(Index face, Rng& rng) {
  for (;;) {
    const std::uint64_t a = rng.lattice_interior();
    const std::uint64_t b = rng.lattice_interior();
    if (a + b != kLattice) return point_in_face_from_square(face, a, b);  // else draw again: keeps it uniform
  }
}

SurfacePoint point_on_face_edge(Index face, int corner, double t) {
  constexpr double kMargin = 0x1p-20;
  t = std::clamp(t, kMargin, 1 - kMargin);
  const auto along = static_cast<std::uint64_t>(std::llround(t * static_cast<double>(kLattice)));
  Eigen::Vector3d barycentric;
  barycentric[corner] = static_cast<double>(kLattice - along) * kLatticeUnit;
  barycentric[(corner + 1) % 3] = static_cast<double>(along) * kLatticeUnit;
  barycentric[(corner + 2) % 3] = 0.0;
  return SurfacePoint::in_face(face, barycentric[0], barycentric[1], barycentric[2]);
}

Index SamplingSurface::random_face(Index component, Rng& rng) const {
  const auto first = component_cumulative_area.begin() + component_area_face_begin[component];
  const auto last = component_cumulative_area.begin() + component_area_face_begin[component + 1];
  const double total = *(last - 1);
  const double r = rng.uniform() * total;
  // First face whose running sum exceeds r; r < total unless rounding says
  // otherwise, hence the clamp to the last face.
  auto it = std::upper_bound(first, last, r);
  if (it == last) --it;
  return component_area_faces[static_cast<std::size_t>(it - component_cumulative_area.begin())];
}

void SamplingSurface::stratified_points(Index component, std::int64_t count, Rng& rng,
                                        std::vector<SurfacePoint>& out) const {
  // R2 sequence (Roberts 2018): steps 1/g and 1/g^2, g the plastic number.
  constexpr double kPlastic = 1.32471795724474602596;
  constexpr double kStep[2] = {1 / kPlastic, 1 / (kPlastic * kPlastic)};
  auto to_lattice = [](double x) {
    return std::clamp<std::uint64_t>(static_cast<std::uint64_t>(x * static_cast<double>(kLattice)), 1, kLattice - 1);
  };
  const Index begin = component_area_face_begin[component], end = component_area_face_begin[component + 1];
  const double total = component_cumulative_area[end - 1];
  const double offset = rng.uniform();
  Index at = begin;
  Index current = -1;
  std::int64_t j = 0;
  double start[2] = {0, 0};
  for (std::int64_t i = 0; i < count; ++i) {
    const double target = (static_cast<double>(i) + offset) * total / static_cast<double>(count);
    while (at + 1 < end && component_cumulative_area[at] <= target) ++at;
    if (at != current) {
      current = at;
      j = 0;
      start[0] = rng.uniform();
      start[1] = rng.uniform();
    }
    double x[2];
    for (int k = 0; k < 2; ++k) {
      x[k] = start[k] + static_cast<double>(j) * kStep[k];
      x[k] -= std::floor(x[k]);
    }
    ++j;
    out.push_back(point_in_face_from_square(component_area_faces[at], to_lattice(x[0]), to_lattice(x[1])));
  }
}

namespace {

/// build_sampling_surface with `prepared` the mesh's topology, or built here
/// (after the faces are checked) when null.
SamplingSurface sampling_surface(const TriangleMesh& mesh, const MeshTopology* prepared, bool with_boundary_loops) {
  SamplingSurface surface;
  surface.mesh = &mesh;
  const Index num_faces = mesh.num_faces();
  const Index num_vertices = mesh.num_vertices();

  surface.face_area.assign(static_cast<std::size_t>(num_faces), 0.0);
  std::vector<Index> proper_faces;
  for (Index f = 0; f < num_faces; ++f) {
    for (int k = 0; k < 3; ++k) {
      if (mesh.faces(f, k) < 0 || mesh.faces(f, k) >= num_vertices) {
        throw Error("sample_sites: face " + std::to_string(f) + " refers to vertex " +
                    std::to_string(mesh.faces(f, k)) + ", out of range [0, " + std::to_string(num_vertices) + ")");
      }
    }
    if (has_repeated_corner(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) {
      if (!mesh.vertices.row(mesh.faces(f, k)).allFinite()) {
        throw Error("sample_sites: vertex " + std::to_string(mesh.faces(f, k)) + " (a corner of face " +
                    std::to_string(f) + ") has a coordinate that is not a finite number");
      }
    }
    proper_faces.push_back(f);
    // Overflow, or a face too thin for the geodesic engine: no site there.
    surface.face_area[f] = has_positive_area(mesh, f) ? face_area(mesh, f) : 0.0;
  }
  // Components: faces joined through shared vertices, in the order of their first face.
  std::optional<MeshTopology> built;
  const MeshTopology& topology = prepared ? *prepared : built.emplace(build_mesh_topology(mesh));
  surface.face_component = topology.face_component;
  surface.num_components = topology.num_components();
  group_by_component(proper_faces, surface.face_component, surface.num_components, surface.component_face_begin,
                     surface.component_faces);

  std::vector<Index> area_faces;
  for (const Index f : proper_faces) {
    if (surface.face_area[f] > 0) area_faces.push_back(f);
  }
  group_by_component(area_faces, surface.face_component, surface.num_components, surface.component_area_face_begin,
                     surface.component_area_faces);
  surface.component_cumulative_area.resize(surface.component_area_faces.size());
  surface.component_area.assign(static_cast<std::size_t>(surface.num_components), 0.0);
  for (Index c = 0; c < surface.num_components; ++c) {
    double sum = 0;
    for (Index i = surface.component_area_face_begin[c]; i < surface.component_area_face_begin[c + 1]; ++i) {
      sum += surface.face_area[surface.component_area_faces[i]];
      surface.component_cumulative_area[i] = sum;
    }
    surface.component_area[c] = sum;
  }
  if (with_boundary_loops) find_boundary_loops(surface, topology);
  return surface;
}

}  // namespace

SamplingSurface build_sampling_surface(const TriangleMesh& mesh, bool with_boundary_loops) {
  return sampling_surface(mesh, nullptr, with_boundary_loops);
}

SamplingSurface build_sampling_surface(const TriangleMesh& mesh, const MeshTopology& topology,
                                       bool with_boundary_loops) {
  return sampling_surface(mesh, &topology, with_boundary_loops);
}

/// Splits `total` into integer parts proportional to `weights` (all > 0),
/// part i at least minimum[i] (total >= sum of the minimums): parts whose
/// share falls below their minimum are fixed there and the rest is shared
/// again; then largest remainders, ties to the lower index.
std::vector<std::int64_t> proportional_split(const std::vector<double>& weights,
                                             const std::vector<std::int64_t>& minimum, std::int64_t total,
                                             const std::vector<double>& held) {
  const std::size_t n = weights.size();
  std::vector<std::int64_t> part(n, 0);
  std::vector<std::uint8_t> fixed(n, 0);
  const auto held_by = [&](std::size_t i) { return held.empty() ? 0.0 : held[i]; };
  for (;;) {
    std::int64_t rest = total;
    double weight = 0, held_free = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (fixed[i]) {
        rest -= minimum[i];
      } else {
        weight += weights[i];
        held_free += held_by(i);
      }
    }
    // Part i's share of what the free parts hold in all, less what it holds.
    const auto share_of = [&](std::size_t i) {
      return (static_cast<double>(rest) + held_free) * weights[i] / weight - held_by(i);
    };
    bool changed = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (!fixed[i] && share_of(i) < static_cast<double>(minimum[i])) {
        fixed[i] = 1;
        changed = true;
      }
    }
    if (changed) continue;
    std::vector<std::pair<double, std::size_t>> remainders;
    std::int64_t given = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (fixed[i]) {
        part[i] = minimum[i];
      } else {
        const double share = share_of(i);
        part[i] = std::max(minimum[i], static_cast<std::int64_t>(share));
        remainders.push_back({share - static_cast<double>(part[i]), i});
      }
      given += part[i];
    }
    std::stable_sort(remainders.begin(), remainders.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    // Rounding may leave a part or two over or under; settle it on the
    // largest remainders (or take from the smallest, never below minimum).
    for (std::size_t k = 0; given < total && !remainders.empty(); k = (k + 1) % remainders.size(), ++given) {
      ++part[remainders[k].second];
    }
    for (bool progress = true; given > total && progress;) {
      progress = false;
      for (std::size_t k = remainders.size(); k-- > 0 && given > total;) {
        const std::size_t i = remainders[k].second;
        if (part[i] > minimum[i]) {
          --part[i];
          --given;
          progress = true;
        }
      }
    }
    return part;
  }
}

}  // namespace geodual::remesh::detail
