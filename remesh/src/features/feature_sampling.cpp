#include "geodual/remesh/feature_sampling.hpp"

#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/remesh/crease_pins.hpp"
#include "geodual/remesh/curvature_density.hpp"
#include "geodual/remesh/error_density.hpp"
#include "geodual/remesh/spacing_density.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace geodual::remesh {
namespace {

/// 5e-4 of the surface's bounding-box diagonal where `given` is 0.
double chord_error(const TriangleMesh& surface, double given) {
  return given > 0 ? given : 5e-4 * referenced_bounding_box(surface).diagonal();
}

}  // namespace

void check_options(const FeatureSamplingOptions& options) {
  const auto require = [](bool holds, const std::string& what, double value, const std::string& range) {
    if (!holds) throw UsageError(what + " " + std::to_string(value) + ": must be " + range);
  };
  const auto in = [](double x, double low, double high) { return std::isfinite(x) && x >= low && x <= high; };
  require(in(options.sharp_angle, 0, 180), "sharp angle", options.sharp_angle, "in [0, 180] degrees (0: no features)");
  require(in(options.continuation_angle, 0, 180), "continuation angle", options.continuation_angle,
          "in [0, 180] degrees (0: off)");
  require(std::isfinite(options.min_feature_length) && options.min_feature_length >= 0, "min feature length",
          options.min_feature_length, "a finite number >= 0 (in spacings)");
  require(std::isfinite(options.max_chord_error) && options.max_chord_error >= 0, "max chord error",
          options.max_chord_error, "a finite distance >= 0 (0: the default)");
  require(in(options.min_spacing, 0, 1), "min spacing", options.min_spacing, "in [0, 1] spacings");
  require(in(options.tight_spacing, 0, 1), "tight spacing", options.tight_spacing, "in [0, 1] spacings");
  require(std::isfinite(options.max_share_near_features) && options.max_share_near_features >= 0,
          "max share near features", options.max_share_near_features, "a finite fraction >= 0 of the sites");
  require(std::isfinite(options.max_share_tightened) && options.max_share_tightened >= 0, "max share tightened",
          options.max_share_tightened, "a finite fraction >= 0 of the sites");
  require(in(options.parallel_fold_angle, 0, 90), "parallel fold angle", options.parallel_fold_angle,
          "in [0, 90] degrees (0: off)");
  require(std::isfinite(options.max_share_narrow_regions) && options.max_share_narrow_regions >= 0,
          "max share narrow regions", options.max_share_narrow_regions, "a finite fraction >= 0 of the sites");
}

FeatureOptions feature_detection_options(const TriangleMesh& surface, std::int64_t sites,
                                         const FeatureSamplingOptions& options) {
  FeatureOptions detection = remesh_feature_options(surface, sites, options.sharp_angle, options.min_feature_length,
                                                    options.continuation_angle);
  detection.parallel_fold_angle = options.parallel_fold_angle;
  detection.machined_regions_smooth = options.machined_regions_smooth;
  detection.given_edges = options.given_edges;
  detection.excluded_edges = options.excluded_edges;
  return detection;
}

