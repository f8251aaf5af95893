#include "geodual/remesh/remesh_smoothing.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/triangle_distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace geodual::remesh {

void check_options(const RemeshSmoothingOptions& options) {
  if (!(options.smoothing_angle >= 0 && options.smoothing_angle <= 60)) {
    throw UsageError("smoothing angle " + std::to_string(options.smoothing_angle) +
                     ": must be in [0, 60] degrees (0: no smoothing)");
  }
  if (!(options.crease_tolerance >= 0 && std::isfinite(options.crease_tolerance))) {
    throw UsageError("crease tolerance " + std::to_string(options.crease_tolerance) +
                     ": must be a finite distance >= 0");
  }
}

RemeshSmoothing smooth_remesh(RepairedDual& remesh, const TriangleMesh& surface,
                              const voronoi::SurfaceTopology& topology, const RemeshSmoothingOptions& options,
                              std::span<const Index> fixed_vertices, std::span<const FeatureChain> creases,
                              const TriangleMesh* crease_mesh) {
  check_options(options);
  const auto num_vertices = static_cast<std::size_t>(remesh.mesh.num_vertices());
  std::vector<SurfacePoint> points(num_vertices);
  std::vector<std::uint8_t> sites_at(num_vertices, 0);  // up to 2: one, or more than one
  const auto vertex_of = [&](std::size_t site) {
    return remesh.vertex_of_site.empty() ? site : static_cast<std::size_t>(remesh.vertex_of_site[site]);
  };
  for (std::size_t site = 0; site < remesh.sites.size(); ++site) {
    const std::size_t v = vertex_of(site);
    points[v] = remesh.sites[site];
    sites_at[v] = static_cast<std::uint8_t>(std::min(2, sites_at[v] + 1));
  }
  std::vector<std::uint8_t> fixed(num_vertices, 0);
  for (std::size_t v = 0; v < num_vertices; ++v) fixed[v] = sites_at[v] != 1;
  for (const Index v : fixed_vertices) {
    if (v >= 0) fixed[static_cast<std::size_t>(v)] = 1;
  }
  const auto near_a_crease = [&](const Eigen::Vector3d& x) {
    for (const FeatureChain& crease : creases) {
      for (std::size_t k = 0; k + 1 < crease.vertices.size(); ++k) {
        if (std::sqrt(squared_distance_to_segment(x, crease_mesh->vertices.row(crease.vertices[k]),
                                                  crease_mesh->vertices.row(crease.vertices[k + 1]))) <=
            options.crease_tolerance) {
          return true;
        }
      }
    }
    return false;
  };
  if (!creases.empty() && crease_mesh) {
    for (std::size_t v = 0; v < num_vertices; ++v) {
      if (!fixed[v] && near_a_crease(remesh.mesh.vertices.row(static_cast<Index>(v)))) fixed[v] = 1;
    }
  }
  RemeshSmoothing result;
  if (options.fit_deviations) {
    result.fitting = fit_deviations(surface, topology, remesh.mesh, points, fixed);
  }
  result.smoothing =
      smooth_smallest_angles(surface, topology, remesh.mesh, points, fixed, {.min_angle = options.smoothing_angle});
  for (std::size_t site = 0; site < remesh.sites.size(); ++site) {
    const std::size_t v = vertex_of(site);
    if (!fixed[v]) remesh.sites[site] = points[v];
  }
  return result;
}

std::vector<Index> pin_vertices(const RepairedDual& remesh, std::span<const SurfacePoint> pins) {
  // The repair may leave sites out (RepairedDual::sites): the pins, at
  // vertices, are found by their vertex.
  std::vector<Index> pin_of_vertex;
  for (std::size_t pin = 0; pin < pins.size(); ++pin) {
    const auto element = static_cast<std::size_t>(pins[pin].element);
    if (pin_of_vertex.size() <= element) pin_of_vertex.resize(element + 1, -1);
    pin_of_vertex[element] = static_cast<Index>(pin);
  }
  std::vector<Index> vertex(pins.size(), -1);
  for (std::size_t s = 0; s < remesh.sites.size(); ++s) {
    const SurfacePoint& site = remesh.sites[s];
    if (site.kind != SurfacePoint::Kind::vertex || static_cast<std::size_t>(site.element) >= pin_of_vertex.size()) {
      continue;
    }
    const Index pin = pin_of_vertex[static_cast<std::size_t>(site.element)];
    if (pin < 0) continue;
    vertex[static_cast<std::size_t>(pin)] =
        remesh.vertex_of_site.empty() ? static_cast<Index>(s) : remesh.vertex_of_site[s];
  }
  return vertex;
}

}  // namespace geodual::remesh
