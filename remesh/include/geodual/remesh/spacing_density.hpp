#pragma once
// A density for the weighted CVT (lloyd.hpp) that asks for closer sites near
// given points: the spacing s_p at point p, growing by `gradation` per unit
// of distance from it, up to the spacing elsewhere. A weighted CVT spaces its
// sites like rho^(-1/4) (curvature_density.hpp), so
//
//   sigma(x) = min(spacing, min_p (s_p + gradation |x - p|)),   rho = (spacing / sigma)^4.
//
// What the dense stretches of feature_sites need: sites on a chain closer
// than the sites beside it make slivers against it.
//
//   auto rho = spacing_density(cut.mesh, sites.dense_points, {.spacing = h});
//   if (carries_density(cut.mesh, rho, h)) count = sites_for_density(cut.mesh, n, {}, rho);  // error_density.hpp

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace geodual::remesh {

/// A point and the spacing of the sites it should have around it.
struct SpacedPoint {
  Eigen::Vector3d position;
  double spacing = 0;
};

struct SpacingDensityOptions {
  double spacing = 0;  ///< the spacing away from the points (> 0)
  /// How fast the spacing grows away from a point, per unit of distance
  /// (> 0): 0.15, a cell 15 % wider than its neighbour towards the point,
  /// the density changing by 1.15^4 = 1.75 across it: the weighted Lloyd
  /// step takes it nearly linear across a cell (docs/algorithms.md).
  double gradation = 0.15;
};

/// One density per vertex of `mesh` (distances in space, not on the
/// surface), 1 where no point asks for less than options.spacing.
/// \throw UsageError for options out of range or a point's spacing not > 0.
std::vector<double> spacing_density(const TriangleMesh& mesh, std::span<const SpacedPoint> points,
                                    const SpacingDensityOptions& options);

/// Whether `mesh` can carry `density` (linear in each face, as the weighted
/// relaxation reads it): every face where it is above 1 at a corner is at
/// most `max_ratio` times as long as the spacing asked there,
/// spacing * rho^(-1/4) at its densest corner. A face much wider than that
/// spreads the density far beyond where it was asked for.
bool carries_density(const TriangleMesh& mesh, std::span<const double> density, double spacing, double max_ratio = 4);

}  // namespace geodual::remesh
