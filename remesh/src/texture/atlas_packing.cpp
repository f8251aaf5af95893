#include "texture/atlas_packing.hpp"

#include "geodual/mesh/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

namespace geodual::remesh::detail {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The convex hull, counter-clockwise (y up), by Andrew's monotone chain.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  });
  if (points.size() < 3) return points;
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

/// A chart turned to its bounding rectangle: rotation * p - corner lies in
/// [0, size.x()] x [0, size.y()].
struct ChartRectangle {
  Eigen::Matrix2d rotation = Eigen::Matrix2d::Identity();
  Eigen::Vector2d corner = Eigen::Vector2d::Zero();
  Eigen::Vector2d size = Eigen::Vector2d::Zero();
};

ChartRectangle bounding_rectangle(const Eigen::Matrix2d& rotation, const std::vector<Eigen::Vector2d>& hull) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  Eigen::Vector2d low = Eigen::Vector2d::Constant(infinity), high = Eigen::Vector2d::Constant(-infinity);
  for (const Eigen::Vector2d& p : hull) {
    const Eigen::Vector2d q = rotation * p;
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  return {rotation, low, high - low};
}

/// The smallest-area bounding rectangle has a side along an edge of the
/// convex hull (Freeman and Shapira): try each edge's direction.
ChartRectangle smallest_rectangle(const std::vector<Eigen::Vector2d>& points) {
  const std::vector<Eigen::Vector2d> hull = convex_hull(points);
  ChartRectangle best = bounding_rectangle(Eigen::Matrix2d::Identity(), hull);
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d edge = hull[(i + 1) % hull.size()] - hull[i];
    const double length = edge.norm();
    if (!(length > 0)) continue;
    const Eigen::Vector2d d = edge / length;
    Eigen::Matrix2d rotation;  // turns d onto the x axis
    rotation << d.x(), d.y(), -d.y(), d.x();
    const ChartRectangle candidate = bounding_rectangle(rotation, hull);
    if (candidate.size.prod() < best.size.prod() * (1 - 1e-9)) best = candidate;
  }
  return best;
}

/// A box's place: its top-left texel and whether it is turned a quarter.
struct BoxPlace {
  int x = 0;
  int y = 0;
  bool turned = false;
};

/// Skyline packing: the texture filled from the top (y = 0) down, the
/// skyline being the lowest filled row over each run of columns. Each box,
/// in the given order, goes upright or turned where it leaves the least
/// space unusable under it (with `least_waste`) and then where its far edge
/// is nearest the top, then leftmost.
class Skyline {
 public:
  explicit Skyline(int size) : size_(size) {}

  bool pack(const std::vector<std::array<int, 2>>& boxes, const std::vector<std::size_t>& order, bool least_waste,
            std::vector<BoxPlace>& places) {
    segments_.assign(1, {0, 0, size_});
    places.resize(boxes.size());
    for (const std::size_t i : order) {
      std::array<long, 3> best_score{-1, 0, 0};
      BoxPlace best;
      int best_width = 0, best_height = 0;
      for (int turned = 0; turned < 2; ++turned) {
        const int width = boxes[i][turned], height = boxes[i][1 - turned];
        if (turned && width == height) break;
        for (std::size_t s = 0; s < segments_.size(); ++s) {
          const int x = segments_[s].x;
          if (x + width > size_) break;
          const auto [y, waste] = floor_under(s, x + width);
          if (y + height > size_) continue;
          const std::array<long, 3> score{least_waste ? waste : 0, y + height, x};
          if (best_score[0] < 0 || score < best_score) {
            best_score = score;
            best = {x, y, turned == 1};
            best_width = width;
            best_height = height;
          }
        }
      }
      if (best_score[0] < 0) return false;
      places[i] = best;
      raise(best.x, best_width, best.y + best_height);
    }
    return true;
  }

 private:
  struct Segment {
    int x, y, width;
  };

  // The lowest free row over columns [segments_[s].x, end), and the texels
  // between it and the skyline there, which a box resting on it would waste.
  std::pair<int, long> floor_under(std::size_t s, int end) const {
    int y = 0;
    for (std::size_t t = s; t < segments_.size() && segments_[t].x < end; ++t) y = std::max(y, segments_[t].y);
    long waste = 0;
    for (std::size_t t = s; t < segments_.size() && segments_[t].x < end; ++t) {
      const int overlap = std::min(end, segments_[t].x + segments_[t].width) - segments_[t].x;
      waste += static_cast<long>(y - segments_[t].y) * overlap;
    }
    return {y, waste};
  }

