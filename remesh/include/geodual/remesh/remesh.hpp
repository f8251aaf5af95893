#pragma once
// Remeshing from sites: the geodesic Voronoi diagram of the sites, its dual,
// and, where the dual falls short of the input's topology (closed-ball
// property), sites added where it fails and everything recomputed.
//
//   auto sites = geodual::remesh::sample_sites(mesh, 4000);
//   auto result = geodual::remesh::remesh_from_sites(mesh, sites);  // 10 Lloyd iterations first
//   result.dual.mesh  // one vertex per site, oriented like the input

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/curvature_density.hpp"
#include "geodual/remesh/dual_repair.hpp"
#include "geodual/remesh/feature_sampling.hpp"
#include "geodual/remesh/lloyd.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/remesh/remesh_sites.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace geodual::remesh {

struct RemeshOptions {
  /// Lloyd relaxation of the given sites first (iterations = 0: none). Its
  /// `voronoi` options are used for every diagram, repair rounds included.
  LloydOptions lloyd;
  /// Curvature-adapted sizing (with lloyd.density empty and a relaxation):
  /// Lloyd relaxes towards the weighted CVT of curvature_density with these
  /// options, spacing 0 meaning the remesh's (uniform_spacing). None: the
  /// uniform geodesic CVT.
  std::optional<CurvatureDensityOptions> curvature;
  /// Rounds of "add sites where the dual fails, recompute" (RepairOptions::max_rounds;
  /// up to twice as many while the repair converges).
  int max_repair_rounds = 10;
};

/// \throw geodual::UsageError naming the first option out of range.
void check_options(const RemeshOptions& options);

/// The remesh that keeps sharp features, as the remesh pipeline makes it
/// with the stages below (sample_features, pin_short_creases,
/// welded_dual_with_repair). See docs/algorithms.md#sharp-features.
struct FeatureRemeshOptions {
  /// The features and the chains' sites (sample_features): creases where the
  /// normals turn by at least sampling.sharp_angle degrees at half the
  /// remesh's spacing, in chains at least sampling.min_feature_length
  /// spacings long, and sampling.given_edges; its given and excluded edges
  /// are here edges of the input (feature_sampling_options puts them on the
  /// cut). sharp_angle 0 and no given edges: none.
  FeatureSamplingOptions sampling;
  /// Creases at sharp_angle too short or too weak at the remesh's scale to
  /// cut along (a fillet's coarse edges, a crease that fades within a
  /// spacing) get sites pinned at their vertices, the sites round them as
  /// close, and edges flipped onto them (pin_short_creases): they add sites
  /// beyond the count, up to twice as many on parts with many such creases.
  bool pin_short_creases = false;
  /// The dual's repair rounds, at most (never extended): where it needs
  /// more, the creases are finer than the spacing there, and the remesh
  /// pipeline leaves out those near the faults ...
  int max_repair_rounds = 4;
  /// ... and where its repair would add more than this fraction of the
  /// sites (twins included), as creases finer than the spacing make it, it
  /// gives up too (0: no bound). Half: a coarse CAD part's creases may need
  /// that many more than the count asked; each added site is reported.
  double max_sites_added = 0.5;
  /// Where that remesh fails at places (DualRepairError::places), the remesh
  /// pipeline tries again without the creases within this many spacings of
  /// them (up to six times, each leaving out more where the last failed)
  /// before it drops them all (0: no such try) ...
  double retry_radius = 2;
  /// ... and where no try keeps the creases with chain sites closer along
  /// curved creases (sampling.tight_spacing), the tries run again with them
  /// no closer than sampling.min_spacing (false: not) ...
  bool loosen_chain_sites = true;
  /// ... and where no try keeps the creases with the sites asked for, they
  /// cannot carry them: the tries run again with twice as many sites, and
  /// again with twice as many, this many times at most, before the remesh
  /// without features (0: never); the sites added are reported.
  int max_site_doublings = 2;
  /// ... and where those fail too with creases round a machined surface's
  /// narrow rough regions (sampling.machined_regions_smooth), the tries and
  /// doublings run again without those, and then where they fail with
  /// creases round narrow faceted sides (sampling.parallel_fold_angle),
  /// without those, before the remesh without features (false: not).
  bool drop_faceted_sides = true;
  /// The dual closed along the chains' sides
  /// (DualOptions::close_boundary_stretches): the stretch between two
  /// consecutive chain sites is an edge by construction where another cell
  /// reaches the chain between them, or a strip narrower than the spacing
  /// lies between two chains, instead of a repair that adds sites there.
  /// false: the repair alone.
  bool close_crease_stretches = true;
};

