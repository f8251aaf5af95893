// Boundary sites (remesh/src/sampling/boundary_sites.hpp): the walk along a loop and
// the slit ends and corners that get a site of their own. Oracles:
// hand-built loops whose slits and corners are known (a square slit to its
// centre, a rectangle, polygons), loops without any (a disk's rim, a ragged
// or rounded outline, a Möbius strip's edge), and loops the walk runs partly
// against their faces' orientation.

#include "../../remesh/src/sampling/boundary_sites.hpp"
#include "remesh/analytic_surfaces.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <tuple>
#include <vector>

namespace geodual::remesh::detail {
namespace {

/// The rectangle [0, nx] x [0, ny] in z = 0, unit cells of two triangles;
/// the cell (flip_x, flip_y) wound the other way when given.
TriangleMesh rectangle(int nx, int ny, int flip_x = -1, int flip_y = -1) {
  std::vector<Eigen::Vector3d> vertices;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) vertices.emplace_back(i, j, 0);
  }
  auto id = [&](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
  std::vector<std::array<Index, 3>> faces;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      std::array<Index, 3> a = {id(i, j), id(i + 1, j), id(i + 1, j + 1)};
      std::array<Index, 3> b = {id(i, j), id(i + 1, j + 1), id(i, j + 1)};
      if (i == flip_x && j == flip_y) {
        std::swap(a[1], a[2]);
        std::swap(b[1], b[2]);
      }
      faces.push_back(a);
      faces.push_back(b);
    }
  }
  return test::mesh_from_lists(vertices, faces);
}

/// A Möbius strip of n quads round a circle of radius 1, width 2w: its edge
/// is one smooth loop of 2n edges, and no orientation of the faces agrees
/// along all of it.
TriangleMesh moebius(int n, double w) {
  std::vector<Eigen::Vector3d> vertices;
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * std::numbers::pi * i / n, twist = angle / 2;
    const Eigen::Vector3d centre(std::cos(angle), std::sin(angle), 0);
    const Eigen::Vector3d across = std::cos(twist) * centre + std::sin(twist) * Eigen::Vector3d::UnitZ();
    vertices.push_back(centre - w * across);
    vertices.push_back(centre + w * across);
  }
  std::vector<std::array<Index, 3>> faces;
  for (int i = 0; i < n; ++i) {
    const auto a = static_cast<Index>(2 * i), b = a + 1;
    // Across the seam the strip comes back upside down.
    const Index c = i + 1 < n ? a + 2 : 1, d = i + 1 < n ? a + 3 : 0;
    faces.push_back({a, c, d});
    faces.push_back({a, d, b});
  }
  return test::mesh_from_lists(vertices, faces);
}

/// The slit ends of the loops of `mesh`, as points, at the given spacing.
std::vector<Eigen::Vector3d> slit_end_points(const TriangleMesh& mesh, double spacing, std::int64_t limit = 1000) {
  const SamplingSurface surface = build_sampling_surface(mesh, true);
  std::vector<LoopWalk> walks;
  for (const BoundaryLoop& loop : surface.boundary_loops) walks.emplace_back(mesh, loop);
  const std::vector<std::int64_t> limits(walks.size(), limit);
  const std::vector<std::vector<std::size_t>> ends = slit_ends(walks, spacing, limits);
  std::vector<Eigen::Vector3d> points;
  for (std::size_t l = 0; l < walks.size(); ++l) {
    for (const std::size_t edge : ends[l]) points.push_back(walks[l].point(walks[l].start(edge)));
  }
  return points;
}

TEST(SlitEnds, ASlitToTheCentreOfASquareHasOne) {
  // Its end (1/2, 1/2); not the square's corners nor the slit's mouth, where
  // the boundary turns by 90 degrees.
  for (const double spacing : {0.05, 0.1, 0.5}) {
    SCOPED_TRACE(spacing);
    const std::vector<Eigen::Vector3d> ends = slit_end_points(test::slit_square(16), spacing);
    ASSERT_EQ(ends.size(), 1u);
    EXPECT_LT((ends[0] - Eigen::Vector3d(0.5, 0.5, 0)).norm(), 1e-12);
  }
  EXPECT_TRUE(slit_end_points(test::slit_square(16), 0.1, 0).empty());  // no sites to spare
}

