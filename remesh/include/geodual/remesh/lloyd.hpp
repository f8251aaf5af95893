#pragma once
// Lloyd relaxation towards a geodesic centroidal Voronoi tessellation
// (Lloyd–Newton by default, after a warm start on the restricted Voronoi
// diagram): the mathematics is in docs/algorithms.md#lloydnewton-relaxation.
//
//   auto relaxed = geodual::remesh::lloyd_relax(mesh, sites, {.iterations = 10});
//   relaxed.energy  // CVT energy before and after each accepted iteration, never increasing

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <Eigen/Core>

#include <functional>
#include <span>
#include <vector>

namespace geodual::remesh {

struct LloydOptions {
  /// At most this many iterations (0: none, the diagram of the given sites).
  int iterations = 10;
  /// At most this many steps on the restricted Voronoi diagram first (the
  /// warm start, see above; 0: none). Skipped when `iterations` is 0, unless
  /// warm_start_alone. Between its steps it asks voronoi.geodesic.progress
  /// (with 0), which can cancel it. It needs no geodesic diagram: the first
  /// is that of the sites it reaches.
  int warm_start_iterations = 30;
  /// The warm start also where `iterations` is 0; the diagram returned is
  /// then that of the sites it reached. For a relaxation that moves a few
  /// sites among fixed ones (`fixed_sites`: an error bound's later rounds),
  /// whose steps on the restricted diagram cost little beside an exact one.
  bool warm_start_alone = false;
  /// Heavy-ball momentum of the warm start (Polyak 1964): each least-damped
  /// Newton step also goes this fraction of the step taken before it, which
  /// carries the slow slides of whole rows of cells along (0: none; < 1).
  double warm_start_momentum = 0.6;
  /// Stop once a step (of the warm start or of the iterations) lowers the
  /// energy by less than this fraction of it. A Newton step must lower it by
  /// this much to be taken (one that lowers it by less is retried more
  /// damped, then Lloyd's step decides).
  double tolerance = 1e-5;
  /// The iterations, each an exact geodesic diagram, also stop once one
  /// lowers the energy by less than this fraction of it; after a warm start
  /// the first is not tried where moving the sites to their cells' centroids
  /// (the cells kept) would lower it by less, unless sites slide along
  /// chains (docs/algorithms.md#how-many-exact-diagrams). Where the
  /// restricted diagram is far from the geodesic one (few sites on a curved
  /// or thin surface) the iterations go on. 0: only `tolerance` stops them.
  double geodesic_tolerance = 1e-3;
  /// With newton = false, each step goes this many times the way to the
  /// centroid (over-relaxed Lloyd; 1 is the plain one); when an over-relaxed
  /// step would raise the energy, the relaxation falls back to 1 from there
  /// on. The Lloyd step that replaces rejected Newton steps is the plain one.
  double over_relaxation = 1.8;
  /// Newton-accelerated steps (Lloyd–Newton): each step solves the CVT
  /// energy's Hessian system, damped by at least `newton_damping` times
  /// Lloyd's diagonal, each site's step at most `newton_max_step` times the
  /// square root of its cell's area (see remesh/src/relax/cvt_newton.hpp). A step
  /// that would not lower the energy is retried more damped, then replaced by
  /// Lloyd's. false: plain (over-relaxed) Lloyd steps only.
  bool newton = true;
  double newton_damping = 0.1;
  double newton_max_step = 0.2;
  /// A density per mesh vertex (linear inside faces, > 0) for a weighted CVT:
  /// the energy becomes sum_i int_cell rho(x) d(x, s_i)^2 dA, and its
  /// minimisers space the sites like rho^(-1/4) (see curvature_density.hpp).
  /// The weighted integrals come from the diagram's to first order in rho's
  /// variation across a cell (remesh/src/relax/weighted_cells.hpp). Empty: rho = 1,
  /// the plain geodesic CVT.
  std::vector<double> density;
  /// Sites on the mesh boundary stay where they are (they carry the
  /// boundary loops into the remesh); true moves them like the others.
  bool move_boundary_sites = false;
  /// Per site (empty: none; shorter: the rest move), nonzero: the site stays
  /// where it is, as the pins on short creases do (crease_pins.hpp).
  std::vector<std::uint8_t> fixed_sites;
  /// Where set, moves the sites that stay otherwise (on the boundary) along
  /// it, as a feature chain's sites slide along their chain (chain_slider.hpp):
  /// told the sites and, per site, its cell's mass and first moment, it
  /// returns the sites, moved. Each iteration's step takes its moves of the
  /// sites that stay, and is kept only if the energy falls, as any other.
  /// Not in the warm start: the restricted diagram's cells reach across a
  /// crease (its distances are straight lines in space), which slides chain
  /// sites where the geodesic diagram would not.
  std::function<std::vector<SurfacePoint>(std::span<const SurfacePoint> sites, std::span<const double> mass,
                                          std::span<const Eigen::Vector3d> moment)>
      slide_boundary_sites;
  voronoi::VoronoiOptions voronoi;
  /// For progress reports: told the iterations accepted so far once the
  /// first diagram is done and after each accepted iteration (a rejected
  /// step costs a diagram but no iteration), then `finished` at the end.
  std::function<void(int iterations_done, bool finished)> on_iteration;
};

struct LloydResult {
  std::vector<SurfacePoint> sites;  ///< the relaxed sites, in the given order
  voronoi::VoronoiDiagram diagram;  ///< of the relaxed sites
  /// CVT energy (weighted by `density` when given) of the first diagram's
  /// sites (the given ones, or those the warm start reached), then after
  /// each accepted iteration.
  std::vector<double> energy;
  int iterations = 0;             ///< iterations accepted
  int warm_start_iterations = 0;  ///< warm-start steps taken
  int diagrams = 0;               ///< geodesic diagrams computed (the first, and one per step tried)
  double warm_start_seconds = 0;  ///< the warm start's steps
  double geodesic_seconds = 0;    ///< all diagrams
  double diagram_seconds = 0;
  double move_seconds = 0;  ///< centroid steps
};

/// \throw geodual::UsageError naming the first option out of range.
void check_options(const LloydOptions& options);

/// Relaxes sites on `surface`'s mesh; every diagram reuses the prepared
/// surface. \throw geodual::UsageError for options out of range, and as
/// compute_voronoi does.
LloydResult lloyd_relax(const voronoi::GeodesicSurface& surface, std::vector<SurfacePoint> sites,
                        const LloydOptions& options = {});

/// The same on a surface prepared for this call alone.
LloydResult lloyd_relax(const TriangleMesh& mesh, std::vector<SurfacePoint> sites, const LloydOptions& options = {});

}  // namespace geodual::remesh
