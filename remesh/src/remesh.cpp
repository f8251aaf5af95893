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

LloydOptions relaxation_options(const TriangleMesh& surface, std::int64_t site_count, const RemeshOptions& options) {
  LloydOptions lloyd = options.lloyd;
  if (options.curvature_adaptation > 0 && lloyd.density.empty() && lloyd.iterations > 0 && site_count > 0) {
    lloyd.density = curvature_density(surface, {.strength = options.curvature_adaptation,
                                                .spacing = uniform_spacing(surface, site_count),
                                                .max_ratio = options.curvature_max_ratio});
  }
  return lloyd;
}

FeatureSamplingOptions feature_sampling_options(const RemeshOptions& options, const TriangleMesh& input,
                                                const ManifoldCut& cut) {
  return {.sharp_angle = options.sharp_angle,
          .min_feature_length = options.min_feature_length,
          .continuation_angle = options.continuation_angle,
          .given_edges = edges_on_cut(cut, input.num_vertices(), options.feature_edges)};
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

RepairOptions repair_options(const RemeshOptions& options, bool keeps_features, std::int64_t site_count) {
  RepairOptions repair{.max_rounds = options.max_repair_rounds, .voronoi = options.lloyd.voronoi, .dual = {}};
  if (!keeps_features) return repair;
  repair.dual.close_boundary_stretches = options.close_crease_stretches;
  repair.max_rounds = std::min(repair.max_rounds, options.max_feature_repair_rounds);
  repair.extend_while_converging = false;
  if (options.max_feature_sites_added > 0) {
    repair.max_sites_added =
        std::max<std::int64_t>(1, std::llround(options.max_feature_sites_added * static_cast<double>(site_count)));
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
  result.dual =
      dual_with_repair(geodesic_surface, result.relaxation.sites, std::move(result.relaxation.diagram),
                       {.max_rounds = options.max_repair_rounds, .voronoi = options.lloyd.voronoi, .dual = {}});
  return result;
}

}  // namespace geodual::remesh
