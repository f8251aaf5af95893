// The density that asks for closer sites near given points: (h / sigma)^4
// with sigma = s + gradation * distance up to h, 1 beyond; and the sites
// sites_for_density adds for it.

#include "analytic_surfaces.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/remesh/error_density.hpp"
#include "geodual/remesh/spacing_density.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace geodual::remesh {
namespace {

constexpr int kGrid = 40;  // 40 x 40 cells on the unit square: edges of 0.025
constexpr Index kCentre = (kGrid / 2) * (kGrid + 1) + kGrid / 2;

TEST(SpacingDensity, AsksForThePointsSpacingAtThemAndGradesBackToTheSpacing) {
  const TriangleMesh square = test::unit_square(kGrid);
  const Eigen::Vector3d centre = square.vertices.row(kCentre).transpose();
  const double h = 0.1, s = 0.025, gradation = 0.5;
  const std::vector<SpacedPoint> points = {{centre, s}, {{0.9, 0.9, 0.0}, 0.2}};  // the second asks for nothing
  const std::vector<double> density = spacing_density(square, points, {.spacing = h, .gradation = gradation});
  ASSERT_EQ(density.size(), static_cast<std::size_t>(square.num_vertices()));
  EXPECT_NEAR(density[kCentre], std::pow(h / s, 4), 1e-9);
  for (Index v = 0; v < square.num_vertices(); ++v) {
    const double d = (square.vertices.row(v).transpose() - centre).norm();
    const double sigma = std::min(h, s + gradation * d);
    EXPECT_NEAR(density[static_cast<std::size_t>(v)], std::pow(h / sigma, 4), 1e-9) << "vertex " << v;
  }
  // Beyond (h - s) / gradation = 0.15 the density is 1: the rest of the
  // square keeps its spacing, and the count grows by the sites of the bump.
  EXPECT_EQ(density[0], 1.0);
  const std::int64_t sites = sites_for_density(square, 1000, {}, density);
  EXPECT_GT(sites, 1000);
  EXPECT_LT(sites, 1000 + 200);
}

TEST(SpacingDensity, IsCarriedOnlyByFacesNarrowEnoughForTheSpacingAsked) {
  // The same bump of spacing 0.025 at the square's centre, on a 40 x 40 grid
  // (edges of 0.025, diagonals of 0.035) and on a 4 x 4 one (0.25 and 0.35):
  // the coarse faces would spread it over a quarter of the square.
  const std::vector<SpacedPoint> points = {{{0.5, 0.5, 0.0}, 0.025}};
  const SpacingDensityOptions options{.spacing = 0.1};
  const TriangleMesh fine = test::unit_square(kGrid), coarse = test::unit_square(4);
  EXPECT_TRUE(carries_density(fine, spacing_density(fine, points, options), options.spacing));
  EXPECT_FALSE(carries_density(coarse, spacing_density(coarse, points, options), options.spacing));
  // Faces where the density is 1 may be as wide as they are.
  const std::vector<double> uniform(static_cast<std::size_t>(coarse.num_vertices()), 1.0);
  EXPECT_TRUE(carries_density(coarse, uniform, options.spacing));
  EXPECT_THROW(carries_density(coarse, std::vector<double>(3, 1.0), options.spacing), UsageError);
}

TEST(SpacingDensity, WithoutPointsIsUniformAndBadOptionsAreRefused) {
  const TriangleMesh square = test::unit_square(4);
  const std::vector<double> uniform = spacing_density(square, {}, {.spacing = 0.1});
  EXPECT_TRUE(std::all_of(uniform.begin(), uniform.end(), [](double rho) { return rho == 1.0; }));
  const std::vector<SpacedPoint> bad = {{{0.5, 0.5, 0.0}, 0.0}};
  EXPECT_THROW(spacing_density(square, bad, {.spacing = 0.1}), UsageError);
  EXPECT_THROW(spacing_density(square, {}, {.spacing = 0.0}), UsageError);
  EXPECT_THROW(spacing_density(square, {}, {.spacing = 0.1, .gradation = 0.0}), UsageError);
}

}  // namespace
}  // namespace geodual::remesh
