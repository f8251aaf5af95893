// Corners of boundary loops (remesh/src/boundary_corners.hpp): where
// sample_sites puts a site of its own. Oracles: hand-built loops whose
// corners are known (a rectangle's four, a slit's end and mouth), smooth
// loops that have none (a disk's rim, a Möbius strip's edge), and loops the
// walk runs partly against their faces' orientation.

#include "remesh/analytic_surfaces.hpp"
#include "../../remesh/src/boundary_corners.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
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

/// The corners of the loops of `mesh`, as points, at the given spacing.
std::vector<Eigen::Vector3d> corner_points(const TriangleMesh& mesh, double spacing, std::int64_t limit = 1000) {
  const SamplingSurface surface = build_sampling_surface(mesh, true);
  std::vector<Eigen::Vector3d> points;
  for (const BoundaryLoop& loop : surface.boundary_loops) {
    const LoopWalk walk(mesh, loop);
    for (const std::size_t edge : loop_corners(walk, spacing, limit)) points.push_back(walk.point(walk.start(edge)));
  }
  return points;
}

int count_near(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& p) {
  return static_cast<int>(std::count_if(points.begin(), points.end(), [&](const Eigen::Vector3d& q) {
    return (q - p).norm() < 1e-12;
  }));
}

void expect_rectangle_corners(const std::vector<Eigen::Vector3d>& corners, double nx, double ny) {
  EXPECT_EQ(corners.size(), 4u);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(nx, 0, 0), Eigen::Vector3d(nx, ny, 0),
                                   Eigen::Vector3d(0, ny, 0)}) {
    EXPECT_EQ(count_near(corners, p), 1) << p.transpose();
  }
}

TEST(LoopCorners, ARectangleHasFour) {
  for (const double spacing : {0.5, 1.0, 2.0}) {
    SCOPED_TRACE(spacing);
    expect_rectangle_corners(corner_points(rectangle(8, 4), spacing), 8, 4);
  }
}

TEST(LoopCorners, FacesWoundAgainstTheirNeighboursChangeNothing) {
  // The walk runs the flipped cell's boundary edges against their faces:
  // taken the faces' way they made false slit ends (two chords back along
  // one edge) on straight sides.
  expect_rectangle_corners(corner_points(rectangle(4, 1, 2, 0), 0.5), 4, 1);
  expect_rectangle_corners(corner_points(rectangle(8, 4, 0, 0), 1.0), 8, 4);
}

TEST(LoopCorners, AtMostTheLimitSharpestFirstAndASpacingApart) {
  EXPECT_EQ(corner_points(rectangle(8, 4), 1.0, 3).size(), 3u);
  // The short sides' two corners are 1 apart, less than a spacing of 2:
  // one of each pair is kept.
  const std::vector<Eigen::Vector3d> corners = corner_points(rectangle(8, 1), 2.0);
  ASSERT_EQ(corners.size(), 2u);
  EXPECT_EQ(count_near(corners, {0, 0, 0}) + count_near(corners, {0, 1, 0}), 1);
  EXPECT_EQ(count_near(corners, {8, 0, 0}) + count_near(corners, {8, 1, 0}), 1);
}

TEST(LoopCorners, ASlitHasItsEndAndTheTwoCornersOfItsMouth) {
  const std::vector<Eigen::Vector3d> corners = corner_points(test::slit_square(16), 0.1);
  EXPECT_EQ(corners.size(), 7u);
  EXPECT_EQ(count_near(corners, {0.5, 0.5, 0}), 1);
  EXPECT_EQ(count_near(corners, {0, 0.5, 0}), 2);  // one on each side of the slit
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0),
                                   Eigen::Vector3d(0, 1, 0)}) {
    EXPECT_EQ(count_near(corners, p), 1) << p.transpose();
  }
}

TEST(LoopCorners, SmoothLoopsHaveNone) {
  // A disk's rim of 64 edges bends by 5.6 degrees an edge; the chords over a
  // spacing turn by at most 60 degrees however small the loop is against it
  // (r is at most a sixth of the loop).
  for (const double spacing : {0.05, 0.3, 1.0, 10.0}) {
    SCOPED_TRACE(spacing);
    EXPECT_TRUE(corner_points(test::disk(8, 64), spacing).empty());
  }
  // A Möbius strip's edge, walked partly against its faces.
  EXPECT_TRUE(corner_points(moebius(96, 0.2), 0.2).empty());
}

TEST(LoopCorners, TheWalkFollowsTheEdgesItRunsBackwards) {
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

}  // namespace
}  // namespace geodual::remesh::detail
