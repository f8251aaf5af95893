#include "geodual/remesh/crease_pins.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/triangle_distance.hpp"
#include "geodual/mesh/union_find.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>

namespace geodual::remesh {
namespace {

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
        keeps = std::sqrt(squared_distance_to_segment(at(k), at(from), at(next))) <= max_error;
      }
      if (!keeps) break;
      to = next;
    }
    pins.push_back(to);
    from = to;
  }
  return pins;
}

/// Calls pair(i, j, distance) for every two of `points` closer than
/// `radius`: a sweep along x over the points sorted by it. Deterministic.
template <typename Pair>
void for_each_pair_within(const std::vector<Eigen::Vector3d>& points, double radius, Pair pair) {
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return points[i].x() < points[j].x() || (points[i].x() == points[j].x() && i < j);
  });
  for (std::size_t a = 0; a < order.size(); ++a) {
    for (std::size_t b = a + 1; b < order.size() && points[order[b]].x() - points[order[a]].x() < radius; ++b) {
      const double d = (points[order[a]] - points[order[b]]).norm();
      if (d < radius) pair(order[a], order[b], d);
    }
  }
}

}  // namespace

CreasePins crease_pins(const TriangleMesh& surface, const FeatureSet& features, const CreasePinOptions& options) {
  return crease_pins(RemeshSurface(surface), features, options);
}

CreasePins crease_pins(const RemeshSurface& prepared, const FeatureSet& features, const CreasePinOptions& options) {
  const TriangleMesh& surface = prepared.mesh();
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
  const MeshTopology& topology = prepared.topology();
  for (std::size_t v = 0; v < num_vertices; ++v) taken[v] |= topology.vertex_on_boundary[v];

  // One pin per vertex, in the order of first use, and the segments between them.
  std::vector<Index> pin_vertex;
  std::vector<std::size_t> pin_at(num_vertices, SIZE_MAX);
  std::vector<std::array<std::size_t, 2>> segments;
  for (const FeatureChain& crease : features.short_creases) {
    std::size_t previous = SIZE_MAX;
    for (const std::size_t i : pins_along(surface, crease, options.spacing, options.max_chord_error)) {
      const Index v = crease.vertices[i];
      if (taken[v]) {
        previous = SIZE_MAX;
        continue;
      }
      if (pin_at[v] == SIZE_MAX) {
        pin_at[v] = pin_vertex.size();
        pin_vertex.push_back(v);
      }
      if (previous != SIZE_MAX && previous != pin_at[v]) segments.push_back({previous, pin_at[v]});
      previous = pin_at[v];
    }
  }
  // Pins closer than the chord error (copies of a vertex, a scan's duplicate
  // points) are one, the first of them.
  std::vector<Eigen::Vector3d> position(pin_vertex.size());
  for (std::size_t i = 0; i < pin_vertex.size(); ++i) position[i] = surface.vertices.row(pin_vertex[i]);
  UnionFind same(pin_vertex.size());
  for_each_pair_within(position, options.max_chord_error, [&](std::size_t i, std::size_t j, double) {
    same.unite(static_cast<Index>(i), static_cast<Index>(j));
  });
  CreasePins result;
  std::vector<std::size_t> kept(pin_vertex.size());
  std::vector<Eigen::Vector3d> kept_position;
  for (std::size_t i = 0; i < pin_vertex.size(); ++i) {
    const auto root = static_cast<std::size_t>(same.find(static_cast<Index>(i)));
    if (root == i) {
      kept[i] = result.sites.size();
      result.sites.push_back(SurfacePoint::at_vertex(pin_vertex[i]));
      kept_position.push_back(position[i]);
    } else {
      kept[i] = kept[root];
    }
  }
  for (const auto& [a, b] : segments) {
    const std::size_t i = std::min(kept[a], kept[b]), j = std::max(kept[a], kept[b]);
    if (i != j) result.segments.push_back({i, j});
  }
  std::sort(result.segments.begin(), result.segments.end());
  result.segments.erase(std::unique(result.segments.begin(), result.segments.end()), result.segments.end());
  // Each pin's spacing: neighbour_spacing times the distance to the nearest other pin.
  std::vector<double> nearest(kept_position.size(), options.spacing);
  for_each_pair_within(kept_position, options.spacing, [&](std::size_t i, std::size_t j, double d) {
    nearest[i] = std::min(nearest[i], d);
    nearest[j] = std::min(nearest[j], d);
  });
  for (std::size_t i = 0; i < kept_position.size(); ++i) {
    const double spacing = options.neighbour_spacing * std::max(nearest[i], options.max_chord_error);
    result.spacing.push_back({kept_position[i], std::min(options.spacing, spacing)});
  }
  return result;
}

}  // namespace geodual::remesh
