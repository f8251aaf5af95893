#include "texture/atlas_packing.hpp"

#include "geodual/mesh/error.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include <tbb/parallel_for.h>

namespace geodual::remesh::detail {
namespace {

using Word = std::uint64_t;
constexpr int kWordBits = 64;
constexpr Word kAllSet = ~Word{0};

/// Slack, in texels, by which every triangle is grown before its texels are
/// found: round-off in the final texture coordinates cannot reach a texel
/// the packer did not count.
constexpr double kSlack = 1e-3;

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

double rectangle_area(const Eigen::Matrix2d& rotation, const std::vector<Eigen::Vector2d>& hull) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  Eigen::Vector2d low = Eigen::Vector2d::Constant(infinity), high = Eigen::Vector2d::Constant(-infinity);
  for (const Eigen::Vector2d& p : hull) {
    const Eigen::Vector2d q = rotation * p;
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  return (high - low).prod();
}

/// The rotation turning the hull to its smallest-area bounding rectangle,
/// which has a side along an edge of the hull (Freeman and Shapira).
Eigen::Matrix2d smallest_rectangle_rotation(const std::vector<Eigen::Vector2d>& hull) {
  Eigen::Matrix2d best = Eigen::Matrix2d::Identity();
  double best_area = rectangle_area(best, hull);
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d edge = hull[(i + 1) % hull.size()] - hull[i];
    const double length = edge.norm();
    if (!(length > 0)) continue;
    const Eigen::Vector2d d = edge / length;
    Eigen::Matrix2d rotation;  // turns d onto the x axis
    rotation << d.x(), d.y(), -d.y(), d.x();
    const double area = rectangle_area(rotation, hull);
    if (area < best_area * (1 - 1e-9)) {
      best = rotation;
      best_area = area;
    }
  }
  return best;
}

/// Lowest and highest set bit of a range of bits, -1 if none.
int highest_set(const Word* row, int begin, int end) {  // bits [begin, end)
  if (begin >= end) return -1;
  const int last = end - 1;
  for (int w = last / kWordBits; w >= begin / kWordBits; --w) {
    Word word = row[w];
    if (w == last / kWordBits && last % kWordBits != kWordBits - 1) word &= (Word{1} << (last % kWordBits + 1)) - 1;
    if (w == begin / kWordBits) word &= kAllSet << (begin % kWordBits);
    if (word != 0) return w * kWordBits + (kWordBits - 1 - std::countl_zero(word));
  }
  return -1;
}

/// Bits [begin, end) of a row set.
void set_bits(Word* row, int begin, int end) {
  for (int x = begin; x < end;) {
    const int w = x / kWordBits, bit = x % kWordBits;
    const int count = std::min(kWordBits - bit, end - x);
    const Word mask = count == kWordBits ? kAllSet : ((Word{1} << count) - 1) << bit;
    row[w] |= mask;
    x += count;
  }
}

/// The runs of clear bits [begin, end) in a row of `words` words, left to
/// right; returns the longest run's length.
int clear_runs(const Word* row, int words, std::vector<std::array<int, 2>>& runs) {
  runs.clear();
  int longest = 0, start = -1;
  for (int w = 0; w < words; ++w) {
    const Word word = row[w];
    for (int bit = 0; bit < kWordBits;) {
      const Word rest = word >> bit;
      if (rest & 1) {
        if (start >= 0) {
          runs.push_back({start, w * kWordBits + bit});
          longest = std::max(longest, w * kWordBits + bit - start);
          start = -1;
        }
        bit += std::countr_one(rest);
      } else {
        if (start < 0) start = w * kWordBits + bit;
        bit += rest == 0 ? kWordBits - bit : std::countr_zero(rest);
      }
    }
  }
  if (start >= 0) {
    runs.push_back({start, words * kWordBits});
    longest = std::max(longest, words * kWordBits - start);
  }
  return longest;
}

/// A chart at one scale and turn: the texels its triangles touch, grown by
/// the gutter in x and y, as rows of bits. A chart point p lies at
/// footprint texel coordinates transform * p + shift.
struct Footprint {
  Eigen::Matrix2d transform = Eigen::Matrix2d::Identity();
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
  int width = 0;
  int height = 0;
  int words = 0;
  std::vector<Word> bits;  // bit x of row y: bits[y * words + x / 64], bit x % 64
  // Per row, its first run of set bits [run_begin, run_end), and whether
  // other bits follow it.
  std::vector<int> run_begin, run_end;
  std::vector<std::uint8_t> more_runs;
  int probe = 0;  // the row with the longest first run
  const Word* row(int y) const { return bits.data() + static_cast<std::size_t>(y) * words; }
};

/// A triangle's touched texels in one row: the columns [begin, end].
struct Span {
  int row, begin, end;
};

/// Scratch reused from chart to chart, so that the packing loops do not allocate.
struct Scratch {
  std::vector<Eigen::Vector2d> moved;
  std::vector<Span> spans;
  std::vector<Word> grown_rows;
};

/// The footprint of a chart (points, triangles) under `transform`, its
/// gutter `gutter` texels.
void rasterise(const std::vector<Eigen::Vector2d>& points, const std::vector<std::array<Index, 3>>& triangles,
               const Eigen::Matrix2d& transform, int gutter, Scratch& scratch, Footprint& out) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector2d>& moved = scratch.moved;
  moved.resize(points.size());
  Eigen::Vector2d low = Eigen::Vector2d::Constant(infinity), high = Eigen::Vector2d::Constant(-infinity);
  for (std::size_t i = 0; i < points.size(); ++i) {
    moved[i] = transform * points[i];
    low = low.cwiseMin(moved[i]);
    high = high.cwiseMax(moved[i]);
  }
  // The chart centred in its whole texels.
  Eigen::Vector2d shift;
  for (int axis = 0; axis < 2; ++axis) {
    const double extent = high[axis] - low[axis];
    shift[axis] = -low[axis] + 0.5 * (std::ceil(extent) - extent);
  }
  for (Eigen::Vector2d& p : moved) p += shift;