TEST(SlitEnds, ASlitShallowerThanHalfASpacingHasNone) {
  // The slit is 1/2 deep; with a spacing of 2 the points r = 5/6 (a sixth
  // of the loop) either side of its end lie on the square's side, apart.
  EXPECT_TRUE(slit_end_points(test::slit_square(16), 2.0).empty());
}

TEST(SlitEnds, LoopsWithoutSlitsHaveNone) {
  for (const double spacing : {0.5, 1.0, 4.0}) {
    SCOPED_TRACE(spacing);
    EXPECT_TRUE(slit_end_points(rectangle(8, 4), spacing).empty());
    EXPECT_TRUE(slit_end_points(test::disk(8, 64), spacing / 8).empty());
  }
  // Nor where the walk runs edges against their faces: a cell wound the
  // other way, a Möbius strip's edge.
  EXPECT_TRUE(slit_end_points(rectangle(4, 1, 2, 0), 0.5).empty());
  EXPECT_TRUE(slit_end_points(rectangle(8, 4, 0, 0), 1.0).empty());
  EXPECT_TRUE(slit_end_points(moebius(96, 0.2), 0.2).empty());
}

TEST(LoopWalk, FollowsTheEdgesItRunsBackwards) {
  // Half of a Möbius strip's edge is run against its faces: its points by
  // arc length must still advance along the loop, each edge's length at a
  // time, and the sites sit at the same points.
  const TriangleMesh mesh = moebius(48, 0.2);
  const SamplingSurface surface = build_sampling_surface(mesh, true);
  ASSERT_EQ(surface.boundary_loops.size(), 1u);
  const BoundaryLoop& loop = surface.boundary_loops.front();
  EXPECT_TRUE(std::any_of(loop.edges.begin(), loop.edges.end(), [](const BoundaryEdge& e) { return e.reversed; }));
  const LoopWalk walk(mesh, loop);
  for (std::size_t i = 0; i < walk.num_edges(); ++i) {
    const double at = walk.start(i), next = i + 1 < walk.num_edges() ? walk.start(i + 1) : walk.length();
    EXPECT_NEAR((walk.point(next) - walk.point(at)).norm(), loop.edges[i].length, 1e-12) << "edge " << i;
    const double middle = (at + next) / 2;
    EXPECT_NEAR((walk.site(middle).position(mesh) - walk.point(middle)).norm(), 0, 1e-9) << "edge " << i;
  }
}

/// The smallest distance in space between two of `points`.
double closest_pair(const std::vector<Eigen::Vector3d>& points) {
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = i + 1; j < points.size(); ++j) closest = std::min(closest, (points[i] - points[j]).norm());
  }
  return closest;
}

/// The positions of k sites placed on `loop` of `mesh` at `spacing`.
std::vector<Eigen::Vector3d> placed_sites(const TriangleMesh& mesh, const BoundaryLoop& loop, std::int64_t k,
                                          double spacing) {
  const std::array<const BoundaryLoop*, 1> loops{&loop};
  const std::array<std::int64_t, 1> sites{k};
  std::vector<SurfacePoint> out;
  place_boundary_sites(mesh, loops, sites, spacing, out);
  std::vector<Eigen::Vector3d> points;
  for (const SurfacePoint& site : out) points.push_back(site.position(mesh));
  return points;
}

