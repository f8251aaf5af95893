#include "geodual/remesh/remesh.hpp"

#include "geodual/error.hpp"

#include <chrono>
#include <string>
#include <utility>

namespace geodual::remesh {

RemeshResult remesh_from_sites(const TriangleMesh& input, std::vector<SurfacePoint> sites,
                               const RemeshOptions& options) {
  RemeshResult result;
  LloydResult relaxed = lloyd_relax(input, std::move(sites), options.lloyd);
  result.lloyd_seconds = relaxed.move_seconds;
  result.geodesic_seconds = relaxed.geodesic_seconds;
  result.diagram_seconds = relaxed.diagram_seconds;
  result.sites = std::move(relaxed.sites);
  result.energy = std::move(relaxed.energy);
  result.lloyd_iterations = relaxed.iterations;
  result.diagram = std::move(relaxed.diagram);
  for (int round = 0;; ++round) {
    if (round > 0) {
      result.diagram = voronoi::compute_voronoi(input, result.sites, options.lloyd.voronoi);
      result.geodesic_seconds += result.diagram.stats.geodesic_seconds;
      result.diagram_seconds += result.diagram.stats.extraction_seconds;
    }
    const auto start = std::chrono::steady_clock::now();
    DualMesh dual = dual_delaunay(input, result.diagram);
    result.dual_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.repair_rounds = round;
    if (dual.check.valid) {
      result.mesh = std::move(dual.mesh);
      result.check = std::move(dual.check);
      return result;
    }
    std::string problems;
    for (const std::string& problem : dual.check.problems) problems += (problems.empty() ? "" : "; ") + problem;
    if (round >= options.max_repair_rounds || dual.check.repair_sites.empty()) {
      throw Error("the dual of the Voronoi diagram is not a valid remesh after " + std::to_string(round) +
                  " repair rounds (" + std::to_string(result.sites_added) + " sites added): " + problems +
                  "; try more sites");
    }
    result.sites_added += static_cast<std::int64_t>(dual.check.repair_sites.size());
    result.sites.insert(result.sites.end(), dual.check.repair_sites.begin(), dual.check.repair_sites.end());
  }
}

}  // namespace geodual::remesh
