#include "geodual/remesh/error_density.hpp"

#include "common/point_grid.hpp"
#include "common/vertex_fields.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>

namespace geodual::remesh {
namespace {

void require_per_vertex(const TriangleMesh& mesh, std::span<const double> field, const char* name, bool may_be_empty) {
  if (may_be_empty && field.empty()) return;
  if (field.size() != static_cast<std::size_t>(mesh.num_vertices())) {
    throw UsageError(std::string("error density: ") + name + " has " + std::to_string(field.size()) +
                     " values for a mesh of " + std::to_string(mesh.num_vertices()) + " vertices");
  }
}

double value_at(std::span<const double> field, Index v) { return field.empty() ? 1.0 : field[v]; }

}  // namespace

std::vector<double> refine_density(const TriangleMesh& mesh, std::span<const double> density,
                                   std::span<const double> deviation, const ErrorDensityOptions& options) {
  auto require = [](bool holds, const std::string& what) {
    if (!holds) throw UsageError("error density: " + what);
  };
  require(options.max_error > 0 && std::isfinite(options.max_error),
          "max_error must be a finite number > 0, got " + std::to_string(options.max_error));
  require(options.spacing > 0 && std::isfinite(options.spacing),
          "spacing must be a finite number > 0, got " + std::to_string(options.spacing));
  require(options.aim > 0 && options.aim <= 1, "aim must be in (0, 1], got " + std::to_string(options.aim));
  require(options.max_ratio >= 1 && std::isfinite(options.max_ratio),
          "max_ratio must be a finite number >= 1, got " + std::to_string(options.max_ratio));
  require_per_vertex(mesh, density, "density", true);
  require_per_vertex(mesh, deviation, "deviation", false);

  std::vector<double> factor(deviation.size());
  for (std::size_t v = 0; v < factor.size(); ++v) {
    const double ratio = std::max(1.0, deviation[v] / (options.aim * options.max_error));
    factor[v] = std::min(options.max_ratio, ratio * ratio);  // chord error ~ h^2, h ~ rho^(-1/4)
  }
  const std::vector<double> area = detail::vertex_areas(mesh);
  const std::vector<std::array<Index, 3>> sides = detail::edge_sides(mesh);
  const double edge = detail::mean_edge_length(mesh, sides);
  if (edge > 0) {
    detail::dilate(factor, sides, static_cast<int>(std::ceil(options.spacing / edge)));
    detail::smooth(factor, sides, area, detail::smoothing_passes(options.spacing, edge));
  }
  for (std::size_t v = 0; v < factor.size(); ++v) factor[v] *= value_at(density, static_cast<Index>(v));
  return factor;
}

std::int64_t sites_for_density(const TriangleMesh& mesh, std::int64_t sites, std::span<const double> from,
                               std::span<const double> to) {
  require_per_vertex(mesh, from, "the previous density", true);
  require_per_vertex(mesh, to, "the density", true);
  // int sqrt(rho) dA with rho linear in each face, by its corners' mean.
  double before = 0, after = 0;
  bool larger = false;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    const double area = face_area(mesh, f);
    double a = 0, b = 0;
    for (int c = 0; c < 3; ++c) {
      const Index v = mesh.faces(f, c);
      a += std::sqrt(value_at(from, v)) / 3;
      b += std::sqrt(value_at(to, v)) / 3;
      larger = larger || value_at(to, v) > value_at(from, v);
    }
    before += area * a;
    after += area * b;
  }
  if (!(before > 0)) return sites;
  const auto scaled = static_cast<std::int64_t>(std::llround(static_cast<double>(sites) * after / before));
  return larger ? std::max(scaled, sites + 1) : scaled;
}

