#include "geodual/remesh/lloyd.hpp"

#include "common/point_grid.hpp"
#include "common/surface_walk.hpp"
#include "geodual/mesh/detail/trim_heap.hpp"
#include "geodual/mesh/error.hpp"
#include "relax/cvt_newton.hpp"
#include "relax/restricted_voronoi.hpp"
#include "relax/weighted_cells.hpp"

#include <Eigen/Geometry>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <utility>

namespace geodual::remesh {
namespace {

/// Per site, whether a step may move it: it is not on the boundary unless
/// boundary sites move. (A site whose cell is empty stays too: the steps
/// check that.)
std::vector<bool> movable_sites(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                const voronoi::SurfaceTopology& topology, const LloydOptions& options) {
  std::vector<bool> movable(sites.size(), true);
  for (std::size_t i = 0; i < movable.size() && i < options.fixed_sites.size(); ++i)
    movable[i] = !options.fixed_sites[i];
  if (options.move_boundary_sites) return movable;
  std::vector<bool> boundary_vertex;
  if (detail::any_at_vertex(sites)) {
    boundary_vertex.assign(static_cast<std::size_t>(mesh.vertices.rows()), false);
    for (std::size_t e = 0; e < topology.edge_faces.size(); ++e) {
      if (topology.edge_faces[e][0] >= 0 && topology.edge_faces[e][1] >= 0) continue;
      for (const Index v : topology.edge_vertices(mesh, static_cast<Index>(e))) boundary_vertex[v] = true;
    }
  }
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const SurfacePoint& site = sites[i];
    movable[i] = movable[i] && !(site.kind == SurfacePoint::Kind::vertex ? bool(boundary_vertex[site.element])
                                                                         : detail::on_surface_boundary(topology, site));
  }
  return movable;
}

/// Frees a field's windows and per-vertex results: of a relaxation's fields,
/// only the last one is needed (for the dual), and a held diagram's field is
/// computed again where the relaxation ends on it. The topology stays (the
/// steps read it). A field keeps one window_begin entry per edge and one
/// more, so an empty window_begin marks the field as released.
void release_field(voronoi::GeodesicField& field) {
  std::vector<voronoi::EdgeWindow>().swap(field.windows);
  std::vector<Index>().swap(field.window_begin);
  std::vector<double>().swap(field.distance);
  std::vector<Index>().swap(field.nearest_site);
  std::vector<bool>().swap(field.valid_face);
  std::vector<voronoi::FacePointSource>().swap(field.face_point_sources);
}

bool field_released(const voronoi::GeodesicField& field) { return field.window_begin.empty(); }

/// `moved` with the sites that stay (not `moving`) where `slid` has them
/// (options.slide_boundary_sites' result; empty: none slide).
void take_slid_sites(std::span<const SurfacePoint> slid, const std::vector<bool>& moving,
                     std::vector<SurfacePoint>& moved) {
  for (std::size_t i = 0; i < moved.size() && i < slid.size(); ++i) {
    if (!moving[i]) moved[i] = slid[i];
  }
}

/// What moving each movable site to its cell's centroid lowers the energy
/// by, the cells kept: sum of |M_i|^2 / m_i (the cell's moment and mass).
/// Recomputing the cells lowers it further: after a warm start an exact
/// iteration brought 1.5 to 3 times this on the benchmark scans.
double centroid_gain(const detail::WeightedCells& cells, const std::vector<bool>& movable) {
  double gain = 0;
  for (std::size_t i = 0; i < movable.size(); ++i) {
    if (movable[i] && cells.mass[i] > 0) gain += cells.moment[i].squaredNorm() / cells.mass[i];
  }
  return gain;
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

/// The Newton step on the geodesic diagram's cells (cvt_newton.hpp); each
/// arc's density is the mean of its two sites'.
std::vector<Eigen::Vector3d> newton_steps(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                          const voronoi::VoronoiDiagram& diagram, const detail::WeightedCells& cells,
                                          const std::vector<bool>& movable, double damping, double max_step,
                                          detail::CvtNewtonBuffers& buffers) {
  const std::vector<Eigen::Matrix<double, 3, 2>> frames = detail::tangent_frames(mesh, sites, *diagram.field.topology);
  std::vector<Eigen::Vector3d> position(sites.size());
  for (std::size_t s = 0; s < sites.size(); ++s) position[s] = sites[s].position(mesh);
  std::vector<detail::CvtBoundary> boundaries;
  boundaries.reserve(diagram.arcs.size());
  for (const voronoi::VoronoiArc& arc : diagram.arcs) {
    const Index i = arc.left_site, j = arc.right_site;
    if (i < 0 || j < 0) continue;
    boundaries.push_back({i, j, (cells.site_density[i] + cells.site_density[j]) / 2, diagram.polyline(arc)});
  }
  return detail::cvt_newton_steps({position, frames, diagram.cell_area, cells.mass, cells.moment}, boundaries, movable,
                                  damping, max_step, buffers);
}

/// The Newton step on the restricted Voronoi diagram's cells.
std::vector<Eigen::Vector3d> newton_steps(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                          const voronoi::SurfaceTopology& topology,
                                          const detail::RestrictedCells& cells, const std::vector<bool>& movable,
                                          double damping, double max_step, detail::CvtNewtonBuffers& buffers) {
  const std::vector<Eigen::Matrix<double, 3, 2>> frames = detail::tangent_frames(mesh, sites, topology);
  // Per site and per boundary, each on its own: on all threads.
  std::vector<Eigen::Vector3d> position(sites.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sites.size(), 512),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t s = range.begin(); s != range.end(); ++s) position[s] = sites[s].position(mesh);
                    });
  std::vector<detail::CvtBoundary> boundaries(cells.boundaries.size());
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, boundaries.size(), 1024), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t b = range.begin(); b != range.end(); ++b) {
          const detail::RestrictedBoundary& boundary = cells.boundaries[b];
          const std::span<const Eigen::Vector3d> ends(cells.segment_ends.data() + boundary.begin,
                                                      static_cast<std::size_t>(boundary.end - boundary.begin));
          boundaries[b] = {boundary.site, boundary.other, boundary.density, ends, true};
        }
      });
  return detail::cvt_newton_steps({position, frames, cells.area, cells.mass, cells.moment}, boundaries, movable,
                                  damping, max_step, buffers);
}

