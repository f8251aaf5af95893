#include "dual/ear_clipping.hpp"

#include "geodual/mesh/triangle_shape.hpp"

#include <algorithm>
#include <cstddef>

namespace geodual::remesh::detail {

std::vector<std::array<Index, 3>> clip_ears(std::vector<Index> polygon, const VertexMatrix& positions,
                                            const std::function<bool(Index, Index)>& is_edge, double min_angle,
                                            double max_edge) {
  // The triangle's smallest angle, or 0 where a side is too long (0 or not a
  // number for a degenerate one).
  const auto angle = [&](Index a, Index b, Index c) {
    const Eigen::Vector3d p = positions.row(a), q = positions.row(b), r = positions.row(c);
    const double longest = std::max({(q - p).norm(), (r - q).norm(), (p - r).norm()});
    return longest <= max_edge ? triangle_shape(p, q, r).min_angle() : 0.0;
  };
  std::vector<std::array<Index, 3>> ears;
  if (polygon.size() < 3) return ears;
  while (polygon.size() > 3) {
    std::size_t best = polygon.size();
    double best_angle = min_angle;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const Index prev = polygon[(i + polygon.size() - 1) % polygon.size()];
      const Index next = polygon[(i + 1) % polygon.size()];
      if (is_edge(prev, next)) continue;
      const double a = angle(prev, polygon[i], next);
      if (a > best_angle) best_angle = a, best = i;
    }
    if (best == polygon.size()) return {};
    ears.push_back(
        {polygon[(best + polygon.size() - 1) % polygon.size()], polygon[best], polygon[(best + 1) % polygon.size()]});
    polygon.erase(polygon.begin() + static_cast<std::ptrdiff_t>(best));
  }
  if (!(angle(polygon[0], polygon[1], polygon[2]) > min_angle)) return {};
  ears.push_back({polygon[0], polygon[1], polygon[2]});
  return ears;
}

}  // namespace geodual::remesh::detail