std::vector<SurfacePoint> add_sites_at_deviations(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                                  std::span<const double> deviation, std::span<const double> density,
                                                  double spacing, std::int64_t count) {
  require_per_vertex(mesh, deviation, "deviation", false);
  require_per_vertex(mesh, density, "density", true);
  if (!std::all_of(density.begin(), density.end(), [](double rho) { return rho > 0 && std::isfinite(rho); })) {
    throw UsageError("error density: the density must be finite and > 0 at every vertex");
  }
  if (!(spacing > 0 && std::isfinite(spacing))) {
    throw UsageError("error density: spacing must be a finite number > 0, got " + std::to_string(spacing));
  }
  if (count < 0) throw UsageError("error density: count must be >= 0, got " + std::to_string(count));
  std::vector<SurfacePoint> result(sites.begin(), sites.end());
  // Only vertices of a face with three distinct corners can hold a site.
  std::vector<std::uint8_t> used(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(mesh.faces(f, k))] = 1;
  }
  std::vector<Index> candidates;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (deviation[v] > 0 && used[static_cast<std::size_t>(v)] != 0) candidates.push_back(v);
  }
  std::stable_sort(candidates.begin(), candidates.end(), [&](Index a, Index b) { return deviation[a] > deviation[b]; });
  auto clearance = [&](Index v) { return spacing / 2 / std::pow(value_at(density, v), 0.25); };
  double widest = 0;
  for (const Index v : candidates) widest = std::max(widest, clearance(v));
  // The sites so far in a grid; those added go to `added`, in a grid of
  // their own cells as wide as the widest clearance.
  std::vector<Eigen::Vector3d> positions(sites.size());
  for (std::size_t s = 0; s < sites.size(); ++s) positions[s] = sites[s].position(mesh);
  const detail::PointGrid grid(positions, std::max(widest, spacing));
  std::vector<Eigen::Vector3d> added;
  std::vector<std::pair<std::array<std::int64_t, 3>, Index>> added_cells;  // sorted by cell
  auto cell_of = [&](const Eigen::Vector3d& p) {
    std::array<std::int64_t, 3> cell;
    for (int a = 0; a < 3; ++a)
      cell[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(std::floor(p[a] / widest));
    return cell;
  };
  for (const Index v : candidates) {
    if (static_cast<std::int64_t>(added.size()) >= count) break;
    const Eigen::Vector3d p = mesh.vertices.row(v).transpose();
    const double r = clearance(v);
    bool near = false;
    grid.for_each_within(p, r, [&](Index, double) { near = true; });
    const std::array<std::int64_t, 3> cell = cell_of(p);
    for (std::int64_t dx = -1; dx <= 1 && !near; ++dx) {
      for (std::int64_t dy = -1; dy <= 1 && !near; ++dy) {
        for (std::int64_t dz = -1; dz <= 1 && !near; ++dz) {
          const std::array<std::int64_t, 3> key{cell[0] + dx, cell[1] + dy, cell[2] + dz};
          auto it = std::lower_bound(added_cells.begin(), added_cells.end(), std::pair(key, Index{-1}));
          for (; it != added_cells.end() && it->first == key && !near; ++it) {
            near = (added[static_cast<std::size_t>(it->second)] - p).norm() <= r;
          }
        }
      }
    }
    if (near) continue;
    const std::pair entry(cell, static_cast<Index>(added.size()));
    added_cells.insert(std::upper_bound(added_cells.begin(), added_cells.end(), entry), entry);
    added.push_back(p);
    result.push_back(SurfacePoint::at_vertex(v));
  }
  return result;
}

std::vector<std::uint8_t> sites_away_from_added(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                                std::size_t first_added, double reach) {
  if (!(reach >= 0 && std::isfinite(reach))) {
    throw UsageError("error density: reach must be a finite number >= 0, got " + std::to_string(reach));
  }
  std::vector<std::uint8_t> away(sites.size(), 1);
  if (first_added >= sites.size()) return away;
  // The sites in a grid; each added one marks those within reach of it.
  std::vector<Eigen::Vector3d> positions(sites.size());
  for (std::size_t s = 0; s < sites.size(); ++s) positions[s] = sites[s].position(mesh);
  const detail::PointGrid grid(positions, reach > 0 ? reach : 1.0);
  for (std::size_t s = first_added; s < sites.size(); ++s) {
    grid.for_each_within(positions[s], reach, [&](Index slot, double) { away[grid.original(slot)] = 0; });
  }
  return away;
}

}  // namespace geodual::remesh