/// \throw geodual::UsageError naming the first option out of range.
void check_options(const FeatureRemeshOptions& options);

/// The Lloyd options remesh_from_sites relaxes `site_count` sites on
/// `surface` with: options.lloyd, with the curvature density filled in when
/// options.curvature asks for it.
LloydOptions relaxation_options(const TriangleMesh& surface, std::int64_t site_count, const RemeshOptions& options);

// The remesh's stages one by one, as the remesh pipeline (and `geodual
// remesh`) makes them; docs/library.md shows them in a row:
// cut_to_manifold, sample_features, pin_short_creases, sample_remesh_sites,
// lloyd_relax, dual_with_repair or welded_dual_with_repair, smooth_remesh.

/// The feature stage's options: options.sampling, with its given and
/// excluded edges (of `input`) on `cut`, the input cut to a manifold.
FeatureSamplingOptions feature_sampling_options(const FeatureRemeshOptions& options, const TriangleMesh& input,
                                                const ManifoldCut& cut);

/// The Lloyd options `sites` (on FeatureSampling::sites_surface) relax
/// with: relaxation_options, the pins fixed, and `feature_density`
/// (FeatureSampling::density: the sites beside dense chain sites and pins;
/// empty: 1) times the curvature density.
LloydOptions relaxation_options(const TriangleMesh& sites_surface, const RemeshSites& sites,
                                std::span<const double> feature_density, const RemeshOptions& options);

/// The dual-with-repair options: the rounds of options.max_repair_rounds and
/// the diagrams of options.lloyd.voronoi ...
RepairOptions repair_options(const RemeshOptions& options);
/// ... and for `site_count` relaxed sites with features, the rounds and
/// sites added the remesh that keeps them allows (features.max_repair_rounds at most, features.max_sites_added,
/// never extended) and the dual closed along the chains
/// (features.close_crease_stretches).
RepairOptions repair_options(const RemeshOptions& options, const FeatureRemeshOptions& features,
                             std::int64_t site_count);

/// Per vertex of `remesh`, the point of the input it is: its site through
/// `features_cut` (FeatureSampling::cut; none where it has no vertices) and
/// `cut` (interpolate_attributes takes these points).
std::vector<SurfacePoint> remesh_points_on_input(const RepairedDual& remesh, const ManifoldCut& cut,
                                                 const FeatureCut& features_cut);

struct RemeshResult {
  /// Input vertices cut apart first and faces of scraps left out (see
  /// manifold_cut.hpp); the remesh has the topology of the cut surface.
  std::int64_t vertices_split = 0;
  std::int64_t faces_disabled = 0;
  LloydResult relaxation;  ///< the relaxation stage (its diagram moved on to `dual`)
  RepairedDual dual;       ///< the dual-with-repair stage: the remesh
};

/// The three stages in a row: cut_to_manifold(input), lloyd_relax with
/// relaxation_options, dual_with_repair with repair_options (both on one
/// GeodesicSurface). Every vertex of the result is at its site: the remesh
/// pipeline's smoothing (smooth_remesh) and features are stages of their
/// own. \throw geodual::UsageError as check_options; geodual::Error as
/// dual_with_repair, and for bad sites as compute_geodesic_field.
RemeshResult remesh_from_sites(const TriangleMesh& input, std::vector<SurfacePoint> sites,
                               const RemeshOptions& options = {});

}  // namespace geodual::remesh
