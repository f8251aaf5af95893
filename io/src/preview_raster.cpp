// Scan conversion for the preview: bounding-box traversal with incremental
// integer edge functions (Pineda 1988; the top-left rule as in Direct3D).

#include "preview_raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace geodual::io::detail {
namespace {

constexpr int kSubpixelBits = 8;
constexpr std::int64_t kSubpixelOne = std::int64_t{1} << kSubpixelBits;  // one sample
constexpr std::int64_t kSubpixelHalf = kSubpixelOne / 2;

// Far outside any picture, yet small enough that products of differences fit in 64 bits.
constexpr double kCoordinateLimit = 1.0e6;

struct FixedPoint {
  std::int64_t x;
  std::int64_t y;
};

FixedPoint to_fixed(const ScreenVertex& v) {
  const auto snap = [](double t) {
    return static_cast<std::int64_t>(
        std::llround(std::clamp(t, -kCoordinateLimit, kCoordinateLimit) * static_cast<double>(kSubpixelOne)));
  };
  return {snap(v.x), snap(v.y)};
}

// Floor and ceiling of a / kSubpixelOne for any sign of a.
std::int64_t floor_samples(std::int64_t a) { return a >> kSubpixelBits; }
std::int64_t ceil_samples(std::int64_t a) { return -((-a) >> kSubpixelBits); }

// Edge function of the directed edge u -> v at p: twice the signed area of
// (u, v, p); positive on the inner side of a positively oriented triangle.
std::int64_t edge_function(const FixedPoint& u, const FixedPoint& v, std::int64_t px, std::int64_t py) {
  return (v.x - u.x) * (py - u.y) - (v.y - u.y) * (px - u.x);
}

// Samples exactly on an edge belong to the triangle on one side only: the
// rule is antisymmetric in the edge's direction, and the two triangles of a
// shared edge run through it in opposite directions.
std::int64_t top_left_bias(const FixedPoint& u, const FixedPoint& v) {
  const std::int64_t dx = v.x - u.x;
  const std::int64_t dy = v.y - u.y;
  return (dy < 0 || (dy == 0 && dx > 0)) ? 0 : -1;
}

}  // namespace

SampleBuffer::SampleBuffer(int width_samples, int height_samples)
    : width(width_samples),
      height(height_samples),
      depth(static_cast<std::size_t>(width_samples) * static_cast<std::size_t>(height_samples),
            std::numeric_limits<float>::infinity()),
      id(depth.size(), kBackgroundId) {}

void rasterise_triangle(SampleBuffer& buffer, const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c,
                        std::int32_t id) {
  FixedPoint p0 = to_fixed(a);
  FixedPoint p1 = to_fixed(b);
  FixedPoint p2 = to_fixed(c);
  double z0 = a.depth;
  double z1 = b.depth;
  double z2 = c.depth;
  std::int64_t area = edge_function(p0, p1, p2.x, p2.y);
  if (area == 0) {
    return;
  }
  if (area < 0) {
    std::swap(p1, p2);
    std::swap(z1, z2);
    area = -area;
  }

  const std::int64_t min_x = std::min({p0.x, p1.x, p2.x});
  const std::int64_t max_x = std::max({p0.x, p1.x, p2.x});
  const std::int64_t min_y = std::min({p0.y, p1.y, p2.y});
  const std::int64_t max_y = std::max({p0.y, p1.y, p2.y});
  // Sample i's centre is i * one + half.
  const std::int64_t i0 = std::max<std::int64_t>(ceil_samples(min_x - kSubpixelHalf), 0);
  const std::int64_t i1 = std::min<std::int64_t>(floor_samples(max_x - kSubpixelHalf), buffer.width - 1);
  const std::int64_t j0 = std::max<std::int64_t>(ceil_samples(min_y - kSubpixelHalf), 0);
  const std::int64_t j1 = std::min<std::int64_t>(floor_samples(max_y - kSubpixelHalf), buffer.height - 1);
  if (i0 > i1 || j0 > j1) {
    return;
  }

  // w0 weighs vertex 0 (edge 1 -> 2), w1 vertex 1 (edge 2 -> 0), w2 vertex 2 (edge 0 -> 1).
  const std::int64_t start_x = i0 * kSubpixelOne + kSubpixelHalf;
  const std::int64_t start_y = j0 * kSubpixelOne + kSubpixelHalf;
  std::int64_t row0 = edge_function(p1, p2, start_x, start_y) + top_left_bias(p1, p2);
  std::int64_t row1 = edge_function(p2, p0, start_x, start_y) + top_left_bias(p2, p0);
  std::int64_t row2 = edge_function(p0, p1, start_x, start_y) + top_left_bias(p0, p1);
  const std::int64_t step_x0 = -(p2.y - p1.y) * kSubpixelOne;
  const std::int64_t step_x1 = -(p0.y - p2.y) * kSubpixelOne;
  const std::int64_t step_x2 = -(p1.y - p0.y) * kSubpixelOne;
  const std::int64_t step_y0 = (p2.x - p1.x) * kSubpixelOne;
  const std::int64_t step_y1 = (p0.x - p2.x) * kSubpixelOne;
  const std::int64_t step_y2 = (p1.x - p0.x) * kSubpixelOne;
  const double inverse_area = 1.0 / static_cast<double>(area);
  const double d0 = z0 * inverse_area;
  const double d1 = z1 * inverse_area;
  const double d2 = z2 * inverse_area;

  float* depth = buffer.depth.data();
  std::int32_t* ids = buffer.id.data();
  for (std::int64_t j = j0; j <= j1; ++j) {
    std::int64_t w0 = row0;
    std::int64_t w1 = row1;
    std::int64_t w2 = row2;
    const std::size_t row_start = static_cast<std::size_t>(j) * static_cast<std::size_t>(buffer.width);
    for (std::int64_t i = i0; i <= i1; ++i) {
      if ((w0 | w1 | w2) >= 0) {  // all three non-negative
        const auto z = static_cast<float>(static_cast<double>(w0) * d0 + static_cast<double>(w1) * d1 +
                                          static_cast<double>(w2) * d2);
        const std::size_t k = row_start + static_cast<std::size_t>(i);
        if (z < depth[k]) {
          depth[k] = z;
          ids[k] = id;
        }
      }
      w0 += step_x0;
      w1 += step_x1;
      w2 += step_x2;
    }
    row0 += step_y0;
    row1 += step_y1;
    row2 += step_y2;
  }
}