  // Per triangle and row, the columns of the texels it touches: the
  // x-extent of the triangle clipped to the row's band (grown by kSlack).
  std::vector<Span>& spans = scratch.spans;
  spans.clear();
  int first_row = std::numeric_limits<int>::max(), last_row = std::numeric_limits<int>::min();
  int first_column = std::numeric_limits<int>::max(), last_column = std::numeric_limits<int>::min();
  for (const auto& triangle : triangles) {
    const Eigen::Vector2d* p[3] = {&moved[triangle[0]], &moved[triangle[1]], &moved[triangle[2]]};
    const double y_low = std::min({p[0]->y(), p[1]->y(), p[2]->y()});
    const double y_high = std::max({p[0]->y(), p[1]->y(), p[2]->y()});
    const int row_begin = static_cast<int>(std::floor(y_low - kSlack));
    const int row_end = static_cast<int>(std::floor(y_high + kSlack));
    for (int row = row_begin; row <= row_end; ++row) {
      const double band_low = row - kSlack, band_high = row + 1 + kSlack;
      double x_low = infinity, x_high = -infinity;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d& a = *p[k];
        const Eigen::Vector2d& b = *p[(k + 1) % 3];
        if (a.y() >= band_low && a.y() <= band_high) {
          x_low = std::min(x_low, a.x());
          x_high = std::max(x_high, a.x());
        }
        for (const double bound : {band_low, band_high}) {
          if ((a.y() - bound) * (b.y() - bound) < 0) {
            const double x = a.x() + (bound - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
            x_low = std::min(x_low, x);
            x_high = std::max(x_high, x);
          }
        }
      }
      if (!(x_low <= x_high)) continue;
      const Span span{row, static_cast<int>(std::floor(x_low - kSlack)), static_cast<int>(std::floor(x_high + kSlack))};
      spans.push_back(span);
      first_row = std::min(first_row, row);
      last_row = std::max(last_row, row);
      first_column = std::min(first_column, span.begin);
      last_column = std::max(last_column, span.end);
    }
  }