TEST(BoundarySites, OnALoopThatRunsBackOverItselfStayApart) {
  // A loop of four copies of one unit edge, there and back twice (what the
  // cut to a manifold leaves where sheets meet along a short edge), far
  // smaller than the spacing: three sites on it, as every loop gets. Evenly
  // by arc length two of them meet; spread, no two are closer than half the
  // edge (the most three points on a segment allow).
  const TriangleMesh mesh = test::mesh_from_lists({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  BoundaryLoop zigzag;
  for (int copy = 0; copy < 4; ++copy) zigzag.edges.push_back({0, 0, 1.0, copy % 2 == 1});
  zigzag.length = 4;
  const std::vector<Eigen::Vector3d> sites = placed_sites(mesh, zigzag, 3, 10.0);
  ASSERT_EQ(sites.size(), 3u);
  EXPECT_GT(closest_pair(sites), 0.5 - 1e-5);
}

/// Expects the k sites placed on the one loop of `mesh` at `spacing` at arc
/// lengths (j + 1/2) L / k.
void expect_even_by_arc_length(const TriangleMesh& mesh, std::int64_t k, double spacing) {
  const SamplingSurface surface = build_sampling_surface(mesh, true);
  ASSERT_EQ(surface.boundary_loops.size(), 1u);
  const BoundaryLoop& loop = surface.boundary_loops.front();
  const LoopWalk walk(mesh, loop);
  const std::vector<Eigen::Vector3d> sites = placed_sites(mesh, loop, k, spacing);
  ASSERT_EQ(sites.size(), static_cast<std::size_t>(k));
  for (std::size_t j = 0; j < sites.size(); ++j) {
    const double at = (static_cast<double>(j) + 0.5) * loop.length / static_cast<double>(k);
    EXPECT_NEAR((sites[j] - walk.point(at)).norm(), 0, 1e-5) << "site " << j;
  }
}

TEST(BoundarySites, OnLoopsThatDoNotRunBackOverThemselvesAreEvenByArcLength) {
  // The unit disk's rim (64 edges, a corner nowhere), 6.28 long, with 12
  // sites at spacing 0.5; and a triangular hole far smaller than the
  // spacing, whose three sites are as far apart along it as in space.
  expect_even_by_arc_length(test::disk(4, 64), 12, 0.5);
  expect_even_by_arc_length(test::mesh_from_lists({{0, 0, 0}, {1, 0, 0}, {0.5, 0.8, 0}}, {{0, 1, 2}}), 3, 10.0);
}

/// The closed polygon `outline` (in z = 0, counter-clockwise) as a fan of
/// triangles from its first point's opposite, the origin: one boundary loop.
TriangleMesh polygon_fan(const std::vector<Eigen::Vector2d>& outline) {
  std::vector<Eigen::Vector3d> vertices{Eigen::Vector3d::Zero()};
  for (const Eigen::Vector2d& p : outline) vertices.emplace_back(p.x(), p.y(), 0);
  std::vector<std::array<Index, 3>> faces;
  const auto n = static_cast<Index>(outline.size());
  for (Index i = 0; i < n; ++i) faces.push_back({0, 1 + i, 1 + (i + 1) % n});
  return test::mesh_from_lists(vertices, faces);
}

/// The corners of the one loop of `mesh` at `spacing` (as many sites as it has edges), as points.
std::vector<Eigen::Vector3d> corner_points(const TriangleMesh& mesh, double spacing) {
  const SamplingSurface surface = build_sampling_surface(mesh, true);
  std::vector<LoopWalk> walks;
  for (const BoundaryLoop& loop : surface.boundary_loops) walks.emplace_back(mesh, loop);
  const std::vector<std::int64_t> limits(walks.size(), 1000);
  const std::vector<std::vector<std::size_t>> none(walks.size());
  const std::vector<std::vector<std::size_t>> corners = loop_corners(walks, spacing, limits, none);
  std::vector<Eigen::Vector3d> points;
  for (std::size_t l = 0; l < walks.size(); ++l) {
    for (const std::size_t edge : corners[l]) points.push_back(walks[l].point(walks[l].start(edge)));
  }
  std::sort(points.begin(), points.end(),
            [](const auto& a, const auto& b) { return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z()); });
  return points;
}

/// The square [-2, 2]^2's outline, each side in `per_side` edges, the points
/// between its corners moved `ragged` inwards and outwards in turn.
std::vector<Eigen::Vector2d> square_outline(int per_side, double ragged) {
  const std::array<Eigen::Vector2d, 4> corner{Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, -2), Eigen::Vector2d(2, 2),
                                              Eigen::Vector2d(-2, 2)};
  std::vector<Eigen::Vector2d> outline;
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector2d& a = corner[static_cast<std::size_t>(side)];
    const Eigen::Vector2d& b = corner[static_cast<std::size_t>((side + 1) % 4)];
    const Eigen::Vector2d inward = Eigen::Vector2d(-(b - a).y(), (b - a).x()).normalized();
    for (int k = 0; k < per_side; ++k) {
      const double offset = k == 0 ? 0.0 : (k % 2 == 0 ? ragged : -ragged);
      outline.push_back(a + (b - a) * k / per_side + offset * inward);
    }
  }
  return outline;
}

