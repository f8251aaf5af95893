#include "geodual/remesh/lloyd.hpp"

#include "surface_walk.hpp"

#include <Eigen/Geometry>
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
  (void)mesh;
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
  // A vertex site steps from the corner of the face around it whose angle
  // holds the step's direction.
  std::vector<Index> fan_begin, fan;
  if (std::any_of(sites.begin(), sites.end(), [](const SurfacePoint& p) { return p.kind == SurfacePoint::Kind::vertex; })) {
    fan_begin.assign(static_cast<std::size_t>(mesh.vertices.rows()) + 1, 0);
    for (Index f = 0; f < mesh.faces.rows(); ++f) {
      if (diagram.field.face_edges[f][0] < 0) continue;
      for (int c = 0; c < 3; ++c) ++fan_begin[mesh.faces(f, c) + 1];
    }
    for (std::size_t v = 1; v < fan_begin.size(); ++v) fan_begin[v] += fan_begin[v - 1];
    fan.resize(static_cast<std::size_t>(fan_begin.back()));
    std::vector<Index> fill(fan_begin.begin(), fan_begin.end() - 1);
    for (Index f = 0; f < mesh.faces.rows(); ++f) {
      if (diagram.field.face_edges[f][0] < 0) continue;
      for (int c = 0; c < 3; ++c) fan[fill[mesh.faces(f, c)]++] = f;
    }
  }
  auto as_face_point = [&](const SurfacePoint& site, const Eigen::Vector3d& step) {
    if (site.kind == SurfacePoint::Kind::face || fan_begin.empty()) return site;
    const Index v = site.element;
    SurfacePoint best = site;
    for (Index i = fan_begin[v]; i < fan_begin[v + 1]; ++i) {
      const Index f = fan[i];
      int c = 0;
      while (mesh.faces(f, c) != v) ++c;
      const Eigen::Vector3d p = mesh.vertices.row(v).transpose();
      const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, (c + 1) % 3)).transpose() - p;
      const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, (c + 2) % 3)).transpose() - p;
      const Eigen::Vector3d n = a.cross(b);
      Eigen::Vector3d b3 = Eigen::Vector3d::Zero();
      b3[c] = 1;
      if (best.kind == SurfacePoint::Kind::vertex) best = SurfacePoint::in_face(f, b3[0], b3[1], b3[2]);
      if (n.dot(a.cross(step)) >= 0 && n.dot(step.cross(b)) >= 0) return SurfacePoint::in_face(f, b3[0], b3[1], b3[2]);
    }
    return best;
  };
  // Each site's step is independent of the others: bit-identical for any
  // number of threads.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, moved.size()), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const double area = diagram.cell_area[i];
      if (!(area > 0)) continue;
      const Eigen::Vector3d step = factor * diagram.cell_log_moment[i] / area;
      const SurfacePoint site = as_face_point(sites[i], step);
      if (site.kind != SurfacePoint::Kind::face) continue;
      if (!options.move_boundary_sites && on_boundary(mesh, diagram.field, site)) continue;
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
