#include "geodual/remesh/crease_pins.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_topology.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace geodual::remesh {
namespace {

double distance_to_segment(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - x).norm();
}

/// The indices into `chain` of its pins: its first vertex, then each time
/// the farthest vertex whose chord from the last pin is at most `spacing`
/// long and keeps the vertices between within `max_error`; its last vertex
/// last. A chain at most twice the error long gets its middle vertex alone.
std::vector<std::size_t> pins_along(const TriangleMesh& surface, const FeatureChain& crease, double spacing,
                                    double max_error) {
  const std::vector<Index>& chain = crease.vertices;
  if (crease.length <= 2 * max_error) return {chain.size() / 2};
  const auto at = [&](std::size_t i) -> Eigen::Vector3d { return surface.vertices.row(chain[i]); };
  std::vector<std::size_t> pins{0};
  const std::size_t last = chain.size() - 1;
  for (std::size_t from = 0; from < last;) {
    std::size_t to = from + 1;
    for (std::size_t next = from + 2; next <= last; ++next) {
      if ((at(next) - at(from)).norm() > spacing) break;
      bool keeps = true;
      for (std::size_t k = from + 1; k < next && keeps; ++k) {
        keeps = distance_to_segment(at(k), at(from), at(next)) <= max_error;
      }
      if (!keeps) break;
      to = next;
    }
    pins.push_back(to);
    from = to;
  }
  return pins;
}

/// Per point, the distance to the nearest other point, at most `cap`: a sweep
/// along x over the points sorted by it.
std::vector<double> nearest_distances(const std::vector<Eigen::Vector3d>& points, double cap) {
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return points[i].x() < points[j].x() || (points[i].x() == points[j].x() && i < j);
  });
  std::vector<double> nearest(points.size(), cap);
  for (std::size_t a = 0; a < order.size(); ++a) {
    for (std::size_t b = a + 1; b < order.size() && points[order[b]].x() - points[order[a]].x() < cap; ++b) {
      const double d = (points[order[a]] - points[order[b]]).norm();
      nearest[order[a]] = std::min(nearest[order[a]], d);
      nearest[order[b]] = std::min(nearest[order[b]], d);
    }
  }
  return nearest;
}

}  // namespace

CreasePins crease_pins(const TriangleMesh& surface, const FeatureSet& features, const CreasePinOptions& options) {
  if (!(options.spacing > 0) || !(options.max_chord_error > 0) || !(options.neighbour_spacing >= 1)) {
    throw UsageError("crease pins: spacing " + std::to_string(options.spacing) + " and chord error " +
                     std::to_string(options.max_chord_error) + " must be > 0, neighbour spacing " +
                     std::to_string(options.neighbour_spacing) + " >= 1");
  }
  const auto num_vertices = static_cast<std::size_t>(surface.num_vertices());
  // The chains and the boundary hold their vertices already: no pin there.
  std::vector<std::uint8_t> taken(num_vertices, 0);
  for (const FeatureChain& chain : features.chains) {
    for (const Index v : chain.vertices) taken[v] = 1;
  }
  const MeshTopology topology = build_mesh_topology(surface);
  for (std::size_t v = 0; v < num_vertices; ++v) taken[v] |= topology.vertex_on_boundary[v];

  CreasePins result;
  std::vector<Eigen::Vector3d> placed;
  std::vector<std::size_t> pin_at(num_vertices, SIZE_MAX);  // per vertex, its pin
  for (const FeatureChain& crease : features.short_creases) {
    std::size_t previous = SIZE_MAX;
    for (const std::size_t i : pins_along(surface, crease, options.spacing, options.max_chord_error)) {
      const Index v = crease.vertices[i];
      if (taken[v]) {
        previous = SIZE_MAX;
        continue;
      }
      const Eigen::Vector3d position = surface.vertices.row(v);
      std::size_t index = pin_at[v];
      // A pin this close to one placed before is that one (the last few, where creases meet).
      for (std::size_t j = placed.size(); j-- > 0 && index == SIZE_MAX && placed.size() - j <= 8;) {
        if ((placed[j] - position).norm() <= options.max_chord_error) index = j;
      }
      if (index == SIZE_MAX) {
        index = placed.size();
        result.sites.push_back(SurfacePoint::at_vertex(v));
        placed.push_back(position);
      }
      pin_at[v] = index;
      if (previous != SIZE_MAX && previous != index) result.segments.push_back({previous, index});
      previous = index;
    }
  }
  const std::vector<double> nearest = nearest_distances(placed, options.spacing);
  for (std::size_t i = 0; i < placed.size(); ++i) {
    result.spacing.push_back({placed[i], std::min(options.spacing, options.neighbour_spacing *
                                                                       std::max(nearest[i], options.max_chord_error))});
  }
  return result;
}

}  // namespace geodual::remesh