  // The footprint's origin: the gutter before the first touched texel.
  const int origin_x = first_column - gutter, origin_y = first_row - gutter;
  out.transform = transform;
  out.shift = shift - Eigen::Vector2d(origin_x, origin_y);
  out.width = last_column - first_column + 1 + 2 * gutter;
  out.height = last_row - first_row + 1 + 2 * gutter;
  out.words = (out.width + kWordBits - 1) / kWordBits;
  const std::size_t row_words = static_cast<std::size_t>(out.words);
  // Touched texels grown in x, then the rows grown in y.
  std::vector<Word>& grown = scratch.grown_rows;
  grown.assign(static_cast<std::size_t>(out.height) * row_words, 0);
  for (const Span& span : spans) {
    set_bits(grown.data() + static_cast<std::size_t>(span.row - origin_y) * row_words, span.begin - origin_x - gutter,
             span.end - origin_x + gutter + 1);
  }
  out.bits.assign(grown.size(), 0);
  for (int y = gutter; y < out.height - gutter; ++y) {
    const Word* source = grown.data() + static_cast<std::size_t>(y) * row_words;
    for (int dy = -gutter; dy <= gutter; ++dy) {
      Word* target = out.bits.data() + static_cast<std::size_t>(y + dy) * row_words;
      for (std::size_t w = 0; w < row_words; ++w) target[w] |= source[w];
    }
  }
  out.run_begin.assign(static_cast<std::size_t>(out.height), 0);
  out.run_end.assign(static_cast<std::size_t>(out.height), 0);
  out.more_runs.assign(static_cast<std::size_t>(out.height), 0);
  out.probe = 0;
  for (int y = 0; y < out.height; ++y) {
    const Word* row = out.row(y);
    int begin = -1;
    for (int w = 0; w < out.words && begin < 0; ++w) {
      if (row[w] != 0) begin = w * kWordBits + std::countr_zero(row[w]);
    }
    if (begin < 0) continue;
    int end = out.words * kWordBits;  // the first clear bit after begin
    for (int w = begin / kWordBits; w < out.words; ++w) {
      const Word clear = ~row[w] & (w == begin / kWordBits ? kAllSet << (begin % kWordBits) : kAllSet);
      if (clear != 0) {
        end = w * kWordBits + std::countr_zero(clear);
        break;
      }
    }
    end = std::min(end, out.width);
    out.run_begin[y] = begin;
    out.run_end[y] = end;
    out.more_runs[y] = highest_set(row, end, out.width) >= 0 ? 1 : 0;
    if (end - begin > out.run_end[out.probe] - out.run_begin[out.probe]) out.probe = y;
  }
}

/// The texture's texels taken: the footprints placed so far, as rows of
/// bits and, per row, its runs of free texels.
class Occupancy {
 public:
  void reset(int size) {
    size_ = size;
    words_ = size / kWordBits + 2;  // a last word past the texture, all set
    bits_.assign(static_cast<std::size_t>(size) * words_, 0);
    for (int y = 0; y < size; ++y) set_bits(row(y), size, words_ * kWordBits);
    longest_.assign(static_cast<std::size_t>(size), size);
    free_.resize(static_cast<std::size_t>(size));
    for (auto& runs : free_) runs.assign(1, {0, size});
  }

  /// The first place (top row first, then leftmost column) where the
  /// footprint fits with its top row at most max_y; false if none.
  bool find(const Footprint& footprint, int max_y, int& best_x, int& best_y) const {
    const int last_y = std::min(max_y, size_ - footprint.height);
    const int last_x = size_ - footprint.width;
    for (int y = 0; y <= last_y; ++y) {
      if (!room_in_rows(footprint, y)) continue;
      // Rows taken in turn, from the widest: each moves x to the first
      // column from x on where its first run fits, until every row's does
      // at one x; then the rows of several runs are tested bit by bit.
      int x = 0, fitting = 0;
      for (int r = footprint.probe; x <= last_x; r = r + 1 == footprint.height ? 0 : r + 1) {
        const int next = first_run_fits_from(footprint, r, x, y);
        fitting = next == x ? fitting + 1 : 1;
        x = next;
        if (fitting < footprint.height || x > last_x) continue;
        if (collides(footprint, x, y)) {
          ++x;
          fitting = 0;
          continue;
        }
        best_x = x;
        best_y = y;
        return true;
      }
    }
    return false;
  }

  void place(const Footprint& footprint, int x, int y) {
    for (int r = 0; r < footprint.height; ++r) {
      Word* target = row(y + r);
      const Word* source = footprint.row(r);
      const int shift = x % kWordBits;
      for (int w = 0; w < footprint.words; ++w) {
        target[x / kWordBits + w] |= source[w] << shift;
        if (shift != 0) target[x / kWordBits + w + 1] |= source[w] >> (kWordBits - shift);
      }
      const auto at = static_cast<std::size_t>(y + r);
      longest_[at] = clear_runs(target, words_, free_[at]);
    }
  }