  // Columns [x, x + width) filled down to row y.
  void raise(int x, int width, int y) {
    const int end = x + width;
    scratch_.clear();
    bool placed = false;
    for (const Segment& s : segments_) {
      const int s_end = s.x + s.width;
      if (s_end <= x) {
        scratch_.push_back(s);
        continue;
      }
      if (s.x < x) scratch_.push_back({s.x, s.y, x - s.x});
      if (!placed) {
        scratch_.push_back({x, y, width});
        placed = true;
      }
      if (s_end > end) scratch_.push_back({std::max(end, s.x), s.y, s_end - std::max(end, s.x)});
    }
    segments_.clear();
    for (const Segment& s : scratch_) {  // neighbours at one height merged
      if (!segments_.empty() && segments_.back().y == s.y) {
        segments_.back().width += s.width;
      } else {
        segments_.push_back(s);
      }
    }
  }

  int size_;
  std::vector<Segment> segments_;
  std::vector<Segment> scratch_;
};

/// The texels a chart side of this length takes at this scale: whole ones,
/// with more than half a texel of slack, so that no chart point comes near
/// a texel edge of its box (and round-off cannot take it into the gutter).
int texels(double length, double scale) { return static_cast<int>(std::floor(length * scale + 0.5)) + 1; }

}  // namespace

std::vector<ChartPlacement> pack_charts(const std::vector<std::vector<Eigen::Vector2d>>& charts, int texture_size,
                                        int gutter) {
  const std::size_t n = charts.size();
  std::vector<ChartRectangle> rectangles(n);
  double area = 0;
  for (std::size_t i = 0; i < n; ++i) {
    rectangles[i] = smallest_rectangle(charts[i]);
    area += rectangles[i].size.prod();
  }
  // Orders to try, larger boxes first: by the longer side, by the shorter
  // side, by area.
  std::vector<std::vector<std::size_t>> orders;
  for (int key = 0; key < 3; ++key) {
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    auto measure = [&](std::size_t i) {
      const Eigen::Vector2d& size = rectangles[i].size;
      return key == 0 ? size.maxCoeff() : key == 1 ? size.minCoeff() : size.prod();
    };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return measure(a) > measure(b); });
    orders.push_back(std::move(order));
  }

  // The first packing that fits, of each order with each placement rule.
  Skyline skyline(texture_size);
  std::vector<std::array<int, 2>> boxes(n);
  std::vector<BoxPlace> places, best_places;
  auto fits = [&](double scale) {
    for (std::size_t i = 0; i < n; ++i) {
      for (int axis = 0; axis < 2; ++axis) boxes[i][axis] = texels(rectangles[i].size[axis], scale) + 2 * gutter;
    }
    for (const bool least_waste : {false, true}) {
      for (const std::vector<std::size_t>& order : orders) {
        if (skyline.pack(boxes, order, least_waste, places)) return true;
      }
    }
    return false;
  };

  // The scale (texels per chart length unit) that would fill the texture
  // with the rectangles alone bounds the search from above; shrink until the
  // charts fit, then bisect between fitting and not.
  const double size = texture_size;
  double high = area > 0 ? size / std::sqrt(area) : 1.0;
  double low = high;
  double best_scale = 0;
  for (int attempt = 0; attempt < 200; ++attempt) {
    if (fits(low)) {
      best_scale = low;
      best_places = places;
      break;
    }
    high = low;
    low *= 0.8;
  }
  if (best_scale == 0) {
    throw Error("make_texture_atlas: " + std::to_string(n) + " charts do not fit a texture of " +
                std::to_string(texture_size) + " texels with a gutter of " + std::to_string(gutter));
  }
  for (int step = 0; step < 24 && high > low * (1 + 1e-4); ++step) {
    const double middle = 0.5 * (low + high);
    if (fits(middle)) {
      low = middle;
      best_scale = middle;
      best_places = places;
    } else {
      high = middle;
    }
  }

  std::vector<ChartPlacement> placements(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ChartRectangle& r = rectangles[i];
    const BoxPlace& place = best_places[i];
    Eigen::Matrix2d turn = Eigen::Matrix2d::Identity();
    Eigen::Vector2d shift = -r.corner;  // rectangle's corner to the origin
    Eigen::Vector2d extent = r.size;
    if (place.turned) {
      // A quarter turn (x, y) -> (-y, x), then back into x >= 0.
      turn << 0, -1, 1, 0;
      shift = turn * shift + Eigen::Vector2d(r.size.y(), 0);
      extent = Eigen::Vector2d(r.size.y(), r.size.x());
    }
    // The chart centred in its whole texels, gutter texels into its box.
    Eigen::Vector2d corner(place.x + gutter, place.y + gutter);
    for (int axis = 0; axis < 2; ++axis) {
      corner[axis] += 0.5 * (texels(extent[axis], best_scale) - extent[axis] * best_scale);
    }
    placements[i].transform = best_scale * turn * r.rotation;
    placements[i].offset = best_scale * shift + corner;
  }
  return placements;
}

}  // namespace geodual::remesh::detail
