// PlaneNearestSite must answer exactly as ConeEnvelope::nearest_site at
// points of a face (the face tracer bisects on its answers, and the diagram
// must not change by a bit): checked against the envelope itself on faces
// holding hundreds of sites with their windows, on near ties, with apexes
// far off the face, with huge coordinates, and at the corners of the grid's
// cells. And ConeEnvelope's slots, looked up by hash beyond a few dozen.

#include "../../voronoi/src/plane_nearest_site.hpp"

#include "geodual/mesh/random.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace geodual::voronoi::detail {
namespace {

const std::array<Eigen::Vector2d, 3> kFace = {Eigen::Vector2d(0, 0), Eigen::Vector2d(2, 0), Eigen::Vector2d(0.7, 1.3)};

Eigen::Vector2d point_in_face(SplitMix64& random) {
  double a = random.uniform(), b = random.uniform();
  if (a + b > 1) a = 1 - a, b = 1 - b;
  return kFace[0] + a * (kFace[1] - kFace[0]) + b * (kFace[2] - kFace[0]);
}

/// Compares the index with the envelope at p and at the doubles around it.
void expect_same_at(const ConeEnvelope& envelope, const PlaneNearestSite& index, const Eigen::Vector2d& p,
                    int& checked) {
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      const double inf = std::numeric_limits<double>::infinity();
      const Eigen::Vector2d q(dx == 0 ? p.x() : std::nextafter(p.x(), dx * inf),
                              dy == 0 ? p.y() : std::nextafter(p.y(), dy * inf));
      ASSERT_EQ(index.nearest_site(q), envelope.nearest_site(q)) << "at (" << q.x() << ", " << q.y() << ")";
      ++checked;
    }
  }
}

/// A face as the tracer sees one that holds `sites` sites: each site's own
/// cone, and windows from it on the face's three sides (a wedge and its two
/// ends' cones); the corners' cones; and sites beyond the sides seen
/// through windows, with apexes unfolded outside the face.
void add_face(ConeEnvelope& envelope, int sites, SplitMix64& random) {
  for (int s = 0; s < sites; ++s) {
    const Eigen::Vector2d site = point_in_face(random);
    envelope.add(site, 0.0, s);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = kFace[k], b = kFace[(k + 1) % 3];
      double t0 = random.uniform(), t1 = random.uniform();
      if (t0 > t1) std::swap(t0, t1);
      envelope.add_wedge(site, 0.0, s, a + t0 * (b - a), a + t1 * (b - a));
    }
  }
  for (int k = 0; k < 3; ++k) envelope.add(kFace[k], random.uniform(), static_cast<Index>(random.below(sites)));
  for (int outside = 0; outside < 20; ++outside) {
    const int k = static_cast<int>(random.below(3));
    const Eigen::Vector2d a = kFace[k], b = kFace[(k + 1) % 3];
    const Eigen::Vector2d away(-(b - a).y(), (b - a).x());  // out of the face (counter-clockwise corners)
    const Eigen::Vector2d apex = a + random.uniform() * (b - a) + (0.05 + 3 * random.uniform()) * away;
    double t0 = random.uniform(), t1 = random.uniform();
    if (t0 > t1) std::swap(t0, t1);
    envelope.add_wedge(apex, random.uniform(), sites + outside, a + t0 * (b - a), a + t1 * (b - a));
  }
}

void expect_same_in_face(const ConeEnvelope& envelope, const PlaneNearestSite& index, SplitMix64& random, int points) {
  int checked = 0;
  for (int i = 0; i < points; ++i) expect_same_at(envelope, index, point_in_face(random), checked);
  // Points a little off the face too: the tracer's sub-triangles round.
  for (int i = 0; i < points / 10; ++i) {
    expect_same_at(envelope, index, point_in_face(random) + 0.01 * Eigen::Vector2d(random.uniform(), random.uniform()),
                   checked);
  }
  for (const Eigen::Vector2d& corner : kFace) expect_same_at(envelope, index, corner, checked);
  EXPECT_GT(checked, 0);
}

TEST(PlaneNearestSite, MatchesTheEnvelopeOnFacesOfManySites) {
  SplitMix64 random(1);
  ConeEnvelope envelope;
  PlaneNearestSite index;
  for (const int sites : {1, 8, 40, 300}) {
    envelope.clear();
    add_face(envelope, sites, random);
    index.build(envelope, kFace);  // rebuilt in place, as a tracer does face after face
    expect_same_in_face(envelope, index, random, 2000);
  }
}