void rasterise_disc(SampleBuffer& buffer, double x, double y, float depth, double radius, double rim_width,
                    std::int32_t fill_id, std::int32_t rim_id) {
  if (!(radius > 0.0)) {
    return;
  }
  x = std::clamp(x, -kCoordinateLimit, kCoordinateLimit);
  y = std::clamp(y, -kCoordinateLimit, kCoordinateLimit);
  // Samples whose centre (i + 0.5) is within radius of x.
  const auto first = [](double t) { return static_cast<std::int64_t>(std::ceil(t - 0.5)); };
  const auto last = [](double t) { return static_cast<std::int64_t>(std::floor(t - 0.5)); };
  const std::int64_t i0 = std::max<std::int64_t>(first(x - radius), 0);
  const std::int64_t i1 = std::min<std::int64_t>(last(x + radius), buffer.width - 1);
  const std::int64_t j0 = std::max<std::int64_t>(first(y - radius), 0);
  const std::int64_t j1 = std::min<std::int64_t>(last(y + radius), buffer.height - 1);
  const double outer = radius * radius;
  const double inner_radius = std::max(radius - rim_width, 0.0);
  const double inner = inner_radius * inner_radius;
  for (std::int64_t j = j0; j <= j1; ++j) {
    const double dy = static_cast<double>(j) + 0.5 - y;
    for (std::int64_t i = i0; i <= i1; ++i) {
      const double dx = static_cast<double>(i) + 0.5 - x;
      const double d2 = dx * dx + dy * dy;
      if (d2 > outer) {
        continue;
      }
      const std::size_t k = buffer.index(static_cast<int>(i), static_cast<int>(j));
      if (depth < buffer.depth[k]) {
        buffer.depth[k] = depth;
        buffer.id[k] = d2 > inner ? rim_id : fill_id;
      }
    }
  }
}

void rasterise_thick_segment(SampleBuffer& buffer, const ScreenVertex& a, const ScreenVertex& b, double half_width,
                             std::int32_t id) {
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double length = std::hypot(dx, dy);
  if (!(length > 0.0) || !(half_width > 0.0)) {
    return;
  }
  const double nx = -dy / length * half_width;
  const double ny = dx / length * half_width;
  const ScreenVertex a_left{a.x + nx, a.y + ny, a.depth};
  const ScreenVertex a_right{a.x - nx, a.y - ny, a.depth};
  const ScreenVertex b_left{b.x + nx, b.y + ny, b.depth};
  const ScreenVertex b_right{b.x - nx, b.y - ny, b.depth};
  rasterise_triangle(buffer, a_left, a_right, b_right, id);
  rasterise_triangle(buffer, a_left, b_right, b_left, id);
}

}  // namespace geodual::io::detail
