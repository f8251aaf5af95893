#pragma once
// Internal: the preview's visibility buffer. Every sample keeps the depth and
// the id of the nearest thing drawn over it (a face index, or one of the
// overlay ids below); colours are worked out afterwards, once per sample that
// is still visible (see preview.cpp).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace geodual::io::detail {

inline constexpr std::int32_t kBackgroundId = -1;
inline constexpr std::int32_t kPolylineId = -2;
inline constexpr std::int32_t kPointFillId = -3;
inline constexpr std::int32_t kPointRimId = -4;

/// A vertex on the sample grid: x to the right, y downwards, in samples (the
/// centre of sample (i, j) is (i + 0.5, j + 0.5)); smaller depth is nearer.
struct ScreenVertex {
  double x = 0.0;
  double y = 0.0;
  float depth = 0.0f;
};

struct SampleBuffer {
  int width = 0;                 ///< samples
  int height = 0;                ///< samples
  std::vector<float> depth;      ///< +infinity where nothing was drawn
  std::vector<std::int32_t> id;  ///< kBackgroundId where nothing was drawn

  SampleBuffer(int width_samples, int height_samples);

  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
  }
};

/// Depth-tested (strictly nearer wins, so the first of equals stays) fill of
/// the samples whose centres lie inside the triangle, either orientation;
/// depth interpolated linearly. Vertices are snapped to 1/256 sample and the
/// edge functions evaluated exactly in integers with a top-left rule: two
/// triangles sharing an edge never both cover, nor both miss, a sample on it.
/// Zero-area triangles draw nothing.
void rasterise_triangle(SampleBuffer& buffer, const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c,
                        std::int32_t id);

/// Depth-tested fill of the samples within `radius` of (x, y), at one depth;
/// samples farther than radius - rim_width from the centre get rim_id.
void rasterise_disc(SampleBuffer& buffer, double x, double y, float depth, double radius, double rim_width,
                    std::int32_t fill_id, std::int32_t rim_id);

/// A segment of the given half width (a rectangle, no caps), depth
/// interpolated along it: two triangles.
void rasterise_thick_segment(SampleBuffer& buffer, const ScreenVertex& a, const ScreenVertex& b, double half_width,
                             std::int32_t id);

}  // namespace geodual::io::detail
