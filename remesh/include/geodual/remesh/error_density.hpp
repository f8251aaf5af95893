#pragma once
// Error-driven sizing: a density for the weighted CVT (lloyd.hpp) that puts
// more sites where a remesh strays farther than a bound from the surface, and
// the site count that keeps the spacing elsewhere. What `--max-error` repeats
// until the bound holds (docs/algorithms.md#error-bound).
//
//   auto rho = refine_density(mesh, previous_rho, deviation, {.max_error = e, .spacing = h});
//   auto sites = sites_for_density(mesh, previous_sites, previous_rho, rho);
//   auto start = add_sites_at_deviations(mesh, last_sites, deviation, rho, h, sites - previous_sites);
//
// A remesh's vertices lie on the surface, so its distance to it is a chord
// error, which falls like h^2 with the spacing h; the weighted CVT spaces its
// sites like rho^(-1/4) (curvature_density.hpp). Where the deviation is r
// times `aim` times the bound (r > 1), the density is multiplied by r^2 (at
// most max_ratio). The aim is below the bound because a remesh's deviation
// at a place also depends on where its vertices happen to fall there, and
// the next remesh's relaxation moves them. That remesh starts from the last
// one's sites and adds those the count asks for where the deviation is
// largest (add_sites_at_deviations).
// The factor is spread over a spacing (one-ring maxima, so that the
// neighbourhood of a narrow peak is refined too) and then smoothed over a
// spacing (the weighted Lloyd step assumes the density nearly linear across
// a cell).

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace geodual::remesh {

struct ErrorDensityOptions {
  double max_error = 0;   ///< the bound, in mesh units (> 0)
  double spacing = 0;     ///< the remesh's mean edge length (> 0): the length the factor spreads over
  double aim = 0.75;      ///< the fraction of the bound the density aims at, in (0, 1]
  double max_ratio = 16;  ///< the largest factor at a vertex (>= 1)
};

/// `density` (one per vertex of `mesh`; empty: all 1) refined where
/// `deviation` (one per vertex: the largest distance between the remesh and
/// the surface measured at it, quality::QualityReport::deviation_at_vertices)
/// is above options.max_error. \throw UsageError for options out of range or
/// sizes that do not match the mesh.
std::vector<double> refine_density(const TriangleMesh& mesh, std::span<const double> density,
                                   std::span<const double> deviation, const ErrorDensityOptions& options);

/// The sites that space density `to` as `sites` sites space density `from`
/// (empty: all 1): sites * int sqrt(to) dA / int sqrt(from) dA, rounded, at
/// least `sites` + 1 when `to` is larger somewhere.
std::int64_t sites_for_density(const TriangleMesh& mesh, std::int64_t sites, std::span<const double> from,
                               std::span<const double> to);

/// `sites` with up to `count` sites added at the vertices of `mesh` (of a
/// face with three distinct corners) where
/// `deviation` (one per vertex) is largest and above 0, largest first (ties
/// by index), each farther than half the local spacing, spacing * rho^(-1/4)
/// (rho from `density`, empty: 1), from every other site: the start of the
/// next remesh of an error bound, which keeps the last one's sites where
/// they were. Fewer are added where fewer vertices are that far.
/// \throw UsageError for sizes that do not match the mesh, a density not > 0,
/// spacing <= 0 or count < 0.
std::vector<SurfacePoint> add_sites_at_deviations(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                                  std::span<const double> deviation, std::span<const double> density,
                                                  double spacing, std::int64_t count);

/// The sites the next remesh's relaxation may leave where they are, to
/// refine locally: per site of `sites` (add_sites_at_deviations' result,
/// the sites added from `first_added` on), 1 where it lies farther than
/// `reach` from every added site, 0 elsewhere (LloydOptions::fixed_sites).
/// \throw UsageError for reach < 0.
std::vector<std::uint8_t> sites_away_from_added(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                                std::size_t first_added, double reach);

}  // namespace geodual::remesh
