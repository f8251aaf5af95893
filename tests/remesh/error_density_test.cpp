// Error-driven sizing: the density grows by (deviation / (aim * bound))^2
// where a remesh strayed beyond the bound, spread over a spacing, and nowhere
// else; the site count keeps the spacing where the density is unchanged; the
// sites it adds go to the largest deviations, half a local spacing apart.

#include "analytic_surfaces.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/remesh/error_density.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace geodual::remesh {
namespace {

constexpr int kGrid = 40;  // 40 x 40 cells on the unit square: edges of 0.025
constexpr Index kCentre = (kGrid / 2) * (kGrid + 1) + kGrid / 2;

double distance_to_centre(const TriangleMesh& mesh, Index v) {
  return (mesh.vertices.row(v) - mesh.vertices.row(kCentre)).norm();
}

TEST(ErrorDensity, GrowsAroundAPeakOfTheDeviationAndNowhereElse) {
  const TriangleMesh square = test::unit_square(kGrid);
  std::vector<double> deviation(static_cast<std::size_t>(square.num_vertices()), 0.0);
  deviation[kCentre] = 0.015;  // twice the aim of 0.75 * 0.01: a factor 4
  const ErrorDensityOptions options{.max_error = 0.01, .spacing = 0.1};
  const std::vector<double> density = refine_density(square, {}, deviation, options);
  ASSERT_EQ(density.size(), deviation.size());
  // Spread over a spacing (4 edges) by maxima, then smoothed over a spacing
  // (16 one-ring passes): at most 20 edges out, the factor is still 1.
  EXPECT_GT(density[kCentre], 2.0);
  EXPECT_LE(*std::max_element(density.begin(), density.end()), 4.0);
  for (Index v = 0; v < square.num_vertices(); ++v) {
    EXPECT_GE(density[v], 1.0) << "vertex " << v;
    if (distance_to_centre(square, v) > 21 * 0.025 * std::sqrt(2.0)) {
      EXPECT_EQ(density[v], 1.0) << "vertex " << v;
    }
  }
  // Within the spread the whole neighbourhood of the peak is refined.
  for (Index v = 0; v < square.num_vertices(); ++v) {
    if (distance_to_centre(square, v) < 0.05) {
      EXPECT_GT(density[v], 1.5) << "vertex " << v;
    }
  }

  // The factor multiplies the density given.
  const std::vector<double> twice(deviation.size(), 2.0);
  const std::vector<double> on_twice = refine_density(square, twice, deviation, options);
  for (std::size_t v = 0; v < density.size(); ++v) EXPECT_DOUBLE_EQ(on_twice[v], 2 * density[v]);

  // A deviation within the aim everywhere changes nothing.
  const std::vector<double> within(deviation.size(), 0.0075);
  EXPECT_EQ(refine_density(square, twice, within, options), twice);
  // The factor stops at max_ratio.
  deviation[kCentre] = 1.0;
  const std::vector<double> capped = refine_density(square, {}, deviation, {.max_error = 0.01, .spacing = 0.025});
  EXPECT_LE(*std::max_element(capped.begin(), capped.end()), 16.0);
}

TEST(ErrorDensity, SitesKeepTheSpacingWhereTheDensityIsUnchanged) {
  const TriangleMesh square = test::unit_square(kGrid);
  const std::size_t n = static_cast<std::size_t>(square.num_vertices());
  const std::vector<double> ones(n, 1.0), fours(n, 4.0);
  // Spacing ~ rho^(-1/4): 4 times the density everywhere is twice the sites.
  EXPECT_EQ(sites_for_density(square, 1000, {}, fours), 2000);
  EXPECT_EQ(sites_for_density(square, 1000, ones, fours), 2000);
  EXPECT_EQ(sites_for_density(square, 1000, fours, fours), 1000);
  EXPECT_EQ(sites_for_density(square, 1000, fours, ones), 500);
  // 4 times on the left half (x < 1/2, the column x = 1/2 between): about 1.5 times.
  std::vector<double> left(n, 1.0);
  for (Index v = 0; v < square.num_vertices(); ++v) {
    if (square.vertices(v, 0) < 0.5) left[v] = 4.0;
  }
  EXPECT_NEAR(static_cast<double>(sites_for_density(square, 1000, {}, left)), 1500.0, 15.0);
  // A little more somewhere is at least one site more.
  std::vector<double> slightly(n, 1.0);
  slightly[kCentre] = 1.0001;
  EXPECT_EQ(sites_for_density(square, 1000, {}, slightly), 1001);
}

TEST(ErrorDensity, SitesAreAddedAtTheLargestDeviationsHalfASpacingApart) {
  const TriangleMesh square = test::unit_square(kGrid);
  // The deviation falls off from the centre, positive within 0.3 of it.
  std::vector<double> deviation(static_cast<std::size_t>(square.num_vertices()));
  for (Index v = 0; v < square.num_vertices(); ++v) deviation[v] = std::max(0.0, 0.3 - distance_to_centre(square, v));
  const std::vector<SurfacePoint> sites = {SurfacePoint::at_vertex(0), SurfacePoint::in_face(100, 0.2, 0.3, 0.5)};
  auto position = [&](const SurfacePoint& p) { return p.position(square); };
  auto check = [&](const std::vector<SurfacePoint>& result, double clearance) {
    ASSERT_GE(result.size(), sites.size());
    EXPECT_TRUE(std::equal(sites.begin(), sites.end(), result.begin(), [&](const auto& a, const auto& b) {
      return a.kind == b.kind && a.element == b.element && a.barycentric == b.barycentric;
    }));
    for (std::size_t i = sites.size(); i < result.size(); ++i) {
      ASSERT_EQ(result[i].kind, SurfacePoint::Kind::vertex);
      EXPECT_GT(deviation[result[i].element], 0.0);
      for (std::size_t j = 0; j < i; ++j) EXPECT_GT((position(result[i]) - position(result[j])).norm(), clearance);
    }
  };

  // Spacing 0.1: no two sites within 0.05; the centre, the largest, first.
  const std::vector<SurfacePoint> four = add_sites_at_deviations(square, sites, deviation, {}, 0.1, 4);
  ASSERT_EQ(four.size(), sites.size() + 4);
  EXPECT_EQ(four[sites.size()].element, kCentre);
  check(four, 0.05);
  // Past the room the positive deviation leaves, fewer are added.
  const std::vector<SurfacePoint> all = add_sites_at_deviations(square, sites, deviation, {}, 0.1, 1000);
  EXPECT_LT(all.size(), sites.size() + 1000);
  EXPECT_GT(all.size(), sites.size() + 20);  // a disk of radius 0.3 holds far more than 20 sites 0.05 apart
  check(all, 0.05);
  // A density of 16 halves the clearance: more fit, some closer than 0.05.
  const std::vector<double> dense(deviation.size(), 16.0);
  const std::vector<SurfacePoint> denser = add_sites_at_deviations(square, sites, deviation, dense, 0.1, 1000);
  EXPECT_GT(denser.size(), all.size() + all.size() / 2);
  check(denser, 0.025);
  // A site already at the centre keeps it from being added again.
  std::vector<SurfacePoint> with_centre = sites;
  with_centre.push_back(SurfacePoint::at_vertex(kCentre));
  const std::vector<SurfacePoint> around = add_sites_at_deviations(square, with_centre, deviation, {}, 0.1, 3);
  ASSERT_EQ(around.size(), with_centre.size() + 3);
  for (std::size_t i = with_centre.size(); i < around.size(); ++i) {
    EXPECT_GT(distance_to_centre(square, around[i].element), 0.05);
  }
  EXPECT_EQ(add_sites_at_deviations(square, sites, deviation, {}, 0.1, 0).size(), sites.size());
  // A vertex no triangle uses (scans have them) holds no site, however far
  // it strays.
  TriangleMesh with_stray = square;
  with_stray.vertices.conservativeResize(square.num_vertices() + 1, 3);
  with_stray.vertices.row(square.num_vertices()) << 0.9, 0.9, 0.0;
  std::vector<double> stray_deviation(deviation);
  stray_deviation.push_back(1.0);  // the largest
  const std::vector<SurfacePoint> strayed = add_sites_at_deviations(with_stray, sites, stray_deviation, {}, 0.1, 1);
  ASSERT_EQ(strayed.size(), sites.size() + 1);
  EXPECT_EQ(strayed.back().element, kCentre);

  EXPECT_THROW(add_sites_at_deviations(square, sites, deviation, {}, 0.0, 1), UsageError);
  EXPECT_THROW(add_sites_at_deviations(square, sites, deviation, {}, 0.1, -1), UsageError);
  EXPECT_THROW(add_sites_at_deviations(square, sites, std::vector<double>(3, 1.0), {}, 0.1, 1), UsageError);
  EXPECT_THROW(add_sites_at_deviations(square, sites, deviation, std::vector<double>(deviation.size(), 0.0), 0.1, 1),
               UsageError);
}

TEST(ErrorDensity, SitesFartherThanTheReachFromEveryAddedOneStay) {
  const TriangleMesh square = test::unit_square(kGrid);
  std::vector<SurfacePoint> sites;
  for (Index f = 0; f < square.num_faces(); f += 37) sites.push_back(SurfacePoint::in_face(f, 0.2, 0.3, 0.5));
  const std::size_t first_added = sites.size();
  sites.push_back(SurfacePoint::at_vertex(kCentre));
  sites.push_back(SurfacePoint::at_vertex(0));  // a corner
  const double reach = 0.2;
  const std::vector<std::uint8_t> away = sites_away_from_added(square, sites, first_added, reach);
  ASSERT_EQ(away.size(), sites.size());
  int staying = 0;
  for (std::size_t s = 0; s < sites.size(); ++s) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t a = first_added; a < sites.size(); ++a) {
      nearest = std::min(nearest, (sites[s].position(square) - sites[a].position(square)).norm());
    }
    EXPECT_EQ(away[s], nearest > reach ? 1 : 0) << s << " at " << nearest;
    staying += away[s];
  }
  EXPECT_GT(staying, static_cast<int>(first_added) / 2);
  EXPECT_LT(staying, static_cast<int>(first_added));
  // Nothing added: every site stays.
  const std::vector<std::uint8_t> none = sites_away_from_added(square, sites, sites.size(), reach);
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), static_cast<std::ptrdiff_t>(sites.size()));
  EXPECT_THROW(sites_away_from_added(square, sites, first_added, -1.0), UsageError);
  EXPECT_THROW(sites_away_from_added(square, sites, first_added, std::nan("")), UsageError);
}

TEST(ErrorDensity, OptionsOutOfRangeAreUsageErrors) {
  const TriangleMesh square = test::unit_square(4);
  const std::vector<double> deviation(static_cast<std::size_t>(square.num_vertices()), 0.0);
  EXPECT_THROW(refine_density(square, {}, deviation, {.max_error = 0, .spacing = 0.1}), UsageError);
  EXPECT_THROW(refine_density(square, {}, deviation, {.max_error = 0.1, .spacing = 0}), UsageError);
  EXPECT_THROW(refine_density(square, {}, deviation, {.max_error = 0.1, .spacing = 0.1, .aim = 1.5}), UsageError);
  EXPECT_THROW(refine_density(square, {}, deviation, {.max_error = 0.1, .spacing = 0.1, .max_ratio = 0.5}), UsageError);
  EXPECT_THROW(refine_density(square, {}, std::vector<double>(3, 0.0), {.max_error = 0.1, .spacing = 0.1}), UsageError);
  EXPECT_THROW(sites_for_density(square, 10, std::vector<double>(3, 1.0), {}), UsageError);
}

}  // namespace
}  // namespace geodual::remesh
