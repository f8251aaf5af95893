#include "geodual/remesh/lloyd.hpp"

#include "cvt_newton.hpp"
#include "geodual/error.hpp"
#include "surface_walk.hpp"
#include "weighted_cells.hpp"

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <numeric>
#include <tuple>
#include <utility>

namespace geodual::remesh {
namespace {

/// True for a face point on a boundary edge of the propagation surface.
bool on_boundary(const voronoi::GeodesicField& field, const SurfacePoint& point) {
  for (int c = 0; c < 3; ++c) {
    if (point.barycentric[c] != 0) continue;
    const Index edge = field.face_edges[point.element][(c + 1) % 3];  // the side opposite corner c
    if (edge >= 0 && (field.edge_faces[edge][0] < 0 || field.edge_faces[edge][1] < 0)) return true;
  }
  return false;
}

/// Per site, whether a step may move it: its cell has area, and it is not on
/// the boundary unless boundary sites move.
std::vector<bool> movable_sites(const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites,
                                const voronoi::VoronoiDiagram& diagram, const LloydOptions& options) {
  const voronoi::GeodesicField& field = diagram.field;
  std::vector<bool> boundary_vertex;
  const bool vertex_sites =
      std::any_of(sites.begin(), sites.end(), [](const SurfacePoint& p) { return p.kind == SurfacePoint::Kind::vertex; });
  if (vertex_sites && !options.move_boundary_sites) {
    boundary_vertex.assign(static_cast<std::size_t>(mesh.vertices.rows()), false);
    for (std::size_t e = 0; e < field.edge_faces.size(); ++e) {
      if (field.edge_faces[e][0] >= 0 && field.edge_faces[e][1] >= 0) continue;
      for (const Index v : field.edge_vertices[e]) boundary_vertex[v] = true;
    }
  }
  std::vector<bool> movable(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const SurfacePoint& site = sites[i];
    const bool boundary = !options.move_boundary_sites && (site.kind == SurfacePoint::Kind::vertex
                                                                ? bool(boundary_vertex[site.element])
                                                                : on_boundary(field, site));
    movable[i] = diagram.cell_area[i] > 0 && !boundary;
  }
  return movable;
}

/// Lloyd's steps, `factor` times each cell's (density-weighted) mean log map.
std::vector<Eigen::Vector3d> lloyd_steps(const detail::WeightedCells& cells, const std::vector<bool>& movable,
                                         double factor) {
  std::vector<Eigen::Vector3d> steps(movable.size(), Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (movable[i] && cells.mass[i] > 0) steps[i] = factor * cells.moment[i] / cells.mass[i];
  }
  return steps;
}

/// Every site walked along the surface by its step (a tangent vector at the
/// site); a pair landing on one point keeps its old places.
std::vector<SurfacePoint> move_sites(const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites,
                                     const voronoi::VoronoiDiagram& diagram, const std::vector<Eigen::Vector3d>& steps) {
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
      const Eigen::Vector3d& step = steps[i];
      const double length = step.norm();
      if (!(length > 0)) continue;
      const SurfacePoint site = as_face_point(sites[i], step);
      if (site.kind != SurfacePoint::Kind::face) continue;
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

/// geodual::UsageError naming the first option out of range.
void check_options(const LloydOptions& options) {
  auto require = [](bool holds, const std::string& what) {
    if (!holds) throw UsageError("lloyd_relax: " + what);
  };
  require(options.iterations >= 0, "iterations must be >= 0, got " + std::to_string(options.iterations));
  require(options.tolerance >= 0, "tolerance must be >= 0, got " + std::to_string(options.tolerance));
  require(options.over_relaxation > 0 && options.over_relaxation < 2,
          "over_relaxation must be in (0, 2), got " + std::to_string(options.over_relaxation));
  require(options.newton_damping > 0 && std::isfinite(options.newton_damping),
          "newton_damping must be a finite number > 0, got " + std::to_string(options.newton_damping));
  require(options.newton_max_step > 0 && std::isfinite(options.newton_max_step),
          "newton_max_step must be a finite number > 0, got " + std::to_string(options.newton_max_step));
  for (std::size_t v = 0; v < options.density.size(); ++v) {
    require(options.density[v] > 0 && std::isfinite(options.density[v]),
            "density must be finite and > 0, got " + std::to_string(options.density[v]) + " at vertex " +
                std::to_string(v));
  }
}

}  // namespace

LloydResult lloyd_relax(const TriangleMesh& mesh, std::vector<SurfacePoint> sites, const LloydOptions& options) {
  check_options(options);
  if (!options.density.empty() && options.density.size() != static_cast<std::size_t>(mesh.num_vertices())) {
    throw UsageError("lloyd_relax: density has " + std::to_string(options.density.size()) +
                     " values for a mesh of " + std::to_string(mesh.num_vertices()) + " vertices");
  }
  LloydResult result;
  auto diagram_of = [&](const std::vector<SurfacePoint>& points) {
    voronoi::VoronoiDiagram diagram = voronoi::compute_voronoi(mesh, points, options.voronoi);
    result.geodesic_seconds += diagram.stats.geodesic_seconds;
    result.diagram_seconds += diagram.stats.extraction_seconds;
    ++result.diagrams;
    return diagram;
  };
  auto cells_of = [&](const std::vector<SurfacePoint>& points, const voronoi::VoronoiDiagram& diagram) {
    return detail::weighted_cells(mesh, points, diagram, options.density);
  };
  result.sites = std::move(sites);
  result.diagram = diagram_of(result.sites);
  detail::WeightedCells cells = cells_of(result.sites, result.diagram);
  result.energy.push_back(cells.total_energy());
  auto tell = [&](bool finished) {
    if (options.on_iteration) options.on_iteration(result.iterations, finished);
  };
  tell(false);

  double factor = options.over_relaxation;
  double damping = options.newton_damping;
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    const double previous = result.energy.back();
    const std::vector<bool> movable = movable_sites(mesh, result.sites, result.diagram, options);
    // Tries a step; keeps it when it lowers the energy.
    auto try_step = [&](const std::vector<Eigen::Vector3d>& steps, double least_decrease) {
      const auto start = std::chrono::steady_clock::now();
      std::vector<SurfacePoint> moved = move_sites(mesh, result.sites, result.diagram, steps);
      result.move_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      voronoi::VoronoiDiagram next = diagram_of(moved);
      detail::WeightedCells next_cells = cells_of(moved, next);
      const double energy = next_cells.total_energy();
      if (!(energy < previous - least_decrease)) return false;
      result.sites = std::move(moved);
      result.diagram = std::move(next);
      cells = std::move(next_cells);
      result.energy.push_back(energy);
      return true;
    };
    bool accepted = false;
    if (options.newton) {
      // Levenberg–Marquardt on the damping: a Newton step that lowers the
      // energy lets the next be less damped (down to newton_damping); one
      // that does not is retried once, more damped, before Lloyd's step is
      // taken instead. A Newton step must lower the energy by the tolerance
      // at least: one that lowers it by less has fallen short of its model
      // (overshooting along some sites, short along others) rather than
      // shown convergence, which Lloyd's step then decides.
      for (int attempt = 0; attempt < 2 && !accepted; ++attempt) {
        const auto start = std::chrono::steady_clock::now();
        const std::vector<Eigen::Vector3d> steps = detail::cvt_newton_steps(
            mesh, result.sites, result.diagram, cells, movable, damping, options.newton_max_step);
        result.move_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        accepted = try_step(steps, options.tolerance * previous);
        damping = accepted ? std::max(damping / 4, options.newton_damping) : damping * 4;
      }
    }
    if (!accepted && factor > 1) {
      accepted = try_step(lloyd_steps(cells, movable, factor), 0);
      // Over-relaxed too far: the plain Lloyd step from here on.
      if (!accepted) factor = 1;
    }
    if (!accepted) accepted = try_step(lloyd_steps(cells, movable, factor), 0);
    if (!accepted) break;  // not even Lloyd's step lowers the energy: stop here
    ++result.iterations;
    if (previous - result.energy.back() < options.tolerance * previous) break;
    tell(false);
  }
  tell(true);
  return result;
}

}  // namespace geodual::remesh
