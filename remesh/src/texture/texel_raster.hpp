#pragma once
// Internal: the texels of a texture whose centres lie in a triangle given in
// texel coordinates (texel (x, y) has its centre at (x + 0.5, y + 0.5)), for
// the atlas's texture_used and the baker's texels: both count the same ones.

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>

namespace geodual::remesh::detail {

/// Calls visit(x, y, weights) for every texel of a size x size texture whose
/// centre lies in triangle t (either orientation; weights: its barycentric
/// coordinates there, all >= 0). A triangle without area has none.
template <typename Visit>
void for_each_texel_in(const std::array<Eigen::Vector2d, 3>& t, int size, Visit&& visit) {
  const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  const double area2 = cross(t[1] - t[0], t[2] - t[0]);
  if (!(std::abs(area2) > 0)) return;
  const auto first = [&](int axis) {
    return std::max(0, static_cast<int>(std::ceil(std::min({t[0][axis], t[1][axis], t[2][axis]}) - 0.5)));
  };
  const auto last = [&](int axis) {
    return std::min(size - 1, static_cast<int>(std::floor(std::max({t[0][axis], t[1][axis], t[2][axis]}) - 0.5)));
  };
  for (int y = first(1); y <= last(1); ++y) {
    for (int x = first(0); x <= last(0); ++x) {
      const Eigen::Vector2d q(x + 0.5, y + 0.5);
      const double w0 = cross(t[2] - t[1], q - t[1]) / area2;
      const double w1 = cross(t[0] - t[2], q - t[2]) / area2;
      const Eigen::Vector3d w(w0, w1, 1.0 - w0 - w1);
      if (w.minCoeff() >= 0) visit(x, y, w);
    }
  }
}

}  // namespace geodual::remesh::detail