/// Lloyd's steps on the restricted diagram: `factor` times the way to each
/// cell's centroid, taken into the site's tangent plane.
std::vector<Eigen::Vector3d> lloyd_steps(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                         const voronoi::SurfaceTopology& topology, const detail::RestrictedCells& cells,
                                         const std::vector<bool>& movable, double factor) {
  const std::vector<Eigen::Matrix<double, 3, 2>> frames = detail::tangent_frames(mesh, sites, topology);
  std::vector<Eigen::Vector3d> steps(movable.size(), Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (movable[i] && cells.mass[i] > 0) {
      steps[i] = factor * frames[i] * (frames[i].transpose() * cells.moment[i]) / cells.mass[i];
    }
  }
  return steps;
}

/// Where a relaxation stands between its steps: the damping of its Newton
/// steps and the over-relaxation of its Lloyd steps, both adapted as it goes.
struct StepControl {
  double damping = 0;
  double factor = 1;
};

/// Lloyd–Newton starts from the least damping; plain Lloyd steps start
/// over-relaxed. The Lloyd step that stands in for two rejected Newton steps
/// is the plain one: it comes when even a damped Newton step does not lower
/// the energy, mostly once the gains are down to what the energy's
/// quadrature resolves, where an over-relaxed step has never been seen to
/// succeed (bunny, igea, armadillo, fertility at 5K and 20K) and only cost
/// a diagram more.
StepControl initial_control(const LloydOptions& options) {
  return {options.newton_damping, options.newton ? 1.0 : options.over_relaxation};
}

