#include "geodual/pipeline/remesh_pipeline.hpp"

#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/mesh/detail/position_welder.hpp"
#include "geodual/mesh/detail/trim_heap.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/sharp_edges.hpp"
#include "geodual/mesh/union_find.hpp"
#include "geodual/pipeline/diagram_output.hpp"
#include "geodual/pipeline/feature_file.hpp"
#include "geodual/remesh/chain_slider.hpp"
#include "geodual/remesh/curvature_density.hpp"
#include "geodual/remesh/error_density.hpp"
#include "geodual/remesh/follow_segments.hpp"
#include "geodual/remesh/remesh_smoothing.hpp"
#include "geodual/remesh/remesh_surface.hpp"
#include "geodual/remesh/sizing.hpp"
#include "geodual/remesh/welded_dual.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>

namespace geodual::pipeline {
namespace {

class StageClock {
 public:
  StageClock(std::vector<StageTiming>& timings, Stage stage) : timings_(timings), stage_(stage) {}
  void stop() {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    timings_.push_back({stage_, seconds, peak_memory_bytes()});
  }

 private:
  std::vector<StageTiming>& timings_;
  Stage stage_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// \throw UsageError for a sizing out of range or more than one of
/// edge_length, faces and given_sites.
void require_one_site_source(const RemeshPipelineOptions& options) {
  if (!std::isfinite(options.edge_length) || options.edge_length < 0) {
    throw UsageError("edge length " + std::to_string(options.edge_length) +
                     ": must be a finite number > 0 (0: unused)");
  }
  if (options.faces < 0)
    throw UsageError("faces " + std::to_string(options.faces) + ": must be at least 1 (0: unused)");
  const int given = (options.edge_length > 0) + (options.faces > 0) + options.given_sites.has_value();
  if (given > 1) {
    throw UsageError("give the sites one way only: an edge length, a face count or the sites themselves");
  }
}

/// \throw UsageError for an error bound out of range or without what it needs.
void require_error_bound_options(const RemeshPipelineOptions& options) {
  if (!std::isfinite(options.max_error_pct) || options.max_error_pct < 0 || options.max_error_pct > 100) {
    throw UsageError("max error " + std::to_string(options.max_error_pct) + " %: must be in (0, 100] (0: unused)");
  }
  if (options.max_error_pct == 0) return;
  if (options.max_sites < 0) throw UsageError("max sites " + std::to_string(options.max_sites) + ": must be >= 0");
  if (options.max_error_rounds < 1) {
    throw UsageError("max error rounds " + std::to_string(options.max_error_rounds) + ": must be at least 1");
  }
  if (options.given_sites) throw UsageError("an error bound adds sites: it cannot be used with given sites");
  if (!options.statistics) throw UsageError("an error bound is checked by the statistics: they cannot be off");
}

void report(const ProgressCallback& progress, Stage stage, double fraction) {
  if (progress && !progress(stage, fraction)) {
    throw Cancelled(std::string(stage_name(stage)) + " cancelled");
  }
}

}  // namespace

std::string_view stage_name(Stage stage) {
  switch (stage) {
    case Stage::load: return "load";
    case Stage::sample: return "sample";
    case Stage::relax: return "relax";
    case Stage::dual: return "dual";
    case Stage::statistics: return "statistics";
    case Stage::texture: return "texture";
  }
  return "?";
}

std::vector<std::pair<Stage, double>> seconds_per_stage(const std::vector<StageTiming>& timings) {
  std::vector<std::pair<Stage, double>> sums;
  for (const StageTiming& timing : timings) {
    const auto found =
        std::find_if(sums.begin(), sums.end(), [&](const auto& sum) { return sum.first == timing.stage; });
    if (found == sums.end()) {
      sums.emplace_back(timing.stage, timing.seconds);
    } else {
      found->second += timing.seconds;
    }
  }
  return sums;
}

DroppedSurface dropped_surface(const TriangleMesh& input, const remesh::ManifoldCut& cut) {
  DroppedSurface dropped;
  double total = 0;
  for (Index f = 0; f < input.num_faces(); ++f) {
    const double area = face_area(input, f);
    if (!cut.copy_of.empty() && cut.copy_of[static_cast<std::size_t>(f)] >= 0) {
      ++dropped.faces;  // a copy of a face that is kept: no surface of its own
      continue;
    }
    total += area;
    if (has_repeated_corner(cut.mesh, f)) {
      ++dropped.faces;
      dropped.area += area;
    }
  }
  dropped.area_pct = total > 0 ? 100 * dropped.area / total : 0;
  return dropped;
}

RemeshPipelineResult run_remesh_pipeline(const std::filesystem::path& input, const RemeshPipelineOptions& options) {
  std::vector<StageTiming> timings;
  report(options.progress, Stage::load, 0.0);
  StageClock clock(timings, Stage::load);
  io::LoadedMesh loaded = io::read_mesh(input);
  require_computable_range(loaded.mesh, input.string());
  clock.stop();
  report(options.progress, Stage::load, 1.0);
  RemeshPipelineResult result = run_remesh_pipeline(std::move(loaded), options);
  result.timings.insert(result.timings.begin(), timings.front());
  return result;
}

namespace {

/// A remesh that starts from the sites of the last (on the same cut surface),
/// with `added` more where the last strayed furthest from the input
/// (remesh_within_error).
struct SiteRefinement {
  std::vector<SurfacePoint> sites;
  std::vector<double> deviation;  ///< per input vertex
  std::int64_t added = 0;
};

/// How far from the sites added a locally refined remesh moves the sites, in
/// spacings of its count: the added sites' neighbours, and theirs, make way.
constexpr double kLocalRefinementReach = 2.0;

/// Where the cut to a manifold made loops the input does not have (at its
/// non-manifold edges), a note for messages about `surface_loops` loops.
std::string loops_made_by_cut(const RemeshPipelineResult& result, std::int64_t surface_loops) {
  if (surface_loops <= result.input_report.boundary_loops) return "";
  const std::int64_t input_loops = result.input_report.boundary_loops, made = surface_loops - input_loops;
  return " (the input has " + std::to_string(input_loops) +
         (input_loops == 1 ? " boundary loop; " : " boundary loops; ") + std::to_string(made) +
         (made == 1 ? " was" : " were") + " made by the cut to a manifold at its non-manifold edges and vertices)";
}

/// \throw Error with options.strict where the cut leaves out more of the input's area than allowed.
void require_dropped_area_allowed(const RemeshPipelineResult& result, const RemeshPipelineOptions& options) {
  if (options.strict && result.dropped.area_pct > options.max_dropped_area_pct) {
    throw Error("the remesh would leave out " + std::to_string(result.dropped.faces) + " faces, " +
                std::to_string(result.dropped.area_pct) +
                " % of the area (scraps and flaps cut off as "
                "non-manifold pieces); more than the " +
                std::to_string(options.max_dropped_area_pct) + " % allowed with strict");
  }
}

/// What the sample stage hands on to the others, besides `result`.
struct SampledSites {
  remesh::RemeshSites initial;                            ///< the sites and where the pins are among them
  std::vector<double> feature_density;                    ///< per vertex of result.feature_cut.mesh; empty: 1
  std::vector<std::array<std::size_t, 2>> pin_segments;   ///< pairs of pins a remesh edge should join
  std::optional<remesh::ChainSlider> slide_along_chains;  ///< with features
};

/// Sharp features cut open and lined with sites, short creases pinned, the
/// rest sampled around them (`sites` in all) on `prepared`, the surface cut
/// to a manifold; the features, their cut and the sites' figures go into `result`.
SampledSites sample_around_features(RemeshPipelineResult& result, const RemeshPipelineOptions& options,
                                    const remesh::RemeshSurface& prepared, std::int64_t sites,
                                    remesh::GivenSiteShare given_share,
                                    std::span<const std::array<Index, 2>> excluded_edges) {
  SampledSites sampled;
  remesh::FeatureSamplingOptions feature_options =
      remesh::feature_sampling_options(options.features, result.input.mesh, result.surface);
  feature_options.excluded_edges.insert(feature_options.excluded_edges.end(), excluded_edges.begin(),
                                        excluded_edges.end());
  if (feature_options.max_chord_error == 0) feature_options.max_chord_error = 5e-4 * result.input_report.bbox_diagonal;
  remesh::FeatureSampling creases = remesh::sample_features(prepared, sites, feature_options);
  remesh::ShortCreasePins pins;
  if (options.features.pin_short_creases) {
    pins = remesh::pin_short_creases(prepared, sites, creases, feature_options.max_chord_error);
  }
  report(options.progress, Stage::sample, 0.5);
  sampled.initial = remesh::sample_remesh_sites(prepared, sites, creases, pins, options.sampling, given_share);
  result.crease_pins_reason = std::move(pins.reason);
  sampled.pin_segments = std::move(pins.segments);
  result.feature_sites = creases.sites.points;
  result.feature_sites_tightened = creases.points_tightened;
  result.feature_chains_split_at_bends = creases.sites.chains_split_at_bends;
  result.site_twins = static_cast<std::int64_t>(creases.sites.sites.size()) - creases.sites.points;
  result.features = std::move(creases.features);
  result.feature_cut = std::move(creases.cut);
  sampled.feature_density = std::move(creases.density);
  // The sites on chains slide along them in the relaxation; corners stay.
  if (!result.features.empty()) sampled.slide_along_chains.emplace(prepared, result.features, result.feature_cut);
  result.sites_added_near_features = sampled.initial.sites_added_near_features;
  result.sites_added_for_topology = sampled.initial.sites_added_for_topology;
  result.sites_added_reason = sampled.initial.topology_reason;
  result.sites_added_for_creases = sampled.initial.sites_added_for_crowding;
  result.sites_added_for_creases_reason = sampled.initial.crowding_reason;
  if (sampled.initial.sites_added_for_topology > 0) {
    // The loops of the surface cut to a manifold (those of the features' cut are the chains' sides).
    result.sites_added_reason += loops_made_by_cut(
        result, result.features.empty() ? sampled.initial.boundary_loops : result.surface_boundary_loops);
  }
  return sampled;
}

/// The relaxation's options for the sites sampled on `surface` (the cut along
/// the features, or the surface cut to a manifold: `cut_is_input` where that
/// is the input itself), with Lloyd's density multiplied by `input_density`
/// (per input vertex; empty: 1).
remesh::LloydOptions relaxation_stage_options(const RemeshPipelineResult& result, const RemeshPipelineOptions& options,
                                              const TriangleMesh& surface, const SampledSites& sampled,
                                              std::span<const double> input_density, bool cut_is_input) {
  remesh::LloydOptions lloyd =
      remesh::relaxation_options(surface, sampled.initial, sampled.feature_density, options.remesh);
  if (!input_density.empty() && lloyd.iterations > 0) {
    // Each vertex of the surface copies one of the input's (through the cuts).
    std::vector<double> density(static_cast<std::size_t>(surface.num_vertices()));
    for (std::size_t v = 0; v < density.size(); ++v) {
      Index original = static_cast<Index>(v);
      if (!result.features.empty()) original = result.feature_cut.original_vertex[static_cast<std::size_t>(original)];
      if (!cut_is_input) original = result.surface.original_vertex[static_cast<std::size_t>(original)];
      density[v] = input_density[static_cast<std::size_t>(original)] * (lloyd.density.empty() ? 1.0 : lloyd.density[v]);
    }
    lloyd.density = std::move(density);
  }
  if (sampled.slide_along_chains) lloyd.slide_boundary_sites = std::cref(*sampled.slide_along_chains);
  return lloyd;
}

/// lloyd_relax, reporting its progress: the geodesic engine reports the
/// fraction of faces reached in each diagram; Lloyd's accepted iterations
/// split the stage.
remesh::LloydResult relax_with_progress(const voronoi::GeodesicSurface& surface, std::vector<SurfacePoint> sites,
                                        remesh::LloydOptions lloyd, const ProgressCallback& progress) {
  // From the warm start the iterations mostly stop after one or two
  // (LloydOptions::geodesic_tolerance); without that stop, all of them run.
  const int diagrams = (lloyd.geodesic_tolerance > 0 ? std::min(lloyd.iterations, 2) : lloyd.iterations) + 1;
  int diagrams_done = 0;  // the first diagram, then one per accepted iteration
  double relaxed = 0;     // the fraction reported last
  if (progress) {
    lloyd.on_iteration = [&](int iterations_done, bool) { diagrams_done = iterations_done + 1; };
    lloyd.voronoi.geodesic.progress = [&](double fraction) {
      // Never backwards: a rejected step's diagram holds the fraction where it is.
      relaxed = std::max(relaxed, std::min(1.0, (diagrams_done + std::min(fraction, 1.0)) / diagrams));
      return progress(Stage::relax, relaxed);
    };
  }
  return remesh::lloyd_relax(surface, std::move(sites), lloyd);
}

/// The dual of result.relaxation with repair, welded along the features
/// where there are any (on `manifold_surface`, the surface cut to a manifold).
remesh::RepairedDual dual_stage(RemeshPipelineResult& result, const RemeshPipelineOptions& options,
                                const voronoi::GeodesicSurface& surface, const TriangleMesh& manifold_surface) {
  const bool features = !result.features.empty();
  remesh::RepairOptions repair = features
                                     ? remesh::repair_options(options.remesh, options.features,
                                                              static_cast<std::int64_t>(result.initial_sites.size()))
                                     : remesh::repair_options(options.remesh);
  if (options.progress) {
    // Each repair round's diagram reports its progress.
    repair.voronoi.geodesic.progress = [&](double) { return options.progress(Stage::dual, 0.5); };
  }
  // The relaxed diagram moves on to the dual (its first round's diagram).
  try {
    return features
               ? remesh::welded_dual_with_repair(surface, manifold_surface, result.features, result.feature_cut,
                                                 result.relaxation.sites, std::move(result.relaxation.diagram), repair)
               : remesh::dual_with_repair(surface, result.relaxation.sites, std::move(result.relaxation.diagram),
                                          repair);
  } catch (const Cancelled&) {
    throw;
  } catch (const remesh::DualRepairError& e) {
    // The message names the surface's pieces and loops: say where loops the
    // input does not have come from.
    const std::string note = loops_made_by_cut(result, result.surface_boundary_loops);
    if (note.empty()) throw;
    throw remesh::DualRepairError(e.what() + note, e.places());
  }
}

/// After the dual: the pins' vertices joined along the short creases, then
/// (with a relaxation: without one the remesh is the dual of the sites as
/// they are) the deviation fitting and the angle smoothing, on `surface`,
/// the surface the sites lie on (`manifold_surface` cut along the features).
void after_dual_stage(RemeshPipelineResult& result, const RemeshPipelineOptions& options, const TriangleMesh& surface,
                      const voronoi::SurfaceTopology& topology, const TriangleMesh& manifold_surface,
                      std::span<const std::array<std::size_t, 2>> pin_segments) {
  std::vector<Index> pin_vertex;
  if (!pin_segments.empty() && result.remesh.mesh.num_faces() > 0) {
    // Onto the short creases: the pins' vertices joined by edges where flips can do it.
    pin_vertex = crease_pin_vertices(result);
    result.crease_segments = remesh::follow_pin_segments(result.remesh.mesh, pin_vertex, pin_segments);
  }
  result.smoothing = {};
  result.fitting = {};
  if (!(options.smoothing.smoothing_angle > 0 || options.smoothing.fit_deviations) ||
      options.remesh.lloyd.iterations <= 0 || result.remesh.mesh.num_faces() == 0) {
    return;
  }
  // Where creases are pinned, what follows them within the feature recall's
  // tolerance stays.
  const std::span<const remesh::FeatureChain> pinned_creases =
      result.crease_pins > 0 ? std::span<const remesh::FeatureChain>(result.features.short_creases)
                             : std::span<const remesh::FeatureChain>();
  remesh::RemeshSmoothingOptions smoothing = options.smoothing;
  if (smoothing.crease_tolerance == 0) {
    smoothing.crease_tolerance = options.quality.feature_tolerance_pct / 100 * result.input_report.bbox_diagonal;
  }
  const remesh::RemeshSmoothing smoothed =
      remesh::smooth_remesh(result.remesh, surface, topology, smoothing, pin_vertex, pinned_creases, &manifold_surface);
  result.smoothing = smoothed.smoothing;
  result.fitting = smoothed.fitting;
}

/// The remesh compared with the input (quality, distances, feature recall).
quality::QualityReport statistics_stage(const RemeshPipelineResult& result, const RemeshPipelineOptions& options) {
  quality::QualityOptions quality_options = options.quality;
  if (quality_options.long_crease_length == 0) {
    // The creases a remesh of this many vertices can keep: those at least its spacing long.
    quality_options.long_crease_length =
        remesh::uniform_spacing(result.input.mesh, std::max<Index>(4, result.remesh.mesh.num_vertices()));
  }
  if (options.progress) {
    quality_options.progress = [&](double fraction) { return options.progress(Stage::statistics, fraction); };
  }
  return quality::compare_meshes(result.input.mesh, result.remesh.mesh, quality_options);
}

/// The stages after `load` on result.input, filling in `result`; Lloyd's
/// density is multiplied by `input_density` (per input vertex; empty: 1).
/// With `refinement` the sites are its, not sampled; otherwise, with sharp
/// features, the sites beside the creases are shared as `given_share` says.
/// Returns false, after the sampling, where the sites sampled are
/// `tried_sites` (the stages after it are deterministic: they would repeat
/// the run that started from them). The `excluded_edges` (vertex pairs of
/// the surface cut to a manifold) are never features.
bool run_stages(RemeshPipelineResult& result, const RemeshPipelineOptions& options,
                std::span<const double> input_density, const SiteRefinement* refinement,
                remesh::GivenSiteShare given_share = remesh::GivenSiteShare::half_cell,
                const std::vector<SurfacePoint>* tried_sites = nullptr,
                std::span<const std::array<Index, 2>> excluded_edges = {}) {
  report(options.progress, Stage::sample, 0.0);
  StageClock sample_clock(result.timings, Stage::sample);
  MeshTopology surface_topology;  // of the surface cut to a manifold, built once
  result.surface = remesh::cut_to_manifold(result.input.mesh, {}, surface_topology);
  report(options.progress, Stage::sample, 0.25);  // each step below takes a while on a large mesh: a chance to cancel
  result.dropped = dropped_surface(result.input.mesh, result.surface);
  std::vector<SurfacePoint> given_sites;
  if (options.given_sites) given_sites = remesh::points_on_cut(result.surface, *options.given_sites);
  // Where the cut changed nothing, its mesh is a copy of the input's: the
  // stages work on the input's (the relaxation is the peak of the memory),
  // and the copy is made again after them.
  const bool cut_is_input = result.surface.mesh.vertices.rows() == result.input.mesh.vertices.rows() &&
                            result.surface.mesh.faces.rows() == result.input.mesh.faces.rows() &&
                            result.surface.mesh.vertices == result.input.mesh.vertices &&
                            result.surface.mesh.faces == result.input.mesh.faces;
  if (cut_is_input) result.surface.mesh = TriangleMesh{};
  const TriangleMesh& manifold_surface = cut_is_input ? result.input.mesh : result.surface.mesh;
  // Its topology, built once for the sizing, the features and the sampling; gone before the relaxation.
  std::optional<remesh::RemeshSurface> prepared(std::in_place, manifold_surface, std::move(surface_topology));
  result.surface_euler_characteristic = 0;
  for (const ComponentCounts& piece : prepared->topology().components) {
    result.surface_euler_characteristic += piece.euler_characteristic();
  }
  result.surface_boundary_loops = prepared->topology().num_boundary_loops;
  require_dropped_area_allowed(result, options);
  // Sizing: the site count for the edge length or face count asked, on the surface remeshed.
  std::int64_t sites = options.sites;
  if (options.edge_length > 0) {
    sites = result.sites_for_sizing = remesh::sites_for_edge_length(*prepared, options.edge_length);
  } else if (options.faces > 0) {
    sites = result.sites_for_sizing = remesh::sites_for_faces(*prepared, options.faces);
  }
  SampledSites sampled;
  std::vector<std::uint8_t> staying;  // of a local refinement: the sites its relaxation leaves where they are
  result.sites_added_near_features = 0;
  if (options.given_sites) {
    sampled.initial.sites = std::move(given_sites);
    remesh::require_a_site_on_every_piece(*prepared, sampled.initial.sites);
  } else if (refinement) {
    auto on_surface = [&](std::span<const double> field) {  // per input vertex -> per surface vertex
      std::vector<double> values;
      if (field.empty()) return values;
      values.resize(static_cast<std::size_t>(manifold_surface.num_vertices()));
      for (std::size_t v = 0; v < values.size(); ++v) values[v] = field[result.surface.original_vertex[v]];
      return values;
    };
    const std::vector<double> density_now = on_surface(input_density);
    sampled.initial.sites = remesh::add_sites_at_deviations(
        manifold_surface, refinement->sites, on_surface(refinement->deviation), density_now,
        remesh::uniform_spacing(manifold_surface, sites), refinement->added);
    if (options.refine_locally) {
      staying = remesh::sites_away_from_added(manifold_surface, sampled.initial.sites, refinement->sites.size(),
                                              kLocalRefinementReach * remesh::uniform_spacing(manifold_surface, sites));
    }
  } else {
    sampled = sample_around_features(result, options, *prepared, sites, given_share, excluded_edges);
  }
  result.initial_sites = sampled.initial.sites;
  result.crease_pins = sampled.initial.pins;
  result.first_crease_pin = sampled.initial.first_pin;
  sample_clock.stop();
  report(options.progress, Stage::sample, 1.0);
  if (tried_sites && result.initial_sites == *tried_sites) return false;
  prepared.reset();

  // The surface the sites lie on, prepared once for every diagram of the
  // relax and dual stages; gone before the statistics.
  const TriangleMesh& surface = result.features.empty() ? manifold_surface : result.feature_cut.mesh;
  remesh::LloydOptions lloyd = relaxation_stage_options(result, options, surface, sampled, input_density, cut_is_input);
  if (!staying.empty() && lloyd.iterations > 0) {
    // The sites that move are few, among sites an earlier relaxation left
    // near the geodesic CVT: the restricted diagram's steps bring them there
    // too, without an exact diagram per step.
    lloyd.fixed_sites.resize(staying.size(), 0);
    for (std::size_t s = 0; s < staying.size(); ++s) lloyd.fixed_sites[s] |= staying[s];
    lloyd.iterations = 0;
    lloyd.warm_start_alone = true;
  }
  report(options.progress, Stage::relax, 0.0);
  StageClock relax_clock(result.timings, Stage::relax);
  std::optional<voronoi::GeodesicSurface> geodesic_surface(std::in_place, surface);
  result.relaxation = relax_with_progress(*geodesic_surface, result.initial_sites, std::move(lloyd), options.progress);
  relax_clock.stop();
  report(options.progress, Stage::relax, 1.0);

  report(options.progress, Stage::dual, 0.0);
  StageClock dual_clock(result.timings, Stage::dual);
  result.remesh = dual_stage(result, options, *geodesic_surface, manifold_surface);
  after_dual_stage(result, options, surface, *geodesic_surface->topology(), manifold_surface, sampled.pin_segments);
  geodesic_surface.reset();
  // The prepared surface was the largest thing held: handed back before the
  // copies and outputs that follow, which would otherwise come on top.
  if (options.remesh.lloyd.voronoi.geodesic.release_memory_between_phases) trim_heap();
  if (options.attributes && !result.input.attributes.empty()) {
    result.attributes =
        interpolate_attributes(result.input.mesh, result.input.attributes, remesh_vertices_on_input(result));
  }
  dual_clock.stop();
  report(options.progress, Stage::dual, 1.0);

  if (options.statistics) {
    report(options.progress, Stage::statistics, 0.0);
    StageClock statistics_clock(result.timings, Stage::statistics);
    result.statistics = statistics_stage(result, options);
    statistics_clock.stop();
    report(options.progress, Stage::statistics, 1.0);
  }
  if (cut_is_input) result.surface.mesh = result.input.mesh;
  return true;
}

}  // namespace

std::vector<Index> crease_pin_vertices(const RemeshPipelineResult& result) {
  return remesh::pin_vertices(result.remesh, std::span<const SurfacePoint>(result.initial_sites)
                                                 .subspan(static_cast<std::size_t>(result.first_crease_pin),
                                                          static_cast<std::size_t>(result.crease_pins)));
}

std::vector<SurfacePoint> remesh_vertices_on_input(const RemeshPipelineResult& result) {
  return remesh::remesh_points_on_input(result.remesh, result.surface, result.feature_cut);
}

namespace {

/// The sharp edges of `features` (on `surface`, cut along them as `cut`) to
/// leave out where a remesh that kept them failed at `places`: those with an
/// end within `radius` of a place, and where a boundary loop is a feature
/// there (a sharp chain runs into it), those with an end on that loop.
std::vector<std::array<Index, 2>> sharp_edges_near(const TriangleMesh& surface, const remesh::FeatureSet& features,
                                                   const remesh::FeatureCut& cut,
                                                   const std::vector<Eigen::Vector3d>& places, double radius) {
  const auto close = [&](Index v) {
    const Eigen::Vector3d x = surface.vertices.row(v);
    return std::any_of(places.begin(), places.end(),
                       [&](const Eigen::Vector3d& p) { return (p - x).norm() <= radius; });
  };
  const remesh::SurfaceOutline& outline = cut.surface;
  std::vector<Index> loop_of_vertex(static_cast<std::size_t>(surface.num_vertices()), -1);
  Index loops = 0;
  for (std::size_t e = 0; e < outline.boundary_edges.size(); ++e) {
    const Index loop = outline.boundary_edge_loop[e];
    for (const Index v : outline.boundary_edges[e]) loop_of_vertex[v] = loop;
    loops = std::max(loops, loop + 1);
  }
  std::vector<std::uint8_t> loop_near(static_cast<std::size_t>(loops), 0);
  for (const remesh::FeatureChain& chain : features.chains) {
    if (chain.on_boundary && std::any_of(chain.vertices.begin(), chain.vertices.end(), close)) {
      loop_near[loop_of_vertex[chain.vertices[1]]] = 1;  // an inner vertex: not a corner on two loops
    }
  }
  const auto on_loop_near = [&](Index v) { return loop_of_vertex[v] >= 0 && loop_near[loop_of_vertex[v]]; };
  std::vector<std::array<Index, 2>> near;
  for (const auto& [a, b] : features.sharp_edges) {
    if (close(a) || close(b) || on_loop_near(a) || on_loop_near(b)) near.push_back({a, b});
  }
  return near;
}

/// `edges` (vertex pairs of `surface`) by stretch: joined where they share
/// a vertex, longest first.
std::vector<FeatureLeftOut> stretches_of(const TriangleMesh& surface, std::span<const std::array<Index, 2>> edges) {
  UnionFind sets(static_cast<std::size_t>(surface.num_vertices()));
  for (const auto& [a, b] : edges) sets.unite(a, b);
  std::vector<Index> stretch_of_root(static_cast<std::size_t>(surface.num_vertices()), -1);
  std::vector<FeatureLeftOut> stretches;
  std::vector<Eigen::Vector3d> centroid;  // length-weighted sums, then means
  for (const auto& [a, b] : edges) {
    Index& stretch = stretch_of_root[static_cast<std::size_t>(sets.find(a))];
    if (stretch < 0) {
      stretch = static_cast<Index>(stretches.size());
      stretches.emplace_back();
      centroid.emplace_back(Eigen::Vector3d::Zero());
    }
    const Eigen::Vector3d pa = surface.vertices.row(a), pb = surface.vertices.row(b);
    const double length = (pb - pa).norm();
    ++stretches[stretch].edges;
    stretches[stretch].length += length;
    centroid[stretch] += length * (pa + pb) / 2;
  }
  std::vector<double> nearest(stretches.size(), std::numeric_limits<double>::infinity());
  for (std::size_t s = 0; s < stretches.size(); ++s) {
    if (stretches[s].length > 0) centroid[s] /= stretches[s].length;
  }
  for (const auto& edge : edges) {
    for (const Index v : edge) {
      const Index s = stretch_of_root[static_cast<std::size_t>(sets.find(v))];
      const Eigen::Vector3d x = surface.vertices.row(v);
      if (const double d = (x - centroid[s]).squaredNorm(); d < nearest[s]) {
        nearest[s] = d;
        stretches[s].place = x;
      }
    }
  }
  std::stable_sort(stretches.begin(), stretches.end(),
                   [](const FeatureLeftOut& a, const FeatureLeftOut& b) { return a.length > b.length; });
  return stretches;
}

/// Where the tries that keep the features all failed: why the last failed,
/// and the creases the tries had, by stretch.
struct FeaturesNotKept {
  std::string reason;
  std::vector<FeatureLeftOut> left_out;
  bool chains_split_at_bends = false;  ///< in some try (FeatureSites::chains_split_at_bends)
};

/// One remesh of result.input (run_stages) that keeps the features: where
/// they cannot be kept with sites as dense beside the creases as elsewhere,
/// they are tried with the denser sites of the components' shares by area
/// (remesh::GivenSiteShare); where they cannot be kept either and the
/// failure lies at places (remesh::DualRepairError), again without the
/// creases near those places, a few times, each try leaving out more where
/// the last failed; where a failure names no place near a crease, or the
/// tries run out, on with as many repair rounds as the remesh without
/// features gets (its faults may lie away from the creases: a thin part, a
/// handle the sites missed), again leaving out creases where it fails. What
/// is left out is reported (RemeshPipelineResult::features_left_out).
/// Returns what the tries could not keep where none succeeded; none where
/// one did.
std::optional<FeaturesNotKept> remesh_keeping_features(RemeshPipelineResult& result,
                                                       const RemeshPipelineOptions& options,
                                                       std::span<const double> input_density,
                                                       const SiteRefinement* refinement) {
  // Only a failure of the remesh that keeps the features (not of the statistics after it) tries again.
  const auto features_failed = [&] { return !result.features.empty() && result.remesh.mesh.num_faces() == 0; };
  std::string reason;                          // why the last try failed
  std::vector<Eigen::Vector3d> places;         // and where
  std::vector<SurfacePoint> first_sites;       // of the first try, where it failed
  std::vector<std::array<Index, 2>> excluded;  // the sharp edges left out near those places
  std::vector<Eigen::Vector3d> dropped_near;   // the places
  std::string dropped_reason;                  // why the try with them all failed
  bool split_at_bends = false;                 // some failed try split chains where they bend
  // Each try costs a relaxation; a part that still fails after this many
  // has creases finer than the spacing all over.
  constexpr int kMaxCreaseDrops = 6, kMaxPatientDrops = 2;
  RemeshPipelineOptions patient = options;
  patient.features.max_repair_rounds = std::max(options.features.max_repair_rounds, options.remesh.max_repair_rounds);
  bool patient_now = false;  // the tries with patient's repair rounds have begun
  int drops_left = kMaxCreaseDrops;
  for (int round = 0;; ++round) {
    const int attempts = round == 0 && !refinement ? 2 : 1;
    for (int attempt = 0; attempt < attempts; ++attempt) {
      try {
        if (round > 0 || attempt > 0) result.timings.clear();
        result.remesh = {};  // a remesh below is this try's (features_failed)
        // Where the denser sites come out the same (few sites beside short
        // creases), the second try would only repeat the first.
        if (!run_stages(result, patient_now ? patient : options, input_density, refinement,
                        attempt == 0 ? remesh::GivenSiteShare::half_cell : remesh::GivenSiteShare::none,
                        attempt > 0 ? &first_sites : nullptr, excluded)) {
          break;
        }
        if (attempt > 0) {
          result.remesh.repair_problems.insert(
              result.remesh.repair_problems.begin(),
              "sites beside the creases made denser, as the weld with them as dense as elsewhere failed: " + reason);
        }
        if (patient_now) {
          result.remesh.repair_problems.insert(
              result.remesh.repair_problems.begin(),
              "the creases kept with up to " + std::to_string(patient.features.max_repair_rounds) +
                  " repair rounds, as " + std::to_string(options.features.max_repair_rounds) +
                  " were not enough: " + reason);
        }
        // A try that left out every crease kept none: no better than the
        // remesh without features, and not taken as keeping them.
        if (!excluded.empty() && result.features.empty()) {
          const TriangleMesh& surface = result.surface.mesh;
          return FeaturesNotKept{"every crease left out near the faults: " + dropped_reason,
                                 stretches_of(surface, excluded), split_at_bends};
        }
        if (!excluded.empty()) {
          result.features_dropped_near = std::move(dropped_near);
          result.features_partly_dropped_reason = std::move(dropped_reason);
          result.features_left_out = stretches_of(result.surface.mesh, excluded);
        }
        return std::nullopt;
      } catch (const Cancelled&) {
        throw;
      } catch (const Error& e) {
        if (!features_failed()) throw;
        reason = e.what();
        split_at_bends = split_at_bends || result.feature_chains_split_at_bends > 0;
        const auto* repair = dynamic_cast<const remesh::DualRepairError*>(&e);
        places = repair ? repair->places() : std::vector<Eigen::Vector3d>{};
        if (round == 0 && attempt == 0) first_sites = std::move(result.initial_sites);
      }
    }
    // The surface the features are on (its copy is held back during the stages where it is the input).
    const TriangleMesh& surface = result.surface.mesh.num_vertices() > 0 ? result.surface.mesh : result.input.mesh;
    std::vector<std::array<Index, 2>> near;
    if (const double spacings = options.features.retry_radius; spacings > 0 && !places.empty()) {
      const double radius = spacings * remesh::uniform_spacing(surface, static_cast<std::int64_t>(first_sites.size()));
      near = sharp_edges_near(surface, result.features, result.feature_cut, places, radius);
    }
    if (drops_left > 0 && !near.empty()) {
      --drops_left;
      excluded.insert(excluded.end(), near.begin(), near.end());
      dropped_near.insert(dropped_near.end(), places.begin(), places.end());
      if (dropped_reason.empty()) dropped_reason = reason;
    } else if (!patient_now && patient.features.max_repair_rounds > options.features.max_repair_rounds) {
      patient_now = true;
      drops_left = kMaxPatientDrops;
    } else {
      break;
    }
  }
  // Every crease the tries kept, and those the last left out.
  const TriangleMesh& surface = result.surface.mesh.num_vertices() > 0 ? result.surface.mesh : result.input.mesh;
  std::vector<std::array<Index, 2>> all = result.features.sharp_edges;
  all.insert(all.end(), excluded.begin(), excluded.end());
  return FeaturesNotKept{std::move(reason), stretches_of(surface, all), split_at_bends};
}

/// `options` with the next narrow regions judged rough, keeping fewer creases:
/// a machined surface's (FeatureSamplingOptions::machined_regions_smooth),
/// then narrow faceted sides (parallel_fold_angle); none after those.
std::optional<RemeshPipelineOptions> rougher(const RemeshPipelineOptions& options) {
  RemeshPipelineOptions rough = options;
  remesh::FeatureSamplingOptions& sampling = rough.features.sampling;
  if (sampling.machined_regions_smooth) {
    sampling.machined_regions_smooth = false;
  } else if (sampling.parallel_fold_angle > 0) {
    sampling.parallel_fold_angle = 0;
  } else {
    return std::nullopt;
  }
  return rough;
}

/// Whether the creases `options` detect on result's surface for `sites`
/// sites include some that `rough` (rougher's) leaves out.
bool narrow_regions_hold_creases(const RemeshPipelineResult& result, const RemeshPipelineOptions& options,
                                 const RemeshPipelineOptions& rough, std::int64_t sites) {
  const TriangleMesh& surface = result.surface.mesh.num_vertices() > 0 ? result.surface.mesh : result.input.mesh;
  const auto creases = [&](const RemeshPipelineOptions& with) {
    const remesh::FeatureSamplingOptions sampling =
        remesh::feature_sampling_options(with.features, result.input.mesh, result.surface);
    return remesh::detect_features(surface, remesh::feature_detection_options(surface, sites, sampling))
        .sharp_edges.size();
  };
  return creases(rough) != creases(options);
}

/// One remesh of result.input (run_stages) that keeps the features
/// (remesh_keeping_features); where no try keeps them with the sites asked
/// for, with twice as many, as often as options.features.max_site_doublings
/// says (the sites added reported, and why); only where that fails too, the
/// remesh without any, and why.
void remesh_once(RemeshPipelineResult& result, const RemeshPipelineOptions& options,
                 std::span<const double> input_density, const SiteRefinement* refinement = nullptr) {
  // Where the tries fail with chain sites closer along curved creases (at
  // their vertices where they bend), once more with them evenly closer, then
  // with them no closer than min_spacing: other chain sites, or fewer, weld
  // where those did not (a part whose creases bend at every spacing).
  const auto keep_features = [&](const RemeshPipelineOptions& with) {
    std::optional<FeaturesNotKept> not_kept = remesh_keeping_features(result, with, input_density, refinement);
    if (!not_kept || !with.features.loosen_chain_sites) return not_kept;
    if (not_kept->chains_split_at_bends) {
      // The points where chains bend, evenly closer instead of at their vertices.
      RemeshPipelineOptions even = with;
      even.features.sampling.split_at_bends = false;
      result.timings.clear();
      if (!remesh_keeping_features(result, even, input_density, refinement) && !result.features.empty()) {
        result.remesh.repair_problems.insert(
            result.remesh.repair_problems.begin(),
            "chain sites evenly closer where creases bend, as the weld with them at the creases' vertices failed: " +
                not_kept->reason);
        return std::optional<FeaturesNotKept>{};
      }
    }
    if (result.feature_sites_tightened == 0) return not_kept;
    RemeshPipelineOptions loose = with;
    loose.features.sampling.tight_spacing = 0;
    result.timings.clear();
    if (remesh_keeping_features(result, loose, input_density, refinement) || result.features.empty()) return not_kept;
    result.remesh.repair_problems.insert(
        result.remesh.repair_problems.begin(),
        "chain sites no closer along curved creases than elsewhere on them, as the weld with closer ones failed: " +
            not_kept->reason);
    return std::optional<FeaturesNotKept>{};
  };
  std::optional<FeaturesNotKept> not_kept = keep_features(options);
  if (!not_kept) return;
  // The count the sites were asked for (sized, or as given).
  const std::int64_t asked = options.edge_length > 0 || options.faces > 0 ? result.sites_for_sizing : options.sites;
  if (!refinement && !options.given_sites) {
    RemeshPipelineOptions more = options;
    more.edge_length = 0;
    more.faces = 0;
    for (int doubling = 1; doubling <= options.features.max_site_doublings; ++doubling) {
      more.sites = asked << doubling;
      result.timings.clear();
      // Kept, and there were creases to keep at that spacing (the scale they
      // are judged at shrinks with it).
      if (!keep_features(more) && !result.features.empty()) {
        // Beside the doublings, what the try's sampling added where chains crowd narrow pieces.
        result.sites_added_for_creases += more.sites - asked;
        result.sites_added_for_creases_reason =
            "site count " + std::to_string(asked) + " raised to " + std::to_string(more.sites) +
            " for the creases: with that count no try kept them (" + not_kept->reason + ")" +
            (result.sites_added_for_creases_reason.empty() ? "" : "; " + result.sites_added_for_creases_reason);
        return;
      }
    }
  }
  // Where the creases round narrow regions are too many for every count
  // tried, all that again without those (a machined surface's first, then
  // faceted sides), before no crease at all.
  const auto at_some_count = [&](const RemeshPipelineOptions& rough) {  // of those tried
    const int doublings = refinement || options.given_sites ? 0 : options.features.max_site_doublings;
    for (int doubling = 0; doubling <= doublings; ++doubling) {
      if (narrow_regions_hold_creases(result, options, rough, asked << doubling)) return true;
    }
    return false;
  };
  // The first rougher options that leave creases out.
  std::optional<RemeshPipelineOptions> rough =
      options.features.drop_faceted_sides ? rougher(options) : std::optional<RemeshPipelineOptions>{};
  while (rough && !at_some_count(*rough)) rough = rougher(*rough);
  if (rough) {
    const bool machined = !rough->features.sampling.machined_regions_smooth &&
                          rough->features.sampling.parallel_fold_angle == options.features.sampling.parallel_fold_angle;
    result.timings.clear();
    remesh_once(result, *rough, input_density, refinement);
    if (!result.features.empty()) {
      result.remesh.repair_problems.insert(
          result.remesh.repair_problems.begin(),
          std::string(machined ? "the creases round the machined surface's narrow rough regions"
                               : "the creases round narrow faceted sides") +
              " left out, as no try kept them: " + not_kept->reason);
    }
    return;
  }
  result.features_dropped_reason = std::move(not_kept->reason);
  result.features_left_out = std::move(not_kept->left_out);
  result.features = {};
  result.feature_cut = {};
  result.feature_sites = result.site_twins = result.sites_added_near_features = result.sites_added_for_creases = 0;
  result.sites_added_for_creases_reason.clear();
  result.timings.clear();
  RemeshPipelineOptions without = options;
  without.features.sampling.sharp_angle = 0;
  without.features.sampling.given_edges.clear();
  run_stages(result, without, input_density, nullptr);
}

/// Remeshes until the Hausdorff distance is within options.max_error_pct:
/// each round's density is the last one's refined where the last remesh
/// strayed beyond the bound (remesh::refine_density), with the sites that
/// keep the spacing elsewhere (remesh::sites_for_density).
RemeshPipelineResult remesh_within_error(RemeshPipelineResult result, const RemeshPipelineOptions& options) {
  RemeshPipelineOptions round = options;
  round.quality.deviation_at_vertices = true;
  const double bound = options.max_error_pct / 100 * result.input_report.bbox_diagonal;
  std::vector<double> density;  // per input vertex; empty: 1
  std::vector<ErrorRound> rounds;
  std::vector<StageTiming> timings;
  std::optional<RemeshPipelineResult> best;  // the closest remesh so far (the input stays with `result`)
  std::int64_t max_sites = options.max_sites;
  // Where a remesh kept no features, the next starts from its sites, so that
  // a narrow detail it has a site on keeps it; after one that kept them
  // (sites on the features' cut, which the fallback may drop) or pinned
  // short creases (pins that the next count spaces anew) the next samples
  // afresh.
  std::optional<SiteRefinement> refinement;
  for (;;) {
    if (options.on_error_round) options.on_error_round(static_cast<int>(rounds.size()) + 1, round.sites);
    remesh_once(result, round, density, refinement ? &*refinement : nullptr);
    const std::int64_t sites = result.sites_for_sizing > 0 ? result.sites_for_sizing : round.sites;
    if (max_sites == 0) max_sites = 8 * sites;
    const double error_pct = result.statistics->hausdorff_pct;
    rounds.push_back({sites, error_pct});
    timings.insert(timings.end(), result.timings.begin(), result.timings.end());
    const bool met = error_pct <= options.max_error_pct;
    const bool last = met || static_cast<int>(rounds.size()) == options.max_error_rounds || sites >= max_sites;
    std::vector<double> deviation = std::move(result.statistics->deviation_at_vertices);
    const bool reuse_sites = result.features.empty() && result.crease_pins == 0;
    std::vector<SurfacePoint> last_sites;
    if (reuse_sites) last_sites = result.remesh.sites;
    // The next round fills in a fresh result, which takes the input over.
    RemeshPipelineResult next;
    next.input = std::move(result.input);
    next.input_report = result.input_report;
    if (met || !best || error_pct < best->statistics->hausdorff_pct) best = std::move(result);
    result = std::move(next);
    if (last) break;
    const TriangleMesh& mesh = result.input.mesh;
    std::vector<double> refined = remesh::refine_density(
        mesh, density, deviation, {.max_error = bound, .spacing = remesh::uniform_spacing(mesh, sites)});
    const std::int64_t next_sites = std::min(max_sites, remesh::sites_for_density(mesh, sites, density, refined));
    refinement.reset();
    if (reuse_sites) {
      refinement = SiteRefinement{std::move(last_sites), std::move(deviation), next_sites - sites};
    }
    round.sites = next_sites;
    round.edge_length = 0;
    round.faces = 0;
    density = std::move(refined);
  }
  best->input = std::move(result.input);
  best->error_rounds = std::move(rounds);
  best->error_bound_met = best->statistics->hausdorff_pct <= options.max_error_pct;
  best->timings = std::move(timings);
  return std::move(*best);
}

/// The texture stage (options.texture_size > 0): the remesh's atlas and the input's look baked onto it.
void texture_stage(RemeshPipelineResult& result, const RemeshPipelineOptions& options) {
  report(options.progress, Stage::texture, 0.0);
  StageClock clock(result.timings, Stage::texture);
  const TriangleMesh& remeshed = result.remesh.mesh;
  const double angle = options.features.sampling.sharp_angle > 0 ? options.features.sampling.sharp_angle : 60.0;
  remesh::AtlasOptions atlas_options{.texture_size = options.texture_size, .seams = atlas_seams(remeshed, angle)};
  result.atlas = remesh::make_texture_atlas(remeshed, atlas_options);
  report(options.progress, Stage::texture, 0.5);
  const VertexAttributes& look = result.input.attributes;
  result.textures = remesh::bake_textures(
      result.input.mesh, {.colors = look.colors, .normals = look.normals, .texture = result.input.texture}, remeshed,
      *result.atlas, {.texture_size = options.texture_size, .normal_map = options.bake_normal_map});
  clock.stop();
  report(options.progress, Stage::texture, 1.0);
}

}  // namespace

std::vector<Index> weld_texture_seams(io::LoadedMesh& input) {
  if (input.texture.empty()) return {};
  PositionWelder welder(static_cast<std::size_t>(input.mesh.num_vertices()));
  std::vector<Index> welded(static_cast<std::size_t>(input.mesh.num_vertices()));
  std::vector<Index> first_copy;
  for (Index v = 0; v < input.mesh.num_vertices(); ++v) {
    welded[v] = welder.weld(input.mesh.vertices(v, 0), input.mesh.vertices(v, 1), input.mesh.vertices(v, 2));
    if (welded[v] == static_cast<Index>(first_copy.size())) first_copy.push_back(v);
  }
  if (welder.welded_corners() == 0) return {};
  input.mesh.vertices = welder.vertices();
  for (Eigen::Index i = 0; i < input.mesh.faces.size(); ++i) {
    input.mesh.faces.data()[i] = welded[input.mesh.faces.data()[i]];
  }
  VertexAttributes& attributes = input.attributes;
  const auto keep_first = [&](auto& rows) {
    if (rows.rows() == 0) return;
    std::remove_cvref_t<decltype(rows)> kept(static_cast<Eigen::Index>(first_copy.size()), rows.cols());
    for (std::size_t v = 0; v < first_copy.size(); ++v) {
      kept.row(static_cast<Eigen::Index>(v)) = rows.row(first_copy[v]);
    }
    rows = std::move(kept);
  };
  keep_first(attributes.colors);
  keep_first(attributes.normals);
  for (VertexScalar& scalar : attributes.scalars) {
    std::vector<double> kept;
    kept.reserve(first_copy.size());
    for (const Index v : first_copy) kept.push_back(scalar.values[static_cast<std::size_t>(v)]);
    scalar.values = std::move(kept);
  }
  input.info.notes.push_back(std::to_string(welder.welded_corners()) +
                             " vertices at the same position as another welded to it (the texture's seams)");
  return welded;
}

std::vector<std::array<Index, 2>> atlas_seams(const TriangleMesh& remesh, double angle_degrees) {
  const MeshTopology topology = build_mesh_topology(remesh);
  std::vector<std::array<Index, 2>> seams;
  for (const Index e : sharp_edges(remesh, topology, angle_degrees)) seams.push_back(topology.edge_vertices[e]);
  return seams;
}

RemeshPipelineResult run_remesh_pipeline(io::LoadedMesh input, const RemeshPipelineOptions& given_options) {
  require_one_site_source(given_options);
  require_error_bound_options(given_options);
  remesh::check_options(given_options.remesh);
  remesh::check_options(given_options.features);
  remesh::check_options(given_options.smoothing);
  require_edges_of(input.mesh, given_options.features.sampling.given_edges, "feature edge");
  require_edges_of(input.mesh, given_options.features.sampling.excluded_edges, "excluded feature edge");
  // A textured input's seams welded first; the feature edges given on it move along.
  std::optional<RemeshPipelineOptions> welded_options;
  if (!given_options.given_sites) {
    if (const std::vector<Index> welded = weld_texture_seams(input); !welded.empty()) {
      welded_options = given_options;
      for (auto* edges :
           {&welded_options->features.sampling.given_edges, &welded_options->features.sampling.excluded_edges}) {
        for (std::array<Index, 2>& edge : *edges) edge = {welded[edge[0]], welded[edge[1]]};
      }
    }
  }
  const RemeshPipelineOptions& options = welded_options ? *welded_options : given_options;
  if (options.texture_size != 0) {
    remesh::check_options(remesh::AtlasOptions{.texture_size = options.texture_size});
    remesh::check_options(remesh::BakeOptions{.texture_size = options.texture_size});
  }
  RemeshPipelineResult result;
  result.input = std::move(input);
  result.input_report = analyze_mesh(result.input.mesh);
  if (options.max_error_pct > 0) {
    result = remesh_within_error(std::move(result), options);
  } else {
    remesh_once(result, options, {});
  }
  if (options.texture_size != 0) texture_stage(result, options);
  return result;
}

}  // namespace geodual::pipeline