TEST(PlaneNearestSite, MatchesTheEnvelopeOnNearTies) {
  // Every cone twice, for two sites, once with sigma one unit in the last
  // place apart and once the very same: rounding and the tie rule (the
  // smaller site) decide.
  SplitMix64 random(2);
  ConeEnvelope envelope;
  PlaneNearestSite index;
  for (const bool same : {false, true}) {
    envelope.clear();
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector2d apex = point_in_face(random);
      const double sigma = 0.1 * random.uniform();
      envelope.add(apex, same ? sigma : std::nextafter(sigma, 1.0), 2 * i + 1);  // the larger site first
      envelope.add(apex, sigma, 2 * i);
    }
    index.build(envelope, kFace);
    expect_same_in_face(envelope, index, random, 2000);
    // And at the apexes themselves, where the two tie at sigma.
    int checked = 0;
    for (int slot = 0; slot < envelope.slot_count(); slot += 7) {
      expect_same_at(envelope, index, envelope.cones(slot)[0].apex, checked);
    }
  }
}

TEST(PlaneNearestSite, MatchesTheEnvelopeAtTheCellsCorners) {
  // Apexes and queries on a lattice: many fall on the boundaries of the
  // grid's cells, where a bound rounds either way.
  ConeEnvelope envelope;
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j)
      envelope.add(Eigen::Vector2d(0.1 * i, 0.065 * j), 0.001 * ((i * 7 + j) % 5), i * 21 + j);
  }
  PlaneNearestSite index;
  index.build(envelope, kFace);
  int checked = 0;
  for (int i = -10; i <= 50; ++i) {
    for (int j = -10; j <= 50; ++j) expect_same_at(envelope, index, Eigen::Vector2d(0.05 * i, 0.0325 * j), checked);
  }
}

TEST(PlaneNearestSite, MatchesTheEnvelopeWithApexesFarOffAndHugeCoordinates) {
  SplitMix64 random(4);
  ConeEnvelope envelope;
  add_face(envelope, 100, random);
  envelope.add(Eigen::Vector2d(-500, 300), 0.0, 1000);  // far off the grid, and nearest nowhere
  envelope.add(Eigen::Vector2d(40, 0.5), 0.0, 1001);
  PlaneNearestSite index;
  index.build(envelope, kFace);
  expect_same_in_face(envelope, index, random, 500);
  // Beyond the scale the bounds are kept for, every cone is evaluated.
  envelope.add(Eigen::Vector2d(1e300, 0), 0.0, 1002);
  index.build(envelope, kFace);
  expect_same_in_face(envelope, index, random, 500);
}

TEST(PlaneNearestSite, EmptyEnvelopeOrDegenerateRegion) {
  ConeEnvelope envelope;
  PlaneNearestSite index;
  index.build(envelope, kFace);
  EXPECT_EQ(index.nearest_site(Eigen::Vector2d(0.5, 0.5)), -1);
  // A zero-area region: no grid, every cone evaluated.
  SplitMix64 random(5);
  add_face(envelope, 50, random);
  const std::array<Eigen::Vector2d, 3> segment = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(2, 0)};
  index.build(envelope, segment);
  expect_same_in_face(envelope, index, random, 300);
}

TEST(ConeEnvelope, FindsTheSlotsOfManySites) {
  // Beyond a few dozen sites slots are looked up by hash: every site keeps
  // its slot (numbered by first appearance), through a clear and a refill.
  ConeEnvelope envelope;
  for (int round = 0; round < 2; ++round) {
    envelope.clear();
    for (int i = 0; i < 300; ++i) {
      const Index site = (i * 37) % 300 + round;  // a permutation, shifted in round 1
      envelope.add(Eigen::Vector2d(i, 0), 0.0, site);
      envelope.add(Eigen::Vector2d(i, 1), 1.0, site);  // a second cone for the same slot
      ASSERT_EQ(envelope.slot_count(), i + 1);
    }
    for (int i = 0; i < 300; ++i) {
      const Index site = (i * 37) % 300 + round;
      ASSERT_EQ(envelope.slot_of(site), i);
      ASSERT_EQ(envelope.site(i), site);
      EXPECT_EQ(envelope.cones(i).size(), 2u);
      EXPECT_EQ(envelope.distance(i, Eigen::Vector2d(i, 0)), 0.0);
    }
    EXPECT_EQ(envelope.slot_of(300 + round), -1);
    EXPECT_EQ(envelope.slot_of(-1), -1);
    EXPECT_NE(envelope.difference(round, 1 + round, Eigen::Vector2d(0, 0)), 0.0);
  }
  envelope.clear();
  envelope.add(Eigen::Vector2d(0, 0), 0.0, 5);
  EXPECT_EQ(envelope.slot_of(5), 0);
  EXPECT_EQ(envelope.slot_of(7), -1);  // a site of before the clear
}

}  // namespace
}  // namespace geodual::voronoi::detail
