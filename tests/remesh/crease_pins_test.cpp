// Short creases and their pins: the sharp edges no chain keeps come back as
// chains of their own, pinned at most a spacing apart where their chords
// keep to the error, one pin where creases meet, none on kept chains.

#include "hard_cases.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/remesh/crease_pins.hpp"
#include "geodual/remesh/features.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace geodual {
namespace {

/// The unit cube, n x n cells per side, two triangles per cell.
TriangleMesh cube(int n) {
  const std::vector<double> steps = bench::hard_case_detail::even_steps(0.0, 1.0, n + 1);
  return bench::hard_case_detail::voxel_surface({steps, steps, steps}, [](int, int, int) { return true; });
}

TEST(CreasePins, CreasesTooShortForChainsComeBackAsShortCreases) {
  const TriangleMesh box = cube(4);
  const remesh::FeatureSet kept = remesh::detect_features(box, {.min_chain_length = 0.99});
  EXPECT_EQ(kept.sharp_chains, 12);
  EXPECT_TRUE(kept.short_creases.empty());
  const remesh::FeatureSet dropped = remesh::detect_features(box, {.min_chain_length = 1.01});
  EXPECT_TRUE(dropped.empty());
  ASSERT_EQ(dropped.short_creases.size(), 12u);
  for (const remesh::FeatureChain& crease : dropped.short_creases) {
    EXPECT_NEAR(crease.length, 1.0, 1e-12);
    EXPECT_EQ(crease.vertices.size(), 5u);
  }
  EXPECT_TRUE(remesh::detect_features(box, {.sharp_angle = 91, .min_chain_length = 1.01}).short_creases.empty());
}

TEST(CreasePins, PinsAtMostASpacingApartOnePerCornerAndSegmentsAlongTheCreases) {
  const TriangleMesh box = cube(4);
  const remesh::FeatureSet features = remesh::detect_features(box, {.min_chain_length = 1.01});
  struct Case {
    double spacing;
    std::size_t per_crease;  // pins inside each crease
    double apart;
  };
  for (const Case c : {Case{0.3, 3, 0.25}, Case{0.6, 1, 0.5}, Case{1.0, 0, 1.0}}) {
    SCOPED_TRACE(c.spacing);
    const remesh::CreasePins pins = remesh::crease_pins(box, features, {.spacing = c.spacing, .max_chord_error = 1e-3});
    EXPECT_EQ(pins.sites.size(), 8 + 12 * c.per_crease);  // the corners once each
    EXPECT_EQ(pins.segments.size(), 12 * (c.per_crease + 1));
    ASSERT_EQ(pins.spacing.size(), pins.sites.size());
    std::set<Index> vertices;
    for (std::size_t i = 0; i < pins.sites.size(); ++i) {
      ASSERT_EQ(pins.sites[i].kind, SurfacePoint::Kind::vertex);
      vertices.insert(pins.sites[i].element);
      EXPECT_EQ(pins.spacing[i].position, pins.sites[i].position(box));
      EXPECT_NEAR(pins.spacing[i].spacing, std::min(1.5 * c.apart, c.spacing), 1e-12);
    }
    EXPECT_EQ(vertices.size(), pins.sites.size());
    for (const auto& [a, b] : pins.segments) {
      const Eigen::Vector3d d = pins.sites[a].position(box) - pins.sites[b].position(box);
      EXPECT_NEAR(d.norm(), c.apart, 1e-12);
      EXPECT_EQ((d.array().abs() > 1e-12).count(), 1);  // along an axis: on a crease
    }
  }
}

TEST(CreasePins, ACurvedCreaseGetsPinsCloserWhereItsChordsWouldLeaveIt) {
  // The turned shaft's circular creases (72 edges a circle) as short creases:
  // pins a spacing apart would leave them by more than the error.
  const TriangleMesh shaft = bench::stepped_shaft();
  const remesh::FeatureSet features = remesh::detect_features(shaft, {.min_chain_length = 1e9});
  ASSERT_FALSE(features.short_creases.empty());
  const double error = 1e-3;
  const remesh::CreasePins pins = remesh::crease_pins(shaft, features, {.spacing = 1e9, .max_chord_error = error});
  ASSERT_FALSE(pins.segments.empty());
  for (const remesh::FeatureChain& crease : features.short_creases) {
    for (const Index v : crease.vertices) {
      // Every crease vertex lies within the error of some segment's chord.
      const Eigen::Vector3d x = shaft.vertices.row(v);
      double nearest = 1e300;
      for (const auto& [a, b] : pins.segments) {
        const Eigen::Vector3d p = pins.sites[a].position(shaft), q = pins.sites[b].position(shaft);
        const double t = std::clamp((x - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0);
        nearest = std::min(nearest, (p + t * (q - p) - x).norm());
      }
      EXPECT_LE(nearest, error + 1e-12);
    }
  }
}

TEST(CreasePins, OptionsOutOfRangeAreRefused) {
  const TriangleMesh box = cube(2);
  const remesh::FeatureSet features = remesh::detect_features(box, {.min_chain_length = 1.01});
  EXPECT_THROW(remesh::crease_pins(box, features, {.spacing = 0, .max_chord_error = 1e-3}), UsageError);
  EXPECT_THROW(remesh::crease_pins(box, features, {.spacing = 1, .max_chord_error = 0}), UsageError);
  EXPECT_THROW(remesh::crease_pins(box, features, {.spacing = 1, .max_chord_error = 1e-3, .neighbour_spacing = 0.5}),
               UsageError);
}

}  // namespace
}  // namespace geodual
