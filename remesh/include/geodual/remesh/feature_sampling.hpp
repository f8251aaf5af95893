#pragma once
// The feature stage of a remesh: the sharp creases found at the remesh's
// scale (features.hpp), the surface cut open along them and the chains lined
// with sites (feature_cut.hpp), and the density the sites beside a chain
// need where its sites are closer than the spacing (spacing_density.hpp).
// Short creases can get sites pinned on them as well (crease_pins.hpp).
// See docs/algorithms.md#sharp-features.
//
//   const geodual::remesh::RemeshSurface surface(cut.mesh);  // cut_to_manifold's
//   auto creases = geodual::remesh::sample_features(surface, 2000);
//   // creases.sites.sites: on creases.cut.mesh, the fixed sites the others are sampled around

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/feature_cut.hpp"
#include "geodual/remesh/features.hpp"
#include "geodual/remesh/remesh_surface.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace geodual::remesh {

struct FeatureSamplingOptions {
  /// Creases where the normals turn by at least this many degrees at half
  /// the spacing, in chains at least min_feature_length spacings long,
  /// continued at continuation_angle between smooth sides
  /// (remesh_feature_options). sharp_angle 0 and no given_edges: no features.
  double sharp_angle = 60;
  double min_feature_length = 0.5;
  double continuation_angle = 30;
  std::vector<std::array<Index, 2>> given_edges = {};     ///< of the surface: features whatever their angle
  std::vector<std::array<Index, 2>> excluded_edges = {};  ///< of the surface: never features
  /// Sites along a chain until its chords stay within this distance of it
  /// (0: 5e-4 of the surface's bounding-box diagonal, half the statistics'
  /// feature recall tolerance) ...
  double max_chord_error = 0;
  /// ... but no closer than this many spacings (sites denser along a chain
  /// than beside it make slivers against it) ...
  double min_spacing = 0.75;
  /// ... except where a chord would still leave the chain: there at its own
  /// vertices where it bends, about this many spacings apart (FeatureSiteOptions::
  /// tight_spacing), with the sites beside them as close (FeatureSampling::density)
  /// unless those would be more than max_share_near_features of the count or
  /// the surface's faces are too wide to carry that density (carries_density):
  /// then spaced as elsewhere beside the chain (narrower triangles against it).
  /// Where the chain sites this spacing adds would be more than
  /// max_share_tightened of the count (creases that bend at every spacing),
  /// or take the chains beyond max_share_narrow_regions, evenly closer ones
  /// instead of those at the chains' vertices, if those fit; else
  /// min_spacing throughout.
  double tight_spacing = 0.4;
  double max_share_near_features = 0.1;
  double max_share_tightened = 0.25;
  /// Where chains bend, points at their own vertices; false: evenly closer
  /// parts (FeatureSiteOptions::split_at_bends).
  bool split_at_bends = true;
  /// Narrow regions whose folds are parallel lines are smooth (FeatureOptions::
  /// parallel_fold_angle; 0: rough where steep).
  double parallel_fold_angle = 10;
  /// On a machined surface no narrow region is rough (FeatureOptions::
  /// machined_regions_smooth).
  bool machined_regions_smooth = true;
  /// Where the chain points would be more than this share of the count with
  /// the creases round narrow smooth regions kept (FeatureOptions::
  /// min_region_width), those round a machined surface's narrow rough
  /// regions go first (judged with machined_regions_smooth false), then
  /// those round narrow faceted sides (parallel_fold_angle 0), then the
  /// rest, as round narrow rough ones: the count cannot carry them.
  double max_share_narrow_regions = 1.0;
};

/// \throw geodual::UsageError naming the first option out of range.
void check_options(const FeatureSamplingOptions& options);

/// What sample_features gives: on a surface without features only `features`
/// (its short creases, perhaps) is filled in.
struct FeatureSampling {
  FeatureSet features;
  FeatureCut cut;      ///< the surface cut open along the features
  FeatureSites sites;  ///< on cut.mesh, twins included
  /// The points tight_spacing added along the chains (0: none, or the
  /// options' tight_spacing 0).
  std::int64_t points_tightened = 0;
  /// Per vertex of the surface the sites go on (sites_surface), the density
  /// the relaxation should give the sites round dense chain sites or pins;
  /// empty: 1 (uniform).
  std::vector<double> density;
  double density_spacing = 0;            ///< the spacing `density` was made for
  std::int64_t sites_near_features = 0;  ///< the sites `density` asks for beyond the count

  bool empty() const { return features.empty(); }
  /// The surface the remesh's sites lie on: cut.mesh, or `surface` itself without features.
  const TriangleMesh& sites_surface(const TriangleMesh& surface) const { return empty() ? surface : cut.mesh; }
};

/// The detection options sample_features starts from for `sites` sites on
/// `surface` (remesh_feature_options, with options' fold angle, given and excluded edges).
FeatureOptions feature_detection_options(const TriangleMesh& surface, std::int64_t sites,
                                         const FeatureSamplingOptions& options);

/// The features of `surface` (a 2-manifold, such as cut_to_manifold's mesh, prepared)
/// for a remesh of `sites` sites, the cut along them and the sites on them.
/// Deterministic. \throw UsageError for options out of range.
FeatureSampling sample_features(const RemeshSurface& surface, std::int64_t sites,
                                const FeatureSamplingOptions& options = {});

/// Sites pinned on the short creases (FeatureSet::short_creases), on the
/// surface the sites go on.
struct ShortCreasePins {
  std::vector<SurfacePoint> pins;
  std::vector<std::array<std::size_t, 2>> segments;  ///< pairs of pins a remesh edge should join
  std::string reason;                                ///< why there are none, where they were too many
};

/// Pins on `sampling`'s short creases (crease_pins), and the density round
/// them folded into sampling.density, with the sites it asks for in
/// sampling.sites_near_features. The spacing grows away from a pin twice as
/// fast as from a dense chain site: pins are many (a fillet's coarse edges),
/// and the slower growth would more than double the count on such parts
/// (docs/algorithms.md#short-creases-pinned). The pins and the sites round
/// them take at most half of `sites`; where they would take more (a scan's
/// noisy edges) there are none, `sampling` is left as it was and `reason`
/// says why. `max_chord_error` as FeatureSamplingOptions's (0: the same default).
ShortCreasePins pin_short_creases(const RemeshSurface& surface, std::int64_t sites, FeatureSampling& sampling,
                                  double max_chord_error = 0);

}  // namespace geodual::remesh
