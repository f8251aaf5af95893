#pragma once
// Deviation fitting: a remesh's vertices moved along the surface towards the
// surface's points that stray farthest from it, where a CVT's dual cuts a
// crease or a scan's rim off, within floors on the triangles' shape. The
// connectivity stays; see docs/algorithms.md#deviation-fitting.
//
//   auto fitted = fit_deviations(surface, topology, remesh, points, fixed);
//   fitted.deviation_after  // in the surface's units

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace geodual::remesh {

struct DeviationFittingOptions {
  /// The vertices that answer for a point of the surface this share of the
  /// largest distance from the remesh or farther move (0: none; below 1).
  double share = 0.7;
  /// Passes: the largest distance found again, then its vertices moved.
  int rounds = 2;
  /// A vertex answers for the surface's points nearer to it than to any other
  /// vertex, and searches over those within this many times its mean edge.
  double reach = 0.75;
  /// No angle of a vertex's triangles ends below the least of this, the
  /// remesh's smallest angle and their own smallest before (degrees).
  double min_angle = 30;
  /// The mean quality Q of a vertex's triangles falls by at most this much.
  double max_q_loss = 0.03;
  /// A vertex moves at most this many times the mean length of its edges.
  double max_move = 0.5;
};

struct DeviationFittingResult {
  std::int64_t vertices_moved = 0;
  /// The largest distance from the remesh's triangles of the surface's
  /// vertices (those of its faces) and, where those are fewer than eight per
  /// remesh vertex, its face centres, before and after, in the surface's units.
  double deviation_before = 0;
  double deviation_after = 0;
  double seconds = 0;
};

/// Moves the vertices of `remesh` that answer for the surface's points
/// farthest from it (a crease or a scan's rim that a CVT's dual cuts off by a
/// third of an edge) along the surface, each to where the largest distance of
/// its points from its triangles is least: the same kind of search as
/// smooth_smallest_angles, on a min-max objective. A move is kept only where
/// that distance falls, no triangle turns over, no angle falls below
/// options.min_angle or the remesh's smallest (whichever is less), no Q below
/// the worst of the triangles with no angle below options.min_angle (those
/// smooth_smallest_angles leaves alone; the remesh's worst if there are none),
/// the triangles' mean Q by at most options.max_q_loss,
/// and no point of the surface under them ends up farther from them by more
/// than 3 % of an edge. The same vertices stay as in smooth_smallest_angles.
/// Deterministic. \throw geodual::UsageError for options out of range or
/// `points` not one per vertex.
DeviationFittingResult fit_deviations(const TriangleMesh& surface, const voronoi::SurfaceTopology& topology,
                                      TriangleMesh& remesh, std::vector<SurfacePoint>& points,
                                      std::span<const std::uint8_t> fixed = {},
                                      const DeviationFittingOptions& options = {});

}  // namespace geodual::remesh
