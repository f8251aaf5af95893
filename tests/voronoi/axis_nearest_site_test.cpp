// AxisNearestSite must answer exactly as ConeEnvelope::nearest_site on the x
// axis (the edge crossings bisect on its answers, and the diagram must not
// change by a bit): checked against the envelope itself on random edges of
// thousands of windows, on near ties, on cones off the axis (a boundary
// edge's), and at the ends of the windows and the doubles next to them.

#include "../../voronoi/src/axis_nearest_site.hpp"

#include "geodual/mesh/random.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace geodual::voronoi::detail {
namespace {

/// Compares the index with the envelope at x and at the doubles around it.
void expect_same_at(const ConeEnvelope& envelope, const AxisNearestSite& index, double x, int& checked) {
  double at = x;
  for (int k = 0; k < 3; ++k) at = std::nextafter(at, -std::numeric_limits<double>::infinity());
  for (int k = 0; k < 7; ++k, at = std::nextafter(at, std::numeric_limits<double>::infinity())) {
    ASSERT_EQ(index.nearest_site(at), envelope.nearest_site(Eigen::Vector2d(at, 0))) << "x = " << at;
    ++checked;
  }
}

/// Random points of [-0.05 length, 1.05 length], every window end, and the
/// midpoints between consecutive ends, as find_edge_crossings asks.
void expect_same_along(const ConeEnvelope& envelope, const AxisNearestSite& index, double length,
                       std::vector<double> ends, SplitMix64& random, int random_points) {
  int checked = 0;
  for (int i = 0; i < random_points; ++i) {
    expect_same_at(envelope, index, length * (1.1 * random.uniform() - 0.05), checked);
  }
  ends.push_back(0);
  ends.push_back(length);
  std::sort(ends.begin(), ends.end());
  for (std::size_t i = 0; i < ends.size(); ++i) {
    expect_same_at(envelope, index, ends[i], checked);
    if (i > 0) expect_same_at(envelope, index, 0.5 * (ends[i - 1] + ends[i]), checked);
  }
  EXPECT_GT(checked, 0);
}

/// Windows tiling [0, length] as MMP leaves them on an edge: sorted, disjoint,
/// each from a source on either side, plus the cones of the edge's two ends.
std::vector<double> add_edge_windows(ConeEnvelope& envelope, double length, int windows, int sites,
                                     SplitMix64& random) {
  std::vector<double> cuts;
  for (int i = 0; i + 1 < windows; ++i) cuts.push_back(length * random.uniform());
  cuts.push_back(0);
  cuts.push_back(length);
  std::sort(cuts.begin(), cuts.end());
  for (int i = 0; i + 1 < static_cast<int>(cuts.size()); ++i) {
    const double b0 = cuts[i], b1 = cuts[i + 1];
    const double side = random.uniform() < 0.5 ? -1.0 : 1.0;
    const Eigen::Vector2d source(b0 + (random.uniform() - 0.5) * length, side * length * (0.01 + random.uniform()));
    const auto site = static_cast<Index>(random.below(static_cast<std::uint64_t>(sites)));
    envelope.add_wedge(source, length * random.uniform(), site, Eigen::Vector2d(b0, 0), Eigen::Vector2d(b1, 0));
  }
  envelope.add(Eigen::Vector2d::Zero(), length * random.uniform(), 0);
  envelope.add(Eigen::Vector2d(length, 0), length * random.uniform(), sites - 1);
  return cuts;
}

TEST(MinTree, ListsExactlyTheKeysAtMostTheThreshold) {
  SplitMix64 random(11);
  MinTree tree;
  for (const int n : {1, 2, 3, 7, 64, 100, 1000}) {
    std::vector<double> keys(static_cast<std::size_t>(n));
    for (double& key : keys) key = std::floor(20 * random.uniform());  // many equal keys
    tree.assign(keys);
    ASSERT_EQ(tree.size(), n);
    for (int trial = 0; trial < 200; ++trial) {
      const auto a = static_cast<Index>(random.below(static_cast<std::uint64_t>(n) + 1));
      const auto b = static_cast<Index>(random.below(static_cast<std::uint64_t>(n) + 1));
      const Index begin = std::min(a, b), end = std::max(a, b);
      const double threshold = std::floor(20 * random.uniform());
      std::vector<Index> listed;
      tree.for_each_at_most(begin, end, threshold, [&](Index i) { listed.push_back(i); });
      std::sort(listed.begin(), listed.end());
      std::vector<Index> expected;
      for (Index i = begin; i < end; ++i) {
        if (keys[i] <= threshold) expected.push_back(i);
      }
      ASSERT_EQ(listed, expected) << "n " << n << " range [" << begin << ", " << end << ")";
    }
  }
}

TEST(AxisNearestSite, MatchesTheEnvelopeOnEdgesOfManyWindows) {
  SplitMix64 random(1);
  ConeEnvelope envelope;
  AxisNearestSite index;
  for (const int windows : {1, 5, 40, 1000}) {
    for (const int sites : {2, 7, 300}) {
      envelope.clear();
      const double length = 0.1 + 10 * random.uniform();
      const std::vector<double> cuts = add_edge_windows(envelope, length, windows, sites, random);
      index.build(envelope);  // rebuilt in place, as a tracer does edge after edge
      expect_same_along(envelope, index, length, cuts, random, 2000);
    }
  }
}

TEST(AxisNearestSite, MatchesTheEnvelopeOnNearTies) {
  // Every window twice, for two sites, once with sigma one unit in the last
  // place apart, and once with the very same cone: which site wins is
  // decided by rounding and by the tie rule (the smaller site).
  SplitMix64 random(2);
  ConeEnvelope envelope;
  AxisNearestSite index;
  for (const bool same : {false, true}) {
    envelope.clear();
    const double length = 3.0;
    std::vector<double> cuts = {0};
    for (int i = 1; i < 500; ++i) cuts.push_back(length * i / 500);
    cuts.push_back(length);
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      // Sources far along the axis, nearly on it: the distance grows almost
      // as fast as x, so the ends' cones tie with the wedge to rounding.
      const Eigen::Vector2d source(-1e3 * (1 + random.uniform()), 1e-9 * random.uniform());
      const double sigma = random.uniform();
      const double other = same ? sigma : std::nextafter(sigma, 2.0);
      const Eigen::Vector2d b0(cuts[i], 0), b1(cuts[i + 1], 0);
      envelope.add_wedge(source, other, 9, b0, b1);  // the larger site first
      envelope.add_wedge(source, sigma, 4, b0, b1);
    }
    index.build(envelope);
    expect_same_along(envelope, index, length, cuts, random, 3000);
  }
}