FeatureSampling sample_features(const RemeshSurface& prepared, std::int64_t sites,
                                const FeatureSamplingOptions& options) {
  check_options(options);
  const TriangleMesh& surface = prepared.mesh();
  FeatureSampling sampling;
  if ((options.sharp_angle <= 0 && options.given_edges.empty()) || sites < 4) return sampling;
  const double spacing = uniform_spacing(surface, sites);
  FeatureOptions feature_options = feature_detection_options(surface, sites, options);
  FeatureSiteOptions site_options{.spacing = spacing,
                                  .max_chord_error = chord_error(surface, options.max_chord_error),
                                  .min_spacing = options.min_spacing * spacing,
                                  .tight_spacing = options.tight_spacing * spacing,
                                  .split_at_bends = options.split_at_bends};
  // These creases, the cut along them and their chain sites; false where there are none.
  const auto line_creases = [&](FeatureSet features) {
    sampling.features = std::move(features);
    if (sampling.features.empty()) return false;
    sampling.cut = cut_along_features(prepared, sampling.features);
    sampling.sites = feature_sites(prepared, sampling.features, sampling.cut, site_options);
    return true;
  };
  if (!line_creases(detect_features(prepared, feature_options))) return sampling;
  // Where the creases are more than the count carries, those round a
  // machined surface's narrow rough regions go, then those round narrow
  // faceted sides, then those round narrow regions, smooth or not. The
  // share is judged on the chains' sites without the points where they bend
  // (tight_spacing 0): where those points alone take the chains beyond it,
  // they go, not creases (below).
  FeatureSiteOptions loose_options = site_options;
  loose_options.tight_spacing = 0;
  const auto narrow_regions_kept = [&] {
    return feature_options.min_region_width < feature_options.min_rough_region_width;
  };
  const double share = options.max_share_narrow_regions * static_cast<double>(sites);
  FeatureSites loose = feature_sites(prepared, sampling.features, sampling.cut, loose_options);
  // Each step judges more narrow regions rough, and keeps fewer creases.
  enum class Fewer { machined_rough, faceted_rough, all_rough };
  for (const Fewer step : {Fewer::machined_rough, Fewer::faceted_rough, Fewer::all_rough}) {
    const bool too_many = narrow_regions_kept() && static_cast<double>(loose.points) > share;
    if (!too_many) break;
    if (step == Fewer::machined_rough) {
      if (!feature_options.machined_regions_smooth) continue;
      feature_options.machined_regions_smooth = false;
    } else if (step == Fewer::faceted_rough) {
      if (feature_options.parallel_fold_angle == 0) continue;
      feature_options.parallel_fold_angle = 0;
    } else {
      feature_options.min_region_width = feature_options.min_rough_region_width;
    }
    FeatureSet fewer = detect_features(prepared, feature_options);
    if (fewer.sharp_edges.size() < sampling.features.sharp_edges.size()) {
      if (!line_creases(std::move(fewer))) return sampling;
      loose = feature_sites(prepared, sampling.features, sampling.cut, loose_options);
    }
  }
  // The closer points, where the count carries them: at the chains' own
  // vertices where they bend, else evenly closer (fewer, as a rule), else none.
  const auto carried = [&](const FeatureSites& closer) {
    return static_cast<double>(closer.points - loose.points) <=
               options.max_share_tightened * static_cast<double>(sites) &&
           !(narrow_regions_kept() && static_cast<double>(closer.points) > share);
  };
  if (!carried(sampling.sites) && sampling.sites.chains_split_at_bends > 0) {
    FeatureSiteOptions evenly_options = site_options;
    evenly_options.split_at_bends = false;
    FeatureSites evenly = feature_sites(prepared, sampling.features, sampling.cut, evenly_options);
    if (carried(evenly)) sampling.sites = std::move(evenly);
  }
  if (!carried(sampling.sites)) {
    sampling.sites = std::move(loose);
    return sampling;
  }
  sampling.points_tightened = sampling.sites.points - loose.points;
  const TriangleMesh& cut = sampling.cut.mesh;
  if (sampling.sites.dense_points.empty()) return sampling;
  sampling.density = spacing_density(cut, sampling.sites.dense_points, {.spacing = spacing});
  sampling.density_spacing = spacing;
  sampling.sites_near_features = sites_for_density(cut, sites, {}, sampling.density) - sites;
  if (static_cast<double>(sampling.sites_near_features) >
          options.max_share_near_features * static_cast<double>(sites) ||
      !carries_density(cut, sampling.density, spacing)) {
    // The chains keep their dense sites; the sites beside them are spaced
    // as elsewhere (a crease followed within the chord error outweighs the
    // narrower triangles against it).
    sampling.density.clear();
    sampling.density_spacing = 0;
    sampling.sites_near_features = 0;
  }
  return sampling;
}

ShortCreasePins pin_short_creases(const RemeshSurface& prepared, std::int64_t sites, FeatureSampling& sampling,
                                  double max_chord_error) {
  const TriangleMesh& surface = prepared.mesh();
  ShortCreasePins pinned;
  if (sampling.features.short_creases.empty()) return pinned;
  const double spacing = uniform_spacing(surface, sites);
  CreasePins crease_pins = remesh::crease_pins(
      prepared, sampling.features, {.spacing = spacing, .max_chord_error = chord_error(surface, max_chord_error)});
  if (crease_pins.sites.empty()) return pinned;
  if (!sampling.empty()) {
    // Onto the features' cut: its faces are the surface's, its vertices copies.
    std::vector<Index> copy(static_cast<std::size_t>(surface.num_vertices()), -1);
    for (std::size_t c = sampling.cut.original_vertex.size(); c-- > 0;) {
      copy[sampling.cut.original_vertex[c]] = static_cast<Index>(c);
    }
    for (SurfacePoint& pin : crease_pins.sites) pin.element = copy[pin.element];
  }
  const TriangleMesh& working = sampling.sites_surface(surface);
  constexpr double kMaxShare = 0.5;
  std::vector<double> with_pins = spacing_density(working, crease_pins.spacing, {.spacing = spacing, .gradation = 0.3});
  for (std::size_t v = 0; v < sampling.density.size(); ++v) {
    with_pins[v] = std::max(with_pins[v], sampling.density[v]);
  }
  const std::int64_t asked = sites_for_density(working, sites, {}, with_pins) - sites;
  if (static_cast<double>(asked - sampling.sites_near_features) + static_cast<double>(crease_pins.sites.size()) >
      kMaxShare * static_cast<double>(sites)) {
    pinned.reason = "the " + std::to_string(crease_pins.sites.size()) +
                    " sites pinned on the short creases and those round them would be more than half the " +
                    std::to_string(sites) + " sites asked: not pinned";
    return pinned;
  }
  sampling.density = std::move(with_pins);
  sampling.density_spacing = spacing;
  sampling.sites_near_features = asked;
  pinned.pins = std::move(crease_pins.sites);
  pinned.segments = std::move(crease_pins.segments);
  return pinned;
}

}  // namespace geodual::remesh