 private:
  Word* row(int y) { return bits_.data() + static_cast<std::size_t>(y) * words_; }
  const Word* row(int y) const { return bits_.data() + static_cast<std::size_t>(y) * words_; }

  // Whether every texture row the footprint would cover at row y has a free
  // run as long as the footprint's first run in that row.
  bool room_in_rows(const Footprint& footprint, int y) const {
    for (int r = 0; r < footprint.height; ++r) {
      if (longest_[static_cast<std::size_t>(y + r)] < footprint.run_end[r] - footprint.run_begin[r]) return false;
    }
    return true;
  }

  // The first column from x on where footprint row r's first run lies in a
  // free run of texture row y + r (past the texture if none).
  int first_run_fits_from(const Footprint& footprint, int r, int x, int y) const {
    const int begin = footprint.run_begin[r], length = footprint.run_end[r] - begin;
    if (length == 0) return x;
    const std::vector<std::array<int, 2>>& runs = free_[static_cast<std::size_t>(y + r)];
    // The first free run that ends at or past the run's end at x.
    auto at = std::partition_point(runs.begin(), runs.end(),
                                   [&](const std::array<int, 2>& run) { return run[1] < x + begin + length; });
    for (; at != runs.end(); ++at) {
      if ((*at)[1] - (*at)[0] >= length) return std::max(x, (*at)[0] - begin);
    }
    return size_;
  }

  // Whether a row of several runs meets a taken texel at (x, y).
  bool collides(const Footprint& footprint, int x, int y) const {
    const int shift = x % kWordBits;
    for (int r = 0; r < footprint.height; ++r) {
      if (!footprint.more_runs[r]) continue;
      const Word* target = row(y + r) + x / kWordBits;
      const Word* source = footprint.row(r);
      for (int w = 0; w < footprint.words; ++w) {
        Word hit = target[w] & (source[w] << shift);
        if (shift != 0) hit |= target[w + 1] & (source[w] >> (kWordBits - shift));
        if (hit != 0) return true;
      }
    }
    return false;
  }

  int size_ = 0;
  int words_ = 0;
  std::vector<Word> bits_;
  std::vector<int> longest_;                           // per row, its longest run of free texels
  std::vector<std::vector<std::array<int, 2>>> free_;  // per row, its runs of free texels [begin, end)
};

/// A chart to pack: its points and triangles, and the turns to try.
struct PackChart {
  const std::vector<Eigen::Vector2d>* points = nullptr;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<Eigen::Matrix2d> turns;
  double area = 0;
  double extent = 0;  // the largest distance from the first point
};

}  // namespace

