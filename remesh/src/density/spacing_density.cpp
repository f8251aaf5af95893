#include "geodual/remesh/spacing_density.hpp"

#include "common/point_grid.hpp"
#include "geodual/mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace geodual::remesh {

std::vector<double> spacing_density(const TriangleMesh& mesh, std::span<const SpacedPoint> points,
                                    const SpacingDensityOptions& options) {
  const double h = options.spacing;
  if (!(h > 0 && std::isfinite(h))) {
    throw UsageError("spacing density: spacing must be a finite number > 0, got " + std::to_string(h));
  }
  if (!(options.gradation > 0 && std::isfinite(options.gradation))) {
    throw UsageError("spacing density: gradation must be a finite number > 0, got " +
                     std::to_string(options.gradation));
  }
  std::vector<Eigen::Vector3d> positions;  // of the points that ask for less than h
  std::vector<double> spacing_of;          // theirs
  double smallest = h;
  for (const SpacedPoint& point : points) {
    if (!(point.spacing > 0 && std::isfinite(point.spacing))) {
      throw UsageError("spacing density: a point's spacing must be a finite number > 0, got " +
                       std::to_string(point.spacing));
    }
    if (point.spacing >= h) continue;  // asks for nothing
    smallest = std::min(smallest, point.spacing);
    positions.push_back(point.position);
    spacing_of.push_back(point.spacing);
  }
  std::vector<double> density(static_cast<std::size_t>(mesh.num_vertices()), 1.0);
  if (positions.empty()) return density;
  // Beyond (h - s) / gradation of every point the spacing is h.
  const double reach = (h - smallest) / options.gradation;
  const detail::PointGrid grid(positions, reach);
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d x = mesh.vertices.row(v).transpose();
    double sigma = h;
    grid.for_each_within(x, reach, [&](Index slot, double d2) {
      sigma = std::min(sigma,
                       spacing_of[static_cast<std::size_t>(grid.original(slot))] + options.gradation * std::sqrt(d2));
    });
    density[static_cast<std::size_t>(v)] = std::pow(h / sigma, 4);
  }
  return density;
}

bool carries_density(const TriangleMesh& mesh, std::span<const double> density, double spacing, double max_ratio) {
  if (density.size() != static_cast<std::size_t>(mesh.num_vertices())) {
    throw UsageError("carries_density: " + std::to_string(density.size()) + " densities for a mesh of " +
                     std::to_string(mesh.num_vertices()) + " vertices");
  }
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    double rho = 1, longest = 0;
    for (int k = 0; k < 3; ++k) {
      rho = std::max(rho, density[static_cast<std::size_t>(mesh.faces(f, k))]);
      longest = std::max(longest,
                         (mesh.vertices.row(mesh.faces(f, k)) - mesh.vertices.row(mesh.faces(f, (k + 1) % 3))).norm());
    }
    if (rho > 1 && longest > max_ratio * spacing * std::pow(rho, -0.25)) return false;
  }
  return true;
}

}  // namespace geodual::remesh
