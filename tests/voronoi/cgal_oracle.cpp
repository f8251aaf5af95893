// The only translation unit of the voronoi tests that includes CGAL.
#include "voronoi/cgal_oracle.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace geodual::test {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Traits = CGAL::Surface_mesh_shortest_path_traits<Kernel, Mesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;
using VertexIndex = Mesh::Vertex_index;
using FaceIndex = Mesh::Face_index;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// CGAL 5.5's expand_root() passes the weight of the edge's source corner as
/// the parameter t of face_location(halfedge, t), which gives that weight to
/// the edge's *target*: a source point on an edge is mirrored along the edge
/// (an interior or vertex source is not affected, nor are queries). Measured
/// once on a unit square split along its diagonal, so that the oracle stays
/// right whether or not the installed CGAL has the defect.
bool cgal_mirrors_edge_sources() {
  static const bool mirrors = [] {
    Mesh sm;
    const VertexIndex v0 = sm.add_vertex(Kernel::Point_3(0, 0, 0)), v1 = sm.add_vertex(Kernel::Point_3(1, 0, 0)),
                      v2 = sm.add_vertex(Kernel::Point_3(1, 1, 0)), v3 = sm.add_vertex(Kernel::Point_3(0, 1, 0));
    const FaceIndex f = sm.add_face(v0, v1, v2);
    sm.add_face(v0, v2, v3);
    // The point 0.8 v0 + 0.2 v2 on the diagonal, in CGAL's corner order.
    const auto h = sm.halfedge(f);
    const VertexIndex corners[3] = {sm.source(h), sm.target(h), sm.target(sm.next(h))};
    std::array<double, 3> b{};
    for (int i = 0; i < 3; ++i) b[static_cast<std::size_t>(i)] = corners[i] == v0 ? 0.8 : corners[i] == v2 ? 0.2 : 0.0;
    ShortestPath solver(sm);
    solver.add_source_point(f, ShortestPath::Barycentric_coordinates{{b[0], b[1], b[2]}});
    const double to_v0 = solver.shortest_distance_to_source_points(v0).first;
    const double right = 0.2 * std::sqrt(2.0), mirrored = 0.8 * std::sqrt(2.0);
    if (std::abs(to_v0 - right) < 1e-12) return false;
    if (std::abs(to_v0 - mirrored) < 1e-12) return true;
    throw std::runtime_error("cgal_geodesic: CGAL places an edge source neither right nor mirrored");
  }();
  return mirrors;
}

}  // namespace