std::vector<ChartPlacement> pack_charts(const std::vector<std::vector<Eigen::Vector2d>>& charts,
                                        const std::vector<std::vector<std::array<Index, 3>>>& triangles,
                                        int texture_size, int gutter) {
  const std::size_t n = charts.size();
  std::vector<std::vector<Eigen::Vector2d>> hulls(n);
  std::vector<PackChart> pack(n);
  double area = 0, extent = 0;
  for (std::size_t c = 0; c < n; ++c) {
    PackChart& chart = pack[c];
    hulls[c] = convex_hull(charts[c]);
    if (c < triangles.size() && !triangles[c].empty()) {
      chart.points = &charts[c];
      chart.triangles = triangles[c];
    } else {  // the hull, as a fan of triangles
      chart.points = &hulls[c];
      const Index corners = static_cast<Index>(hulls[c].size());
      for (Index k = 1; k + 1 < corners; ++k) chart.triangles.push_back({0, k, k + 1});
      if (corners < 3) chart.triangles.push_back({0, corners - 1, corners - 1});
    }
    for (const auto& [a, b, d] : chart.triangles) {
      const std::vector<Eigen::Vector2d>& p = *chart.points;
      chart.area += 0.5 * std::abs(cross(p[b] - p[a], p[d] - p[a]));
    }
    for (const Eigen::Vector2d& p : *chart.points)
      chart.extent = std::max(chart.extent, (p - chart.points->front()).norm());
    area += chart.area;
    extent = std::max(extent, chart.extent);
    // Quarter turns of the smallest bounding rectangle's rotation and of the
    // chart as flattened.
    const Eigen::Matrix2d rectangle = smallest_rectangle_rotation(hulls[c]);
    Eigen::Matrix2d quarter;
    quarter << 0, -1, 1, 0;
    for (int base = 0; base < (rectangle.isIdentity(0) ? 1 : 2); ++base) {
      Eigen::Matrix2d turn = base == 0 ? rectangle : Eigen::Matrix2d::Identity();
      for (int k = 0; k < 4; ++k) {
        chart.turns.push_back(turn);
        turn = quarter * turn;
      }
    }
  }
  // Larger charts first.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return pack[a].area > pack[b].area; });
  // Charts after the largest few (a share of the area under 1 % each) are
  // tried at the quarter turns of their smallest rectangle only: they fill
  // holes, where the four other turns rarely find a better place, at half the cost.
  for (std::size_t rank = 0; rank < n; ++rank) {
    PackChart& chart = pack[order[rank]];
    if (rank >= 8 && chart.area < 0.01 * area && chart.turns.size() > 4) chart.turns.resize(4);
  }

  // Per turn of a chart (at most 8), tried side by side: its footprint and scratch, and where it fits.
  struct TurnTry {
    Scratch scratch;
    Footprint footprint;
    int x = -1, y = -1;
  };
  std::size_t most_turns = 0;
  for (const PackChart& chart : pack) most_turns = std::max(most_turns, chart.turns.size());
  std::vector<TurnTry> tries(most_turns);
  Occupancy occupancy;
  std::vector<ChartPlacement> placements(n), best_placements;
  auto fits = [&](double scale) {
    occupancy.reset(texture_size);
    for (const std::size_t c : order) {
      const PackChart& chart = pack[c];
      // Every turn's first place (top row first, then leftmost), found in parallel.
      tbb::parallel_for(std::size_t{0}, chart.turns.size(), [&](std::size_t k) {
        TurnTry& attempt = tries[k];
        attempt.x = attempt.y = -1;
        rasterise(*chart.points, chart.triangles, scale * chart.turns[k], gutter, attempt.scratch, attempt.footprint);
        if (attempt.footprint.width > texture_size || attempt.footprint.height > texture_size) return;
        occupancy.find(attempt.footprint, texture_size, attempt.x, attempt.y);
      });
      // The one whose bottom is highest, then leftmost, then the first turn: the same whatever the threads.
      std::size_t best = tries.size();
      long best_bottom = std::numeric_limits<long>::max();
      for (std::size_t k = 0; k < chart.turns.size(); ++k) {
        const TurnTry& attempt = tries[k];
        if (attempt.x < 0) continue;
        const long bottom = attempt.y + attempt.footprint.height;
        if (bottom < best_bottom || (bottom == best_bottom && attempt.x < tries[best].x)) {
          best_bottom = bottom;
          best = k;
        }
      }
      if (best == tries.size()) return false;
      const TurnTry& chosen = tries[best];
      occupancy.place(chosen.footprint, chosen.x, chosen.y);
      placements[c].transform = chosen.footprint.transform;
      placements[c].offset = chosen.footprint.shift + Eigen::Vector2d(chosen.x, chosen.y);
    }
    return true;
  };

  // The scale (texels per chart length unit) at which the charts alone would
  // fill the texture bounds the search from above; shrink until the charts
  // fit, then bisect between fitting and not.
  const double size = texture_size;
  double high = area > 0 ? size / std::sqrt(area) : 1.0;
  double low = 0.85 * high;  // charts leave gaps and need their gutters: the bound itself never fits
  double best_scale = 0;
  for (int attempt = 0; attempt < 200 && low * extent > 1e-3; ++attempt) {
    if (fits(low)) {
      best_scale = low;
      best_placements = placements;
      break;
    }
    high = low;
    low *= 0.93;
  }
  if (best_scale == 0) {
    throw Error("make_texture_atlas: " + std::to_string(n) + " charts do not fit a texture of " +
                std::to_string(texture_size) + " texels with a gutter of " + std::to_string(gutter) +
                " texels each; a larger texture (--texture-size) holds them");
  }
  for (int step = 0; step < 16 && high > low * (1 + 1e-2); ++step) {
    const double middle = 0.5 * (low + high);
    if (fits(middle)) {
      low = middle;
      best_placements = placements;
    } else {
      high = middle;
    }
  }
  return best_placements;
}

std::vector<ChartPlacement> pack_charts(const std::vector<std::vector<Eigen::Vector2d>>& charts, int texture_size,
                                        int gutter) {
  return pack_charts(charts, {}, texture_size, gutter);
}

}  // namespace geodual::remesh::detail