/// One step of the relaxation from a state of energy `energy`:
/// Levenberg–Marquardt on the damping — a Newton step that lowers the energy
/// lets the next be less damped (down to newton_damping); one that does not
/// is retried once, more damped, before Lloyd's step is taken instead. A
/// Newton step must lower the energy by the tolerance at least: one that
/// lowers it by less has fallen short of its model (overshooting along some
/// sites, short along others) rather than shown convergence, which Lloyd's
/// step then decides. Without Newton steps Lloyd's are over-relaxed (factor
/// > 1) until one fails, and plain from there on.
/// `newton(damping)` and `lloyd(factor)` give the steps; `take(steps,
/// least_decrease)` keeps them when the energy falls by more than
/// least_decrease. Returns whether a step was taken.
template <class Newton, class Lloyd, class Take>
bool relaxation_step(const LloydOptions& options, double energy, StepControl& control, Newton newton, Lloyd lloyd,
                     Take take) {
  bool taken = false;
  if (options.newton) {
    for (int attempt = 0; attempt < 2 && !taken; ++attempt) {
      taken = take(newton(control.damping), options.tolerance * energy);
      control.damping = taken ? std::max(control.damping / 4, options.newton_damping) : control.damping * 4;
    }
  }
  if (!taken && control.factor > 1) {
    taken = take(lloyd(control.factor), 0.0);
    if (!taken) control.factor = 1;  // over-relaxed too far: the plain Lloyd step from here on
  }
  if (!taken) taken = take(lloyd(control.factor), 0.0);
  return taken;
}

/// Where only a few of the sites move (at most a quarter), the cells the
/// warm start's steps can change: per site, 1 for the moving sites and for
/// those within twice the longest distance between a moving site and a
/// neighbour of its cell in `cells` (a step keeps a site inside its cell, and
/// the fixed sites round the moving ones keep those together); empty where
/// more move, for every cell.
std::vector<std::uint8_t> cells_the_steps_change(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                                 const std::vector<bool>& movable,
                                                 const detail::RestrictedCells& cells) {
  const auto moving = static_cast<std::size_t>(std::count(movable.begin(), movable.end(), true));
  if (moving == 0 || 4 * moving > sites.size()) return {};
  std::vector<Eigen::Vector3d> position(sites.size());
  for (std::size_t s = 0; s < sites.size(); ++s) position[s] = sites[s].position(mesh);
  double farthest = 0;
  for (const detail::RestrictedBoundary& boundary : cells.boundaries) {
    if (movable[boundary.site] || movable[boundary.other]) {
      farthest = std::max(farthest, (position[boundary.site] - position[boundary.other]).norm());
    }
  }
  std::vector<std::uint8_t> changed(sites.size(), 0);
  for (std::size_t s = 0; s < sites.size(); ++s) changed[s] = movable[s] ? 1 : 0;
  if (!(farthest > 0)) return changed;
  const detail::PointGrid grid(position, 2 * farthest);
  for (Index slot = 0; slot < grid.size(); ++slot) {
    if (!movable[grid.original(slot)]) continue;
    grid.for_each_near(slot, [&](Index other, double) { changed[grid.original(other)] = 1; });
  }
  return changed;
}

