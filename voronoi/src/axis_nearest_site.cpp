#include "axis_nearest_site.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace geodual::voronoi::detail {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
/// The wedges' intervals are found on [-domain, domain]; beyond the largest
/// scale, x - apex.x could overflow there, and every cone is evaluated instead.
constexpr double domain = 0x1p1000;
constexpr double largest_scale = 0x1p900;

/// The doubles in order as integers (both zeros at 0), and back.
std::int64_t ordered(double d) {
  const auto bits = std::bit_cast<std::int64_t>(d);
  return bits >= 0 ? bits : std::numeric_limits<std::int64_t>::min() - bits;
}
double from_ordered(std::int64_t k) {
  return std::bit_cast<double>(k >= 0 ? k : std::numeric_limits<std::int64_t>::min() - k);
}

/// Where `holds`, monotone in x on [-domain, domain], is true: [lo, hi], open
/// to infinity on the side where it holds at the end of the domain, or
/// lo > hi where it never holds. The change is searched over the doubles
/// themselves, so the ends are exactly where the floating-point test
/// changes: galloping out from `guess` (where it changes in exact
/// arithmetic, a few units in the last place off), then bisecting.
template <typename Holds>
std::pair<double, double> where_holds(Holds&& holds, double guess) {
  const bool at_low = holds(-domain), at_high = holds(domain);
  if (at_low == at_high) return at_low ? std::pair(-infinity, infinity) : std::pair(infinity, -infinity);
  // Doubles as offsets from -domain in order; holds() takes at_high's value
  // from some offset on. Bracket that offset: holds(a) != at_high == holds(b).
  const std::int64_t low = ordered(-domain);
  const std::uint64_t high = static_cast<std::uint64_t>(ordered(domain)) - static_cast<std::uint64_t>(low);
  auto holds_at = [&](std::uint64_t offset) {
    return holds(from_ordered(static_cast<std::int64_t>(static_cast<std::uint64_t>(low) + offset))) == at_high;
  };
  const std::uint64_t start = guess > -domain && guess < domain  // false for NaN
                                  ? static_cast<std::uint64_t>(ordered(guess)) - static_cast<std::uint64_t>(low)
                                  : high / 2;
  std::uint64_t a = 0, b = high;
  if (holds_at(start)) {
    b = start;
    for (std::uint64_t step = 1; step < b; step *= 2) {
      if (!holds_at(b - step)) {
        a = b - step;
        break;
      }
      b -= step;
    }
  } else {
    a = start;
    for (std::uint64_t step = 1; step < high - a; step *= 2) {
      if (holds_at(a + step)) {
        b = a + step;
        break;
      }
      a += step;
    }
  }
  while (b - a > 1) {
    const std::uint64_t middle = a + (b - a) / 2;
    (holds_at(middle) ? b : a) = middle;
  }
  const double first = from_ordered(static_cast<std::int64_t>(static_cast<std::uint64_t>(low) + b));
  const double last = from_ordered(static_cast<std::int64_t>(static_cast<std::uint64_t>(low) + a));
  return at_high ? std::pair(first, infinity) : std::pair(-infinity, last);
}

}  // namespace

void MinTree::assign(std::span<const double> keys) {
  size_ = static_cast<Index>(keys.size());
  leaves_ = 1;
  while (leaves_ < size_) leaves_ *= 2;
  nodes_.assign(2 * static_cast<std::size_t>(leaves_), infinity);
  std::copy(keys.begin(), keys.end(), nodes_.begin() + leaves_);
  for (Index node = leaves_ - 1; node >= 1; --node) nodes_[node] = std::min(nodes_[2 * node], nodes_[2 * node + 1]);
}

