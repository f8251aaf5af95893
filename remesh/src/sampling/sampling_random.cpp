// Uniform by area: a face with probability proportional to its area (running
// sums of the component's face areas, binary search), then a uniform point
// inside it.

#include "sampling/sampling_strategies.hpp"

namespace geodual::remesh::detail {

void sample_interior_random(const SamplingSurface& surface, const ComponentTask& task, Rng& rng,
                            std::vector<SurfacePoint>& out) {
  for (std::int64_t i = 0; i < task.interior; ++i) {
    out.push_back(random_point_in_face(surface.random_face(task.component, rng), rng));
  }
}

}  // namespace geodual::remesh::detail
