#pragma once
// Smoothing of a remesh's worst triangles. A centroidal Voronoi tessellation
// leaves a few triangles with a small angle where its sites meet in an
// irregular pattern (next to a vertex of valence 4 or 8, say); no relaxation
// of the sites removes them, since the dual's connectivity is what makes
// them. Here the corners of every triangle with an angle below a bound are
// moved along the surface, one vertex at a time, to where the smallest angle
// of the triangles round it is largest: a pattern search on that max-min
// objective, the optimization-based smoothing of Freitag, Jones & Plassmann
// [FJP95]. The connectivity stays; see docs/algorithms.md#angle-smoothing.
//
//   auto smoothed = smooth_smallest_angles(surface, topology, remesh, points, fixed);
//   smoothed.min_angle_after  // degrees

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace geodual::remesh {

struct AngleSmoothingOptions {
  /// The corners of triangles with an angle below this many degrees move
  /// (0: none; at most 60).
  double min_angle = 30;
  /// Passes over the triangles still below it (a move can help a neighbour's).
  int rounds = 4;
  /// A vertex moves at most this many times the mean length of its edges.
  double max_move = 0.5;
};

struct AngleSmoothingResult {
  std::int64_t vertices_moved = 0;
  double min_angle_before = 0;  ///< the remesh's smallest angle, degrees
  double min_angle_after = 0;
  double seconds = 0;
};

/// Moves vertices of `remesh` (oriented and manifold, its vertex v at
/// `points[v]` on `surface`, whose faces `topology` joins), keeping each on
/// the surface: remesh.vertices and `points` change in place. A move is kept
/// only where it raises the smallest angle round the vertex, turns no
/// triangle over, leaves none of them with a lower quality Q than the worst
/// they had and no more of their angles below the bound, and takes them no
/// farther from any point of the surface under them than 3 % of an edge
/// more than they were, nor 6 % more than before the first move (the
/// Hausdorff distance stays). Stay where they are: the vertices with
/// fixed[v] != 0 (`fixed` may be empty or shorter), those at a vertex of the surface and
/// those on its boundary (boundary loops, the sides of a cut), and those on
/// the remesh's boundary. Deterministic (one vertex after the other, in
/// index order).
/// \throw geodual::UsageError for options out of range or `points` not one per vertex.
AngleSmoothingResult smooth_smallest_angles(const TriangleMesh& surface, const voronoi::SurfaceTopology& topology,
                                            TriangleMesh& remesh, std::vector<SurfacePoint>& points,
                                            std::span<const std::uint8_t> fixed = {},
                                            const AngleSmoothingOptions& options = {});

}  // namespace geodual::remesh