void AxisNearestSite::build(const ConeEnvelope& envelope) {
  points_.clear();
  wedges_.clear();
  others_.clear();
  scale_ = 0;
  for (int slot = 0; slot < envelope.slot_count(); ++slot) {
    for (const DistanceCone& cone : envelope.cones(slot)) {
      scale_ = std::max(scale_, std::abs(cone.sigma) + std::abs(cone.apex.x()) + std::abs(cone.apex.y()));
    }
  }
  const bool bounded = scale_ <= largest_scale;  // false for NaN too
  std::vector<Wedge>& wedges = wedge_scratch_;
  wedges.clear();
  for (int slot = 0; slot < envelope.slot_count(); ++slot) {
    const Index site = envelope.site(slot);
    for (const DistanceCone& cone : envelope.cones(slot)) {
      if (!bounded || (cone.in_wedge_only && !cone.wedge_opens)) {
        others_.push_back({cone, site});
      } else if (!cone.in_wedge_only) {
        points_.push_back({cone, site});
      } else {
        // q = p - apex, as DistanceCone::sees() computes it; each test
        // changes where q meets its ray's line (q.y = -apex.y).
        const double qy = -cone.apex.y();
        const auto [lo0, hi0] =
            where_holds([&](double x) { return cone.after_ray0(Eigen::Vector2d(Eigen::Vector2d(x, 0) - cone.apex)); },
                        cone.apex.x() + cone.ray0.x() * qy / cone.ray0.y());
        const auto [lo1, hi1] =
            where_holds([&](double x) { return cone.before_ray1(Eigen::Vector2d(Eigen::Vector2d(x, 0) - cone.apex)); },
                        cone.apex.x() + cone.ray1.x() * qy / cone.ray1.y());
        const double lo = std::max(lo0, lo1), hi = std::min(hi0, hi1);
        if (lo <= hi) wedges.push_back({lo, hi, {cone, site}});
      }
    }
  }

  std::sort(points_.begin(), points_.end(),
            [](const SiteCone& a, const SiteCone& b) { return a.cone.apex.x() < b.cone.apex.x(); });
  point_x_.clear();
  for (const SiteCone& e : points_) point_x_.push_back(e.cone.apex.x());
  const Index num_points = static_cast<Index>(points_.size());
  keys_.clear();
  for (const SiteCone& e : points_) keys_.push_back(e.cone.sigma - e.cone.apex.x());
  left_keys_.assign(keys_);
  best_left_upto_.resize(points_.size());
  for (Index i = 0; i < num_points; ++i) {
    best_left_upto_[i] = i > 0 && keys_[best_left_upto_[i - 1]] <= keys_[i] ? best_left_upto_[i - 1] : i;
  }
  keys_.clear();
  for (const SiteCone& e : points_) keys_.push_back(e.cone.sigma + e.cone.apex.x());
  right_keys_.assign(keys_);
  best_right_from_.resize(points_.size());
  for (Index i = num_points; i-- > 0;) {
    best_right_from_[i] =
        i + 1 < num_points && keys_[best_right_from_[i + 1]] <= keys_[i] ? best_right_from_[i + 1] : i;
  }

  std::sort(wedges.begin(), wedges.end(), [](const Wedge& a, const Wedge& b) { return a.lo < b.lo; });
  wedge_lo_.clear();
  keys_.clear();
  for (const Wedge& w : wedges) {
    wedges_.push_back(w.entry);
    wedge_lo_.push_back(w.lo);
    keys_.push_back(-w.hi);
  }
  wedge_minus_hi_.assign(keys_);
}

Index AxisNearestSite::nearest_site(double x) const {
  NearestCone nearest{Eigen::Vector2d(x, 0)};
  auto consider = [&](const SiteCone& c) { nearest.consider(c); };
  for (const SiteCone& e : others_) consider(e);
  const auto wedge_end =
      static_cast<Index>(std::upper_bound(wedge_lo_.begin(), wedge_lo_.end(), x) - wedge_lo_.begin());
  wedge_minus_hi_.for_each_at_most(0, wedge_end, -x, [&](Index i) { consider(wedges_[i]); });
  if (points_.empty()) return nearest.site;

  // Points [0, split) have apex.x <= x. The smallest bound on each side is
  // a cone that sees p: its value bounds the nearest from above.
  const Index num_points = static_cast<Index>(points_.size());
  const auto split = static_cast<Index>(std::upper_bound(point_x_.begin(), point_x_.end(), x) - point_x_.begin());
  if (split > 0) consider(points_[best_left_upto_[split - 1]]);
  if (split < num_points) consider(points_[best_right_from_[split]]);
  // A cone whose computed value is at most the least value so far has a
  // computed bound below that plus the margin: the value, the key and the
  // threshold are each within a few units in the last place of scale_ + |x|
  // of their exact figures.
  const double margin = 32 * std::numeric_limits<double>::epsilon() * (scale_ + std::abs(x));
  const double bound = nearest.value;
  left_keys_.for_each_at_most(0, split, bound - x + margin, [&](Index i) { consider(points_[i]); });
  right_keys_.for_each_at_most(split, num_points, bound + x + margin, [&](Index i) { consider(points_[i]); });
  return nearest.site;
}

}  // namespace geodual::voronoi::detail