/// The warm start: the relaxation's steps on the restricted Voronoi diagram
/// (restricted_voronoi.hpp) for at most options.warm_start_iterations steps,
/// stopping early by the same rules. Returns the sites reached and counts
/// the steps taken. Where few sites move, only the cells their steps can
/// change are integrated, and the energies compared are those cells'.
std::vector<SurfacePoint> warm_start(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology,
                                     std::vector<SurfacePoint> sites, const std::vector<bool>& movable,
                                     const LloydOptions& options, int& steps_taken) {
  // The fans round the vertices are kept for sites at vertices only: the
  // walks move sites to face points, so only those that stay can be there.
  const detail::RestrictedSurface surface =
      detail::prepare_restricted_surface(mesh, topology, options.density, detail::any_at_vertex(sites));
  detail::RestrictedCells cells = detail::restricted_voronoi(surface, sites);
  const std::vector<std::uint8_t> changed = cells_the_steps_change(mesh, sites, movable, cells);
  if (!changed.empty()) cells = detail::restricted_voronoi(surface, sites, changed);
  detail::CvtNewtonBuffers buffers;
  StepControl control = initial_control(options);
  // The step last taken: the momentum's memory.
  std::vector<Eigen::Vector3d> taken_step;
  for (steps_taken = 0; steps_taken < options.warm_start_iterations;) {
    const double previous = cells.total_energy();
    // A site whose restricted cell is empty (it shares its place) stays.
    std::vector<bool> moving = movable;
    for (std::size_t i = 0; i < moving.size(); ++i) moving[i] = moving[i] && cells.mass[i] > 0;
    auto take = [&](std::vector<Eigen::Vector3d> steps, double least_decrease) {
      std::vector<SurfacePoint> moved = detail::move_sites(mesh, topology, sites, steps);
      detail::RestrictedCells next = detail::restricted_voronoi(surface, moved, changed);
      if (!(next.total_energy() < previous - least_decrease)) return false;
      sites = std::move(moved);
      cells = std::move(next);
      taken_step = std::move(steps);
      return true;
    };
    auto newton = [&](double damping) {
      std::vector<Eigen::Vector3d> steps =
          newton_steps(mesh, sites, topology, cells, moving, damping, options.newton_max_step, buffers);
      // Only on the least damped step: a step retried more damped has
      // overshot, and goes without the momentum.
      if (damping == options.newton_damping && !taken_step.empty()) {
        for (std::size_t i = 0; i < steps.size(); ++i) {
          if (moving[i]) steps[i] += options.warm_start_momentum * taken_step[i];
        }
      }
      return steps;
    };
    auto lloyd = [&](double factor) { return lloyd_steps(mesh, sites, topology, cells, moving, factor); };
    if (!relaxation_step(options, previous, control, newton, lloyd, take)) break;
    ++steps_taken;
    // No geodesics run here, so the progress callback that can cancel them
    // is asked between the steps (with a fraction of 0: no diagram is under way).
    const auto& progress = options.voronoi.geodesic.progress;
    if (progress && !progress(0.0)) throw Cancelled("Lloyd's warm start cancelled");
    if (previous - cells.total_energy() < options.tolerance * previous) break;
  }
  return sites;
}

}  // namespace

void check_options(const LloydOptions& options) {
  auto require = [](bool holds, const std::string& what) {
    if (!holds) throw UsageError("lloyd_relax: " + what);
  };
  require(options.iterations >= 0, "iterations must be >= 0, got " + std::to_string(options.iterations));
  require(options.warm_start_iterations >= 0,
          "warm_start_iterations must be >= 0, got " + std::to_string(options.warm_start_iterations));
  require(options.tolerance >= 0, "tolerance must be >= 0, got " + std::to_string(options.tolerance));
  require(options.geodesic_tolerance >= 0,
          "geodesic_tolerance must be >= 0, got " + std::to_string(options.geodesic_tolerance));
  require(options.over_relaxation > 0 && options.over_relaxation < 2,
          "over_relaxation must be in (0, 2), got " + std::to_string(options.over_relaxation));
  require(options.warm_start_momentum >= 0 && options.warm_start_momentum < 1,
          "warm_start_momentum must be in [0, 1), got " + std::to_string(options.warm_start_momentum));
  require(options.newton_damping > 0 && std::isfinite(options.newton_damping),
          "newton_damping must be a finite number > 0, got " + std::to_string(options.newton_damping));
  require(options.newton_max_step > 0 && std::isfinite(options.newton_max_step),
          "newton_max_step must be a finite number > 0, got " + std::to_string(options.newton_max_step));
  for (std::size_t v = 0; v < options.density.size(); ++v) {
    require(options.density[v] > 0 && std::isfinite(options.density[v]), "density must be finite and > 0, got " +
                                                                             std::to_string(options.density[v]) +
                                                                             " at vertex " + std::to_string(v));
  }
}

LloydResult lloyd_relax(const TriangleMesh& mesh, std::vector<SurfacePoint> sites, const LloydOptions& options) {
  check_options(options);
  const voronoi::GeodesicSurface surface(mesh);
  if (options.voronoi.geodesic.release_memory_between_phases) trim_heap();  // the preparation's scratch
  return lloyd_relax(surface, std::move(sites), options);
}

