#include "geodual/remesh/lloyd.hpp"

#include "surface_walk.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <numeric>
#include <tuple>
#include <utility>

namespace geodual::remesh {
namespace {

double total_energy(const voronoi::VoronoiDiagram& diagram) {
  return std::accumulate(diagram.cell_energy.begin(), diagram.cell_energy.end(), 0.0);
}

/// True for a site on a boundary edge of the propagation surface.
bool on_boundary(const TriangleMesh& mesh, const voronoi::GeodesicField& field, const SurfacePoint& site) {
  if (site.kind == SurfacePoint::Kind::vertex) {
    (void)mesh;
    return false;  // vertex sites: only added by repair, never by sampling; they move like any other
  }
  for (int c = 0; c < 3; ++c) {
    if (site.barycentric[c] != 0) continue;
    const Index edge = field.face_edges[site.element][(c + 1) % 3];  // the side opposite corner c
    if (edge >= 0 && (field.edge_faces[edge][0] < 0 || field.edge_faces[edge][1] < 0)) return true;
  }
  return false;
}

/// Every movable site stepped `factor` times its mean log map along the
/// surface; a pair landing on one point keeps its old places.
std::vector<SurfacePoint> step_sites(const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites,
                                     const voronoi::VoronoiDiagram& diagram, double factor,
                                     const LloydOptions& options) {
  std::vector<SurfacePoint> moved = sites;
  // Each site's step is independent of the others: bit-identical for any
  // number of threads.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, moved.size()), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const double area = diagram.cell_area[i];
      if (!(area > 0)) continue;
      const SurfacePoint& site = sites[i];
      if (site.kind != SurfacePoint::Kind::face) continue;
      if (!options.move_boundary_sites && on_boundary(mesh, diagram.field, site)) continue;
      const Eigen::Vector3d step = factor * diagram.cell_log_moment[i] / area;
      const double length = step.norm();
      if (!(length > 0)) continue;
      moved[i] = detail::walk_on_surface(mesh, diagram.field, site, step, length);
    }
  });
  std::vector<std::size_t> order(moved.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<Eigen::Vector3d> position(moved.size());
  for (std::size_t i = 0; i < moved.size(); ++i) position[i] = moved[i].position(mesh);
  auto key = [&](std::size_t i) { return std::tuple(position[i].x(), position[i].y(), position[i].z()); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (key(order[k]) == key(order[k - 1])) {
      moved[order[k]] = sites[order[k]];
      moved[order[k - 1]] = sites[order[k - 1]];
    }
  }
  return moved;
}

}  // namespace

LloydResult lloyd_relax(const TriangleMesh& mesh, std::vector<SurfacePoint> sites, const LloydOptions& options) {
  LloydResult result;
  auto diagram_of = [&](const std::vector<SurfacePoint>& points) {
    voronoi::VoronoiDiagram diagram = voronoi::compute_voronoi(mesh, points, options.voronoi);
    result.geodesic_seconds += diagram.stats.geodesic_seconds;
    result.diagram_seconds += diagram.stats.extraction_seconds;
    return diagram;
  };
  result.sites = std::move(sites);
  result.diagram = diagram_of(result.sites);
  result.energy.push_back(total_energy(result.diagram));

  double factor = options.over_relaxation;
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<SurfacePoint> moved = step_sites(mesh, result.sites, result.diagram, factor, options);
    result.move_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    voronoi::VoronoiDiagram next = diagram_of(moved);
    double energy = total_energy(next);
    const double previous = result.energy.back();
    if (!(energy <= previous) && factor > 1) {
      // Over-relaxed too far: the plain Lloyd step (which lowers the energy
      // of an exact CVT iteration) from here on.
      factor = 1;
      const auto again = std::chrono::steady_clock::now();
      moved = step_sites(mesh, result.sites, result.diagram, factor, options);
      result.move_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - again).count();
      next = diagram_of(moved);
      energy = total_energy(next);
    }
    if (!(energy <= previous)) break;  // the step would not lower the energy: stop here
    result.sites = std::move(moved);
    result.diagram = std::move(next);
    result.energy.push_back(energy);
    ++result.iterations;
    if (previous - energy < options.tolerance * previous) break;
  }
  return result;
}

}  // namespace geodual::remesh
