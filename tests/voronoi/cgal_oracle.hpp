#pragma once
// The independent oracle: CGAL's Surface_mesh_shortest_path (Xin-Wang exact
// geodesics) run on a copy of our TriangleMesh. This header keeps CGAL out of
// the test files; cgal_oracle.cpp is the one translation unit that includes it.
//
// Only for clean meshes: every face with three distinct corners must be
// accepted by a manifold halfedge structure (throws std::runtime_error
// otherwise). Unreferenced vertices are allowed (they get +inf and -1).

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <span>
#include <vector>

namespace geodual::test {

struct OracleResult {
  /// Per mesh vertex: distance to the nearest site; +inf where unreachable.
  std::vector<double> distance;
  /// Per mesh vertex: index into the site list; -1 where unreachable.
  std::vector<Index> nearest_site;
  /// Per extra query point (see cgal_geodesic): distance and nearest site.
  std::vector<double> query_distance;
  std::vector<Index> query_site;
  double build_mesh_seconds = 0;  ///< Surface_mesh construction
  double solve_seconds = 0;       ///< build_sequence_tree + the vertex queries
};

/// Exact geodesic distances from `sites` (vertex or face + barycentric with
/// respect to our corner order) to every vertex, and to every point of
/// `queries` (which must be face points).
OracleResult cgal_geodesic(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                           std::span<const SurfacePoint> queries = {});

}  // namespace geodual::test