LloydResult lloyd_relax(const voronoi::GeodesicSurface& surface, std::vector<SurfacePoint> sites,
                        const LloydOptions& options) {
  check_options(options);
  const TriangleMesh& mesh = surface.mesh();
  if (!options.density.empty() && options.density.size() != static_cast<std::size_t>(mesh.num_vertices())) {
    throw UsageError("lloyd_relax: density has " + std::to_string(options.density.size()) + " values for a mesh of " +
                     std::to_string(mesh.num_vertices()) + " vertices");
  }
  LloydResult result;
  auto diagram_of = [&](const std::vector<SurfacePoint>& points) {
    voronoi::VoronoiDiagram diagram = voronoi::compute_voronoi(surface, points, options.voronoi);
    result.geodesic_seconds += diagram.stats.geodesic_seconds;
    result.diagram_seconds += diagram.stats.extraction_seconds;
    ++result.diagrams;
    return diagram;
  };
  auto cells_of = [&](const std::vector<SurfacePoint>& points, const voronoi::VoronoiDiagram& diagram) {
    return detail::weighted_cells(mesh, points, diagram, options.density);
  };
  const voronoi::SurfaceTopology& topology = *surface.topology();
  result.sites = std::move(sites);
  // The warm start needs no geodesics: the first diagram is that of the
  // sites it reaches (issue #17: no diagram just to judge it).
  if ((options.iterations > 0 || options.warm_start_alone) && options.warm_start_iterations > 0) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<bool> movable = movable_sites(mesh, result.sites, topology, options);
    result.sites = warm_start(mesh, topology, std::move(result.sites), movable, options, result.warm_start_iterations);
    result.warm_start_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  result.diagram = diagram_of(result.sites);
  detail::WeightedCells cells = cells_of(result.sites, result.diagram);
  result.energy.push_back(cells.total_energy());
  auto tell = [&](bool finished) {
    if (options.on_iteration) options.on_iteration(result.iterations, finished);
  };
  tell(false);

  StepControl control = initial_control(options);
  detail::CvtNewtonBuffers buffers;
  const double stop_fraction = std::max(options.tolerance, options.geodesic_tolerance);
  // A trial step's diagram is computed while the current one is held, whose
  // field (windows, distances) goes first (the peak memory is then about one
  // diagram's). If the relaxation ends on a rejected step it is computed
  // again, the same.
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    const double previous = result.energy.back();
    // Judged again each iteration: a walk may have ended on the boundary.
    std::vector<bool> movable = movable_sites(mesh, result.sites, topology, options);
    for (std::size_t i = 0; i < movable.size(); ++i) movable[i] = movable[i] && result.diagram.cell_area[i] > 0;
    // After a warm start, no iteration (and no diagram for it) where its
    // first-order gain is below the fraction that would stop the iterations
    // after it: the warm start took the sites about as close to the geodesic
    // centroids as the iterations would. Not where sites slide along their
    // chains, which only the iterations do.
    if (iteration == 0 && result.warm_start_iterations > 0 && options.geodesic_tolerance > 0 &&
        !options.slide_boundary_sites && centroid_gain(cells, movable) < options.geodesic_tolerance * previous) {
      break;
    }
    // The slide of the sites that stay, the same for every step tried this iteration.
    const std::vector<SurfacePoint> slid = options.slide_boundary_sites
                                               ? options.slide_boundary_sites(result.sites, cells.mass, cells.moment)
                                               : std::vector<SurfacePoint>{};
    auto take = [&](const std::vector<Eigen::Vector3d>& steps, double least_decrease) {
      const auto start = std::chrono::steady_clock::now();
      std::vector<SurfacePoint> moved = detail::move_sites(mesh, topology, result.sites, steps);
      take_slid_sites(slid, movable, moved);
      result.move_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      release_field(result.diagram.field);
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
    auto newton = [&](double damping) {
      const auto start = std::chrono::steady_clock::now();
      std::vector<Eigen::Vector3d> steps =
          newton_steps(mesh, result.sites, result.diagram, cells, movable, damping, options.newton_max_step, buffers);
      result.move_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return steps;
    };
    auto lloyd = [&](double factor) { return lloyd_steps(cells, movable, factor); };
    // Not even Lloyd's step lowers the energy: stop here.
    if (!relaxation_step(options, previous, control, newton, lloyd, take)) break;
    ++result.iterations;
    if (previous - result.energy.back() < stop_fraction * previous) break;
    tell(false);
  }
  if (field_released(result.diagram.field)) {
    voronoi::GeodesicField field = voronoi::compute_geodesic_field(surface, result.sites, options.voronoi.geodesic);
    result.geodesic_seconds += field.stats.total_seconds;
    result.diagram.field = std::move(field);
  }
  tell(true);
  return result;
}

}  // namespace geodual::remesh
