#pragma once
// The interior sites of one connected component, by each strategy. The
// boundary sites are already placed; strategies that care about spacing
// treat them as fixed sites.

#include "sampling/sampling_surface.hpp"

#include <cmath>
#include <memory>
#include <numbers>

namespace geodual::remesh::detail {

struct ComponentTask {
  Index component = -1;
  std::int64_t interior = 0;  ///< sites to add
  std::int64_t total = 0;     ///< all the component's sites, boundary ones included
  std::span<const SurfacePoint> boundary_sites;
};

/// Centre distance of `sites` equal disks packed hexagonally on `area`:
/// each site owns a regular hexagon of area (sqrt(3) / 2) s^2.
inline double hexagonal_spacing(double area, std::int64_t sites) {
  return std::sqrt(2 * area / (std::numbers::sqrt3 * static_cast<double>(sites)));
}

/// task.interior points uniform by area.
void sample_interior_random(const SamplingSurface& surface, const ComponentTask& task, Rng& rng,
                            std::vector<SurfacePoint>& out);

/// Weighted sample elimination (Yuksel 2015) of 5 x task.interior random
/// candidates down to task.interior, with the boundary sites as fixed
/// neighbours.
void sample_interior_poisson(const SamplingSurface& surface, const ComponentTask& task, Rng& rng,
                             std::vector<SurfacePoint>& out);

/// Farthest point sampling over a candidate graph; keeps scratch memory
/// between components.
class FarthestPointSampler {
 public:
  explicit FarthestPointSampler(const SamplingSurface& surface);
  ~FarthestPointSampler();
  void sample(const ComponentTask& task, Rng& rng, std::vector<SurfacePoint>& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace geodual::remesh::detail