OracleResult cgal_geodesic(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                           std::span<const SurfacePoint> queries) {
  OracleResult out;
  const auto t0 = std::chrono::steady_clock::now();

  // Compact the vertices referenced by faces that take part (CGAL's
  // Surface_mesh_shortest_path expects no isolated vertices).
  const Index nv = mesh.num_vertices(), nf = mesh.num_faces();
  std::vector<Index> to_cgal(static_cast<std::size_t>(nv), -1);
  std::vector<Index> from_cgal;
  std::vector<FaceIndex> cgal_face(static_cast<std::size_t>(nf));
  Mesh sm;
  auto takes_part = [&](Index f) {
    return mesh.faces(f, 0) != mesh.faces(f, 1) && mesh.faces(f, 1) != mesh.faces(f, 2) &&
           mesh.faces(f, 0) != mesh.faces(f, 2);
  };
  for (Index f = 0; f < nf; ++f) {
    if (!takes_part(f)) continue;
    for (int c = 0; c < 3; ++c) {
      const Index v = mesh.faces(f, c);
      if (to_cgal[v] < 0) {
        to_cgal[v] = static_cast<Index>(from_cgal.size());
        from_cgal.push_back(v);
      }
    }
  }
  for (Index v : from_cgal) {
    sm.add_vertex(Kernel::Point_3(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2)));
  }
  for (Index f = 0; f < nf; ++f) {
    if (!takes_part(f)) {
      cgal_face[f] = Mesh::null_face();
      continue;
    }
    const FaceIndex cf = sm.add_face(VertexIndex(static_cast<Mesh::size_type>(to_cgal[mesh.faces(f, 0)])),
                                     VertexIndex(static_cast<Mesh::size_type>(to_cgal[mesh.faces(f, 1)])),
                                     VertexIndex(static_cast<Mesh::size_type>(to_cgal[mesh.faces(f, 2)])));
    if (cf == Mesh::null_face()) {
      throw std::runtime_error("cgal_geodesic: face " + std::to_string(f) + " is not manifold; use a clean mesh");
    }
    cgal_face[f] = cf;
  }

  // CGAL's barycentric coordinates of face f refer to source(h), target(h),
  // target(next(h)) with h = halfedge(f); map ours (corners 0, 1, 2) onto them.
  // Source points on an edge are pre-mirrored where CGAL mirrors them.
  auto to_cgal_location = [&](const SurfacePoint& p, bool is_source) {
    const Index f = p.element;
    if (f < 0 || f >= nf || cgal_face[f] == Mesh::null_face()) {
      throw std::runtime_error("cgal_geodesic: face point on a face that takes no part");
    }
    const FaceIndex cf = cgal_face[f];
    const auto h = sm.halfedge(cf);
    const VertexIndex cv[3] = {sm.source(h), sm.target(h), sm.target(sm.next(h))};
    std::array<double, 3> b{};
    for (int i = 0; i < 3; ++i) {
      const Index ours = from_cgal[static_cast<std::size_t>(cv[i])];
      int corner = -1;
      for (int c = 0; c < 3; ++c) {
        if (mesh.faces(f, c) == ours) corner = c;
      }
      if (corner < 0) throw std::runtime_error("cgal_geodesic: face corner mapping failed");
      b[static_cast<std::size_t>(i)] = p.barycentric[corner];
    }
    const int zeros = (b[0] == 0) + (b[1] == 0) + (b[2] == 0);
    if (is_source && zeros == 1 && cgal_mirrors_edge_sources()) {
      const std::size_t zero = b[0] == 0 ? 0 : b[1] == 0 ? 1 : 2;
      std::swap(b[(zero + 1) % 3], b[(zero + 2) % 3]);
    }
    return ShortestPath::Face_location(cf, ShortestPath::Barycentric_coordinates{{b[0], b[1], b[2]}});
  };

  out.build_mesh_seconds = seconds_since(t0);
  const auto t1 = std::chrono::steady_clock::now();

  ShortestPath solver(sm);
  std::unordered_map<const void*, Index> site_of;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const SurfacePoint& s = sites[i];
    ShortestPath::Source_point_iterator it;
    if (s.kind == SurfacePoint::Kind::vertex) {
      if (s.element < 0 || s.element >= nv || to_cgal[s.element] < 0) {
        throw std::runtime_error("cgal_geodesic: site on an unreferenced vertex");
      }
      it = solver.add_source_point(VertexIndex(static_cast<Mesh::size_type>(to_cgal[s.element])));
    } else {
      it = solver.add_source_point(to_cgal_location(s, true));
    }
    site_of[static_cast<const void*>(&*it)] = static_cast<Index>(i);
  }
  solver.build_sequence_tree();

  const double inf = std::numeric_limits<double>::infinity();
  out.distance.assign(static_cast<std::size_t>(nv), inf);
  out.nearest_site.assign(static_cast<std::size_t>(nv), -1);
  for (std::size_t i = 0; i < from_cgal.size(); ++i) {
    const auto result = solver.shortest_distance_to_source_points(VertexIndex(static_cast<Mesh::size_type>(i)));
    if (result.first < 0 || result.second == solver.source_points_end()) continue;
    const Index v = from_cgal[i];
    out.distance[v] = result.first;
    out.nearest_site[v] = site_of.at(static_cast<const void*>(&*result.second));
  }
  for (const SurfacePoint& q : queries) {
    if (q.kind != SurfacePoint::Kind::face) throw std::runtime_error("cgal_geodesic: queries must be face points");
    const auto location = to_cgal_location(q, false);
    const auto result = solver.shortest_distance_to_source_points(location.first, location.second);
    if (result.first < 0 || result.second == solver.source_points_end()) {
      out.query_distance.push_back(inf);
      out.query_site.push_back(-1);
    } else {
      out.query_distance.push_back(result.first);
      out.query_site.push_back(site_of.at(static_cast<const void*>(&*result.second)));
    }
  }
  out.solve_seconds = seconds_since(t1);
  return out;
}

}  // namespace geodual::test