TEST(AxisNearestSite, MatchesTheEnvelopeForConesOffTheAxis) {
  // A boundary edge's envelope holds its face's cones moved into the edge's
  // frame: apexes anywhere, wedges through any segment, and wedges that do
  // not open (apex on the line of their interval).
  SplitMix64 random(3);
  ConeEnvelope envelope;
  AxisNearestSite index;
  const double length = 2.0;
  for (int trial = 0; trial < 20; ++trial) {
    envelope.clear();
    std::vector<double> ends;
    auto point = [&] {
      return Eigen::Vector2d(length * (3 * random.uniform() - 1), length * (2 * random.uniform() - 1));
    };
    for (int i = 0; i < 150; ++i) {
      const auto site = static_cast<Index>(random.below(12));
      const double sigma = length * random.uniform();
      const double kind = random.uniform();
      if (kind < 0.3) {
        envelope.add(point(), sigma, site);
      } else if (kind < 0.8) {
        const Eigen::Vector2d end0 = point(), end1 = point();
        envelope.add_wedge(point(), sigma, site, end0, end1);
      } else {
        // Apex on the axis, looking along it: the wedge does not open.
        const double a = length * random.uniform(), b = length * random.uniform();
        envelope.add_wedge(Eigen::Vector2d(-length * random.uniform(), 0), sigma, site, Eigen::Vector2d(a, 0),
                           Eigen::Vector2d(b, 0));
        ends.push_back(a);
        ends.push_back(b);
      }
    }
    index.build(envelope);
    expect_same_along(envelope, index, length, ends, random, 500);
  }
}

TEST(AxisNearestSite, MatchesTheEnvelopeWithHugeCoordinates) {
  // Beyond the scale the bounds are kept for, every cone is evaluated.
  SplitMix64 random(4);
  ConeEnvelope envelope;
  const std::vector<double> cuts = add_edge_windows(envelope, 1.0, 100, 5, random);
  envelope.add(Eigen::Vector2d(1e300, 0), 0.0, 2);
  AxisNearestSite index;
  index.build(envelope);
  expect_same_along(envelope, index, 1.0, cuts, random, 500);
}

TEST(AxisNearestSite, EmptyEnvelopeHasNoSite) {
  ConeEnvelope envelope;
  AxisNearestSite index;
  index.build(envelope);
  EXPECT_EQ(index.nearest_site(0.5), -1);
  // A wedge that sees none of the axis.
  envelope.add_wedge(Eigen::Vector2d(0, 1), 0.0, 3, Eigen::Vector2d(0, 2), Eigen::Vector2d(1, 2));
  index.build(envelope);
  EXPECT_EQ(envelope.nearest_site(Eigen::Vector2d(0.5, 0)), 3);  // the ends' cones see everywhere
  EXPECT_EQ(index.nearest_site(0.5), 3);
}

}  // namespace
}  // namespace geodual::voronoi::detail
