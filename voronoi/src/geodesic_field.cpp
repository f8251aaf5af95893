#include "geodual/voronoi/geodesic_field.hpp"

#include "geodual/mesh/detail/trim_heap.hpp"
#include "geodual/mesh/error.hpp"
#include "prepared_surface.hpp"
#include "window_vtp.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

namespace geodual::voronoi {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string site_name(std::size_t i) { return "site " + std::to_string(i); }

/// The vertices of the smallest element holding a site (its vertex, the edge
/// or the face it lies inside), increasing, -1 for the rest.
std::array<Index, 3> carrier(const TriangleMesh& mesh, const SurfacePoint& site) {
  std::array<Index, 3> vertices = {-1, -1, -1};
  if (site.kind == SurfacePoint::Kind::vertex) {
    vertices[0] = site.element;
    return vertices;
  }
  int n = 0;
  for (int c = 0; c < 3; ++c) {
    if (site.barycentric[c] > 0) vertices[static_cast<std::size_t>(n++)] = mesh.faces(site.element, c);
  }
  std::sort(vertices.begin(), vertices.begin() + n);
  return vertices;
}

/// Checks every site and brings it to a canonical form: a face point with two
/// zero barycentric coordinates becomes a vertex site.
std::vector<SurfacePoint> validated_sites(const TriangleMesh& mesh, const detail::PropagationMesh& pm,
                                          const detail::LocalityOrder& locality, std::span<const SurfacePoint> sites) {
  std::vector<SurfacePoint> result(sites.begin(), sites.end());
  for (std::size_t i = 0; i < result.size(); ++i) {
    SurfacePoint& site = result[i];
    if (site.kind == SurfacePoint::Kind::vertex) {
      if (site.element < 0 || site.element >= mesh.num_vertices()) {
        throw Error(site_name(i) + ": vertex index " + std::to_string(site.element) + " is out of range [0, " +
                    std::to_string(mesh.num_vertices()) + ")");
      }
    } else {
      if (site.element < 0 || site.element >= mesh.num_faces()) {
        throw Error(site_name(i) + ": face index " + std::to_string(site.element) + " is out of range [0, " +
                    std::to_string(mesh.num_faces()) + ")");
      }
      Eigen::Vector3d& b = site.barycentric;
      if (!b.allFinite() || b.minCoeff() < -1e-12 || std::abs(b.sum() - 1) > 1e-9) {
        throw Error(site_name(i) + ": barycentric coordinates (" + std::to_string(b[0]) + ", " + std::to_string(b[1]) +
                    ", " + std::to_string(b[2]) + ") must be non-negative and sum to 1");
      }
      for (int c = 0; c < 3; ++c) b[c] = b[c] < 1e-14 ? 0.0 : b[c];
      b /= b.sum();
      const Index local_face = locality.new_face[site.element];
      if (!pm.included(local_face)) {
        throw Error(site_name(i) + ": face " + std::to_string(site.element) +
                    " repeats a vertex index and takes no part in the surface");
      }
      int nonzero = 0, corner = 0;
      for (int c = 0; c < 3; ++c) {
        if (b[c] > 0) ++nonzero, corner = c;
      }
      if (nonzero == 1) {
        site = SurfacePoint::at_vertex(mesh.faces(site.element, corner));
      } else if (!has_area_from_lengths(pm.face_lengths(pm.face_records[local_face]))) {
        throw Error(site_name(i) + ": face " + std::to_string(site.element) +
                    " has zero area; place the site on a neighbouring face");
      }
    }
    if (site.kind == SurfacePoint::Kind::vertex && pm.vertex_face[locality.new_vertex[site.element]] < 0) {
      throw Error(site_name(i) + ": vertex " + std::to_string(site.element) + " is used by no triangle");
    }
  }
  // Two sites at the same point would have no cell between them. The same
  // position is the same point only on the same vertex, edge or face: two
  // sides of a cut (a slit, a crease cut open) meet in space but not on the
  // surface.
  std::vector<std::size_t> order(result.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<Eigen::Vector3d> positions(result.size());
  std::vector<std::array<Index, 3>> carriers(result.size());
  for (std::size_t i = 0; i < result.size(); ++i) {
    positions[i] = result[i].position(mesh);
    carriers[i] = carrier(mesh, result[i]);
  }
  auto less = [&](std::size_t a, std::size_t b) {
    const Eigen::Vector3d &p = positions[a], &q = positions[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return carriers[a] != carriers[b] ? carriers[a] < carriers[b] : a < b;
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t i = 1; i < order.size(); ++i) {
    if (positions[order[i]] == positions[order[i - 1]] && carriers[order[i]] == carriers[order[i - 1]]) {
      throw Error(site_name(std::min(order[i], order[i - 1])) + " and " + site_name(std::max(order[i], order[i - 1])) +
                  " are at the same point");
    }
  }
  return result;
}

/// Renumbers per-vertex values in place: value v goes to old_vertex[v]
/// (following each cycle of the permutation; no second array at the peak).
template <class... Values>
void to_caller_numbering(const std::vector<Index>& old_vertex, std::vector<Values>&... values) {
  std::vector<bool> placed(old_vertex.size(), false);
  for (std::size_t start = 0; start < old_vertex.size(); ++start) {
    if (placed[start]) continue;
    // Carry start's values round its cycle: each lands where it belongs and
    // picks up the values that were there.
    auto carried = std::make_tuple(values[start]...);
    for (std::size_t to = static_cast<std::size_t>(old_vertex[start]);; to = static_cast<std::size_t>(old_vertex[to])) {
      placed[to] = true;
      std::apply([&](auto&... carry) { (std::swap(carry, values[to]), ...); }, carried);
      if (to == start) break;
    }
  }
}

/// Runs window-VTP from the sites (in the propagation's numbering) and fills
/// the field's per-face results in the caller's numbering, its per-vertex
/// ones still in the propagation's. Returns the windows; the rest of the
/// propagation's state is freed.
detail::WindowStore propagate(const detail::PropagationMesh& pm, const detail::LocalityOrder& order,
                              const std::vector<SurfacePoint>& local_sites, const GeodesicOptions& options,
                              GeodesicField& field) {
  const auto start = Clock::now();
  detail::WindowVtp vtp(pm, options);
  vtp.add_sites(local_sites);
  vtp.run();
  field.stats = vtp.stats();
  field.stats.propagation_seconds = seconds_since(start);

  const std::vector<bool> valid = vtp.valid_faces();
  field.valid_face.resize(order.old_face.size());
  for (std::size_t f = 0; f < order.old_face.size(); ++f) field.valid_face[order.old_face[f]] = valid[f];
  field.face_point_sources = vtp.point_sources();
  for (FacePointSource& source : field.face_point_sources) source.face = order.old_face[source.face];
  field.distance = vtp.take_distance();  // still in the propagation's numbering
  field.nearest_site = vtp.take_label();
  std::stable_sort(field.face_point_sources.begin(), field.face_point_sources.end(),
                   [](const FacePointSource& a, const FacePointSource& b) { return a.face < b.face; });
  return vtp.take_windows();
}

/// The retained windows into the field, grouped by edge, emptying the store
/// as they go (see WindowStore::drain: the two copies would otherwise be the
/// peak of the whole computation).
void move_windows(detail::WindowStore& store, Index num_edges, GeodesicField& field) {
  constexpr int kRounds = 2;
  field.window_begin.assign(static_cast<std::size_t>(num_edges) + 1, 0);
  field.windows.reserve(static_cast<std::size_t>(store.live()));
  Index next_edge = 0;
  auto take = [&](Index edge, std::span<const detail::Window> windows) {
    for (; next_edge <= edge; ++next_edge) field.window_begin[next_edge] = static_cast<Index>(field.windows.size());
    for (const detail::Window& w : windows) {
      const detail::WindowSource& source = store.source_of(w);
      field.windows.push_back({w.b0, w.b1, w.source_x, w.source_y, source.sigma, source.site});
    }
  };
  store.drain(take, kRounds);
  for (; next_edge <= num_edges; ++next_edge) field.window_begin[next_edge] = static_cast<Index>(field.windows.size());
}

/// compute_geodesic_field on a prepared surface and its topology. For a
/// single field (`disposable`, holding `prepared`, and no topology yet), the
/// topology is made once propagation is over and the surface goes before
/// the windows are moved out: the peak is then what one field needs.
GeodesicField compute_field(const TriangleMesh& mesh, const detail::PreparedSurface& prepared,
                            std::shared_ptr<const SurfaceTopology> topology, std::span<const SurfacePoint> sites,
                            const GeodesicOptions& options, std::optional<detail::PreparedSurface>* disposable) {
  const auto start = Clock::now();
  // Propagation runs on the surface's copy renumbered for memory locality;
  // everything it returns is mapped back to the caller's numbering.
  const detail::PropagationMesh& pm = prepared.propagation;
  const detail::LocalityOrder& order = prepared.order;
  GeodesicField field;
  field.sites = validated_sites(mesh, pm, order, sites);
  std::vector<SurfacePoint> local_sites = field.sites;
  for (SurfacePoint& site : local_sites) {
    site.element =
        site.kind == SurfacePoint::Kind::vertex ? order.new_vertex[site.element] : order.new_face[site.element];
  }
  if (disposable != nullptr) {
    // Only the maps back to the caller's numbering are needed from here on.
    // (Assigning {} would keep a vector's memory.)
    (*disposable)->order.new_vertex = std::vector<Index>();
    (*disposable)->order.new_face = std::vector<Index>();
  }
  const double setup_seconds = seconds_since(start);

  detail::WindowStore windows = propagate(pm, order, local_sites, options, field);
  windows.compact();
  to_caller_numbering(order.old_vertex, field.distance, field.nearest_site);
  field.stats.setup_seconds = setup_seconds;
  const Index num_edges = pm.num_edges();
  if (disposable != nullptr) {
    detail::PreparedSurface& surface = **disposable;
    // What only propagation needed goes first.
    surface.propagation.vertex_face = std::vector<Index>();
    surface.propagation.fan_offsets = decltype(surface.propagation.fan_offsets)();
    surface.propagation.extra_fans = std::vector<std::array<Index, 2>>();
    surface.propagation.is_pseudo_source = std::vector<std::uint8_t>();
    if (!topology)
      topology = std::make_shared<const SurfaceTopology>(detail::caller_topology(surface.propagation, surface.order));
    disposable->reset();
  }
  field.topology = std::move(topology);
  field.edge_vertices = field.topology->edge_vertices;
  field.edge_faces = field.topology->edge_faces;
  field.edge_length = field.topology->edge_length;
  field.face_edges = field.topology->face_edges;
  if (options.release_memory_between_phases) trim_heap();  // the propagation's state (and the surface given up)
  move_windows(windows, num_edges, field);
  field.stats.total_seconds = seconds_since(start);
  return field;
}

}  // namespace

GeodesicField compute_geodesic_field(const GeodesicSurface& surface, std::span<const SurfacePoint> sites,
                                     const GeodesicOptions& options) {
  return compute_field(surface.mesh(), surface.prepared(), surface.topology(), sites, options, nullptr);
}

GeodesicField compute_geodesic_field(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                     const GeodesicOptions& options) {
  const auto start = Clock::now();
  std::optional<detail::PreparedSurface> prepared(detail::prepare_surface(mesh));
  const double preparation_seconds = seconds_since(start);
  if (options.release_memory_between_phases) trim_heap();  // the preparation's scratch
  GeodesicField field = compute_field(mesh, *prepared, nullptr, sites, options, &prepared);
  field.stats.setup_seconds += preparation_seconds;
  field.stats.total_seconds += preparation_seconds;
  return field;
}

PointDistance query(const GeodesicField& field, const TriangleMesh& mesh, const SurfacePoint& point) {
  if (point.kind == SurfacePoint::Kind::vertex) {
    return {field.distance.at(point.element), field.nearest_site.at(point.element)};
  }
  const Index f = point.element;
  PointDistance best{std::numeric_limits<double>::infinity(), -1};
  auto consider = [&](double d, Index site) {
    if (d < best.distance) best = {d, site};
  };
  // Through the face's corners (exact where the path passes a corner).
  const Eigen::Vector3d p = point.position(mesh);
  for (int c = 0; c < 3; ++c) {
    const Index v = mesh.faces(f, c);
    consider(field.distance[v] + (p - mesh.vertices.row(v).transpose()).norm(), field.nearest_site[v]);
  }
  if (field.face_edges[f][0] < 0) return best;
  // Point sources in the face or on its edges.
  const auto [first, last] =
      std::equal_range(field.face_point_sources.begin(), field.face_point_sources.end(), FacePointSource{f},
                       [](const FacePointSource& a, const FacePointSource& b) { return a.face < b.face; });
  for (auto it = first; it != last; ++it) {
    const Eigen::Vector3d q =
        SurfacePoint::in_face(f, it->barycentric[0], it->barycentric[1], it->barycentric[2]).position(mesh);
    consider(it->sigma + (q - p).norm(), it->site);
  }
  // Through the windows entering the face: lay the face out on each edge's
  // frame and look through the window's interval.
  for (int k = 0; k < 3; ++k) {
    const Index e = field.face_edges[f][k];
    const int side = field.edge_faces[e][0] == f ? 0 : 1;
    const Index v0 = field.edge_vertices[e][0], v1 = field.edge_vertices[e][1];
    const Eigen::Vector3d a = mesh.vertices.row(v0).transpose(), b = mesh.vertices.row(v1).transpose();
    const double length = field.edge_length[e];
    if (!(length > 0)) continue;
    const Eigen::Vector3d axis = (b - a) / (b - a).norm();
    const Eigen::Vector3d r = p - a;
    const double x = r.dot(axis);
    const double y_abs = (r - x * axis).norm();
    const double y = side == 0 ? y_abs : -y_abs;  // the face lies on its side of the edge
    for (Index i = field.window_begin[e]; i < field.window_begin[e + 1]; ++i) {
      const EdgeWindow& w = field.windows[i];
      if ((w.source_y < 0) != (side == 0)) continue;  // leaves this face
      // Where the segment from the source to the point crosses the edge.
      const double t = -w.source_y / (y - w.source_y);
      const double crossing = w.source_x + (x - w.source_x) * t;
      if (crossing < w.b0 - 1e-12 * length || crossing > w.b1 + 1e-12 * length) continue;
      consider(w.sigma + std::hypot(x - w.source_x, y - w.source_y), w.site);
    }
  }
  return best;
}

}  // namespace geodual::voronoi