TEST(BoundarySites, CornersWhereStraightSidesMeetGetSitesOfTheirOwn) {
  // The rectangle [0, 8] x [0, 4] at spacing 2: its four corners, and its
  // twelve sites one at each corner and evenly between (2 apart).
  const std::vector<Eigen::Vector3d> corners = corner_points(rectangle(8, 4), 2.0);
  const std::vector<Eigen::Vector3d> expected{{0, 0, 0}, {0, 4, 0}, {8, 0, 0}, {8, 4, 0}};
  ASSERT_EQ(corners.size(), expected.size());
  for (std::size_t i = 0; i < corners.size(); ++i) EXPECT_NEAR((corners[i] - expected[i]).norm(), 0, 1e-12);
  const SamplingSurface surface = build_sampling_surface(rectangle(8, 4), true);
  const std::vector<Eigen::Vector3d> sites = placed_sites(rectangle(8, 4), surface.boundary_loops.front(), 12, 2.0);
  for (const Eigen::Vector3d& corner : expected) {
    EXPECT_TRUE(std::any_of(sites.begin(), sites.end(), [&](const auto& s) { return (s - corner).norm() < 1e-5; }));
  }
  EXPECT_NEAR(closest_pair(sites), 2.0, 1e-5);
  // A triangle (corners of 60 degrees and less) and a square of 16 edges a
  // side at spacing 1 (sides straight for 2 spacings and more: 4 long).
  EXPECT_EQ(corner_points(polygon_fan({{-3, -2}, {3, -2}, {0, 4}}), 1.0).size(), 3u);
  EXPECT_EQ(corner_points(polygon_fan(square_outline(16, 0)), 1.0).size(), 4u);
  // A regular polygon's corners turn by 360 / n degrees: a hexagon's (60)
  // are corners, a 12-gon's (30, less than 45) not.
  auto regular = [](int n, double radius) {
    std::vector<Eigen::Vector2d> outline;
    for (int k = 0; k < n; ++k) {
      const double angle = 2 * std::numbers::pi * k / n;
      outline.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
    }
    return polygon_fan(outline);
  };
  EXPECT_EQ(corner_points(regular(6, 8), 1.0).size(), 6u);
  EXPECT_TRUE(corner_points(regular(12, 16), 1.0).empty());
}

TEST(BoundarySites, RaggedRoundOrShortLoopsHaveNoCorners) {
  // A scan's ragged outline: the square's sides zigzag by 0.1 (a tenth of
  // the spacing, beyond the spacing / 20 a straight side keeps to).
  EXPECT_TRUE(corner_points(polygon_fan(square_outline(16, 0.1)), 1.0).empty());
  // ... while a zigzag within it leaves the square's corners.
  EXPECT_EQ(corner_points(polygon_fan(square_outline(16, 0.02)), 1.0).size(), 4u);
  // A disk's rim; a square whose sides (4) are shorter than two spacings.
  EXPECT_TRUE(corner_points(test::disk(4, 64), 0.1).empty());
  EXPECT_TRUE(corner_points(polygon_fan(square_outline(16, 0)), 4.0).empty());
}

}  // namespace
}  // namespace geodual::remesh::detail
