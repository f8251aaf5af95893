#include "geodual/remesh/remesh.hpp"

#include "fault_places.hpp"
#include "geodual/mesh/detail/trim_heap.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <optional>
#include <string>
#include <utility>

namespace geodual::remesh {

namespace {

/// Where the repair points of a failed round lie (fault_places).
std::vector<Eigen::Vector3d> repair_places(const TriangleMesh& mesh, const voronoi::VoronoiDiagram& diagram,
                                           const std::vector<SurfacePoint>& points) {
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(points.size());
  for (const SurfacePoint& point : points) positions.push_back(point.position(mesh));
  return fault_places(positions, diagram.mean_spacing());
}

/// dual_with_repair on `mesh`; `surface` is its prepared surface, made on
/// the first repair round when it is empty.
RepairedDual repair_dual(const TriangleMesh& mesh, std::optional<voronoi::GeodesicSurface>& surface,
                         std::vector<SurfacePoint> sites, voronoi::VoronoiDiagram diagram,
                         const RepairOptions& options) {
  RepairedDual result;
  result.sites = std::move(sites);
  result.diagram = std::move(diagram);
  std::size_t asked_before = 0;  // sites the last round asked to add or leave out
  for (int round = 0;; ++round) {
    if (round > 0) {
      if (!surface) surface.emplace(mesh);
      result.diagram = voronoi::compute_voronoi(*surface, result.sites, options.voronoi);
      result.geodesic_seconds += result.diagram.stats.geodesic_seconds;
      result.diagram_seconds += result.diagram.stats.extraction_seconds;
    }
    const auto start = std::chrono::steady_clock::now();
    DualMesh dual = dual_delaunay(mesh, result.diagram, options.dual);
    result.dual_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.repair_rounds = round;
    if (dual.check.valid) {
      result.mesh = std::move(dual.mesh);
      result.check = std::move(dual.check);
      return result;
    }
    if (result.repair_problems.empty()) result.repair_problems = dual.check.problems;
    const std::string problems = problems_line(dual.check.problems);
    const std::size_t asked = dual.check.repair_sites.size() + dual.check.redundant_sites.size();
    const bool converging =
        options.extend_while_converging && round > 0 && round < 2 * options.max_rounds && asked < asked_before;
    if ((round >= options.max_rounds && !converging) || asked == 0) {
      std::vector<Eigen::Vector3d> places = repair_places(mesh, result.diagram, dual.check.repair_sites);
      const std::string message = "the dual of the Voronoi diagram is not a valid remesh after " +
                                  std::to_string(round) + " repair rounds (" + std::to_string(result.sites_added) +
                                  " sites added): " + problems + fault_places_text(places) + "; try more sites";
      throw DualRepairError(message, std::move(places));
    }
    asked_before = asked;
    // Sites no added site can help go (indices increasing, so from the back).
    for (auto it = dual.check.redundant_sites.rbegin(); it != dual.check.redundant_sites.rend(); ++it) {
      result.sites.erase(result.sites.begin() + *it);
    }
    result.sites_left_out += static_cast<std::int64_t>(dual.check.redundant_sites.size());
    result.sites_added += static_cast<std::int64_t>(dual.check.repair_sites.size());
    if (options.max_sites_added > 0 && result.sites_added > options.max_sites_added) {
      throw DualRepairError("the dual of the Voronoi diagram is not a valid remesh after " + std::to_string(round + 1) +
                                " repair rounds: they would add " + std::to_string(result.sites_added) +
                                " sites, more than the " + std::to_string(options.max_sites_added) + " allowed (" +
                                problems + "); try more sites",
                            repair_places(mesh, result.diagram, dual.check.repair_sites));
    }
    result.sites.insert(result.sites.end(), dual.check.repair_sites.begin(), dual.check.repair_sites.end());
  }
}

}  // namespace

RepairedDual dual_with_repair(const voronoi::GeodesicSurface& surface, std::vector<SurfacePoint> sites,
                              voronoi::VoronoiDiagram diagram, const RepairOptions& options) {
  std::optional<voronoi::GeodesicSurface> prepared(surface);  // a copy shares the prepared data
  return repair_dual(surface.mesh(), prepared, std::move(sites), std::move(diagram), options);
}

RepairedDual dual_with_repair(const TriangleMesh& surface, std::vector<SurfacePoint> sites,
                              voronoi::VoronoiDiagram diagram, const RepairOptions& options) {
  std::optional<voronoi::GeodesicSurface> prepared;
  return repair_dual(surface, prepared, std::move(sites), std::move(diagram), options);
}

LloydOptions relaxation_options(const TriangleMesh& surface, std::int64_t site_count, const RemeshOptions& options) {
  LloydOptions lloyd = options.lloyd;
  if (options.curvature_adaptation > 0 && lloyd.density.empty() && lloyd.iterations > 0 && site_count > 0) {
    lloyd.density = curvature_density(surface, {.strength = options.curvature_adaptation,
                                                .spacing = uniform_spacing(surface, site_count),
                                                .max_ratio = options.curvature_max_ratio});
  }
  return lloyd;
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
