#include "geodual/remesh/remesh.hpp"

#include "geodual/mesh/detail/trim_heap.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace geodual::remesh {

void check_options(const RemeshOptions& options) {
  check_options(options.lloyd);
  if (options.curvature) {
    CurvatureDensityOptions curvature = *options.curvature;
    if (curvature.spacing == 0) curvature.spacing = 1;  // the remesh's, known once the sites are
    check_options(curvature);
  }
  if (options.max_repair_rounds < 0) {
    throw UsageError("max repair rounds " + std::to_string(options.max_repair_rounds) + ": must be >= 0");
  }
}

void check_options(const FeatureRemeshOptions& options) {
  check_options(options.sampling);
  const auto require = [](bool holds, const std::string& what, double value, const std::string& range) {
    if (!holds) throw UsageError(what + " " + std::to_string(value) + ": must be " + range);
  };
  require(options.max_repair_rounds >= 0, "max feature repair rounds", options.max_repair_rounds, ">= 0");
  require(std::isfinite(options.max_sites_added) && options.max_sites_added >= 0, "max feature sites added",
          options.max_sites_added, "a finite fraction >= 0 of the sites");
  require(std::isfinite(options.retry_radius) && options.retry_radius >= 0, "feature retry radius",
          options.retry_radius, "a finite number >= 0 (in spacings)");
  require(options.max_site_doublings >= 0 && options.max_site_doublings <= 10, "max feature site doublings",
          options.max_site_doublings, "in [0, 10]");
}

LloydOptions relaxation_options(const TriangleMesh& surface, std::int64_t site_count, const RemeshOptions& options) {
  LloydOptions lloyd = options.lloyd;
  if (options.curvature && options.curvature->strength > 0 && lloyd.density.empty() && lloyd.iterations > 0 &&
      site_count > 0) {
    CurvatureDensityOptions curvature = *options.curvature;
    if (curvature.spacing == 0) curvature.spacing = uniform_spacing(surface, site_count);
    lloyd.density = curvature_density(surface, curvature);
  }
  return lloyd;
}

FeatureSamplingOptions feature_sampling_options(const FeatureRemeshOptions& options, const TriangleMesh& input,
                                                const ManifoldCut& cut) {
  FeatureSamplingOptions sampling = options.sampling;
  sampling.given_edges = edges_on_cut(cut, input.num_vertices(), options.sampling.given_edges);
  sampling.excluded_edges = edges_on_cut(cut, input.num_vertices(), options.sampling.excluded_edges);
  return sampling;
}

LloydOptions relaxation_options(const TriangleMesh& sites_surface, const RemeshSites& sites,
                                std::span<const double> feature_density, const RemeshOptions& options) {
  LloydOptions lloyd = relaxation_options(sites_surface, static_cast<std::int64_t>(sites.sites.size()), options);
  if (sites.pins > 0) {
    lloyd.fixed_sites.assign(sites.sites.size(), 0);
    std::fill_n(lloyd.fixed_sites.begin() + sites.first_pin, sites.pins, std::uint8_t{1});
  }
  if (!feature_density.empty() && lloyd.iterations > 0) {
    if (lloyd.density.empty()) {
      lloyd.density.assign(feature_density.begin(), feature_density.end());
    } else {
      for (std::size_t v = 0; v < lloyd.density.size(); ++v) lloyd.density[v] *= feature_density[v];
    }
  }
  return lloyd;
}

RepairOptions repair_options(const RemeshOptions& options) {
  return {.max_rounds = options.max_repair_rounds, .voronoi = options.lloyd.voronoi, .dual = {}};
}

RepairOptions repair_options(const RemeshOptions& options, const FeatureRemeshOptions& features,
                             std::int64_t site_count) {
  RepairOptions repair = repair_options(options);
  repair.dual.close_boundary_stretches = features.close_crease_stretches;
  repair.max_rounds = std::min(repair.max_rounds, features.max_repair_rounds);
  repair.extend_while_converging = false;
  if (features.max_sites_added > 0) {
    repair.max_sites_added =
        std::max<std::int64_t>(1, std::llround(features.max_sites_added * static_cast<double>(site_count)));
  }
  return repair;
}

std::vector<SurfacePoint> remesh_points_on_input(const RepairedDual& remesh, const ManifoldCut& cut,
                                                 const FeatureCut& features_cut) {
  std::vector<SurfacePoint> points(static_cast<std::size_t>(remesh.mesh.num_vertices()));
  for (std::size_t site = 0; site < remesh.sites.size(); ++site) {
    SurfacePoint point = remesh.sites[site];
    if (point.kind == SurfacePoint::Kind::vertex) {
      // A copy of a copy: feature cut -> manifold cut -> input.
      Index v = point.element;
      if (!features_cut.original_vertex.empty()) v = features_cut.original_vertex[static_cast<std::size_t>(v)];
      point.element = cut.original_vertex[static_cast<std::size_t>(v)];
    }
    const std::size_t vertex =
        remesh.vertex_of_site.empty() ? site : static_cast<std::size_t>(remesh.vertex_of_site[site]);
    points[vertex] = point;  // welded twins are copies of one point
  }
  return points;
}

RemeshResult remesh_from_sites(const TriangleMesh& mesh, std::vector<SurfacePoint> sites,
                               const RemeshOptions& options) {
  check_options(options);
  RemeshResult result;
  // The surface to remesh: cut apart at non-manifold edges and vertices.
  ManifoldCut cut = cut_to_manifold(mesh);
  result.vertices_split = cut.vertices_split;
  result.faces_disabled = cut.faces_disabled;
  const bool changed = cut.vertices_split > 0 || cut.faces_disabled > 0;
  if (changed) sites = points_on_cut(cut, std::move(sites));
  require_a_site_on_every_piece(changed ? cut.mesh : mesh, sites);
  if (!changed) cut.mesh = TriangleMesh{};  // the input itself is remeshed: no second copy held
  const bool release_memory = options.lloyd.voronoi.geodesic.release_memory_between_phases;
  if (release_memory) trim_heap();  // the cut's scratch (a sorted list of all half-edges)
  const TriangleMesh& surface = changed ? cut.mesh : mesh;
  const LloydOptions lloyd = relaxation_options(surface, static_cast<std::int64_t>(sites.size()), options);
  // Prepared once for every diagram of both stages.
  const voronoi::GeodesicSurface geodesic_surface(surface);
  if (release_memory) trim_heap();  // the preparation's scratch
  result.relaxation = lloyd_relax(geodesic_surface, std::move(sites), lloyd);
  // The relaxed diagram moves on to the dual (its first round's diagram).
  result.dual = dual_with_repair(geodesic_surface, result.relaxation.sites, std::move(result.relaxation.diagram),
                                 repair_options(options));
  return result;
}

}  // namespace geodual::remesh
