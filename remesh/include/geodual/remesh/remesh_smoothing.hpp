#pragma once
// The last stage of a remesh: its vertices fitted to the surface where it
// strays farthest (fit_deviations), then its smallest angles
// raised (smooth_smallest_angles), each vertex moved along the surface and
// its site with it; the vertices that carry a crease stay.
//
//   auto smoothed = geodual::remesh::smooth_remesh(remesh, surface.mesh(), *surface.topology());

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/angle_smoothing.hpp"
#include "geodual/remesh/deviation_fitting.hpp"
#include "geodual/remesh/dual_repair.hpp"
#include "geodual/remesh/features.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"

#include <span>
#include <vector>

namespace geodual::remesh {

struct RemeshSmoothingOptions {
  /// smooth_smallest_angles's bound, degrees (0: no angle smoothing; at most 60).
  double smoothing_angle = 30;
  bool fit_deviations = true;  ///< fit_deviations first
  /// A vertex within this distance of a pinned crease stays (it may be what follows the crease).
  double crease_tolerance = 0;
};

/// \throw geodual::UsageError naming the first option out of range.
void check_options(const RemeshSmoothingOptions& options);

struct RemeshSmoothing {
  DeviationFittingResult fitting;
  AngleSmoothingResult smoothing;
};

/// Smooths `remesh`, whose sites lie on `surface` (faces joined by
/// `topology`), in place: remesh.mesh's vertices and remesh.sites move
/// together. Stay: a vertex of welded twins (a chain's) or of several sites,
/// those in `fixed_vertices` (-1 ignored: a pin the repair left out), those
/// within options.crease_tolerance of `creases` (vertex polylines of
/// `crease_mesh`), and those the two smoothings keep. \throw UsageError for
/// options out of range.
RemeshSmoothing smooth_remesh(RepairedDual& remesh, const TriangleMesh& surface,
                              const voronoi::SurfaceTopology& topology, const RemeshSmoothingOptions& options = {},
                              std::span<const Index> fixed_vertices = {}, std::span<const FeatureChain> creases = {},
                              const TriangleMesh* crease_mesh = nullptr);

/// Per pin (sites at vertices of the surface, such as ShortCreasePins::pins),
/// its vertex in `remesh`; -1 where the repair left it out.
std::vector<Index> pin_vertices(const RepairedDual& remesh, std::span<const SurfacePoint> pins);

}  // namespace geodual::remesh
