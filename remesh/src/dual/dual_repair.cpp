#include "geodual/remesh/dual_repair.hpp"

#include "dual/fault_places.hpp"

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

}  // namespace geodual::remesh
