// The smoothing of a remesh's worst triangles (angle_smoothing.hpp): on a
// plane a grid with one vertex pushed aside gets it back to a good place, on
// a sphere the vertex moved stays on the surface, and what must stay (fixed,
// at a vertex of the surface, on the remesh's boundary) stays.

#include "remesh/analytic_surfaces.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/triangle_distance.hpp"
#include "geodual/mesh/triangle_shape.hpp"
#include "geodual/remesh/angle_smoothing.hpp"
#include "geodual/remesh/deviation_fitting.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

namespace geodual {
namespace {

double smallest_angle_degrees(const TriangleMesh& mesh) {
  double smallest = 180;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const TriangleShape shape = triangle_shape(mesh.vertices.row(mesh.faces(f, 0)), mesh.vertices.row(mesh.faces(f, 1)),
                                               mesh.vertices.row(mesh.faces(f, 2)));
    smallest = std::min(smallest, shape.min_angle() * 180 / std::numbers::pi);
  }
  return smallest;
}

/// The face point of `surface` (a flat mesh in z = 0) at (x, y), by search.
SurfacePoint point_on_plane(const TriangleMesh& surface, double x, double y) {
  for (Index f = 0; f < surface.num_faces(); ++f) {
    const Eigen::Vector2d a = surface.vertices.row(surface.faces(f, 0)).head<2>();
    const Eigen::Vector2d b = surface.vertices.row(surface.faces(f, 1)).head<2>();
    const Eigen::Vector2d c = surface.vertices.row(surface.faces(f, 2)).head<2>();
    const Eigen::Vector2d p(x, y);
    auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
    const double area = cross(b - a, c - a);
    const double wa = cross(b - p, c - p) / area, wb = cross(c - p, a - p) / area, wc = 1 - wa - wb;
    if (wa >= 0 && wb >= 0 && wc >= 0) return SurfacePoint::in_face(f, wa, wb, wc);
  }
  ADD_FAILURE() << "no face holds (" << x << ", " << y << ")";
  return {};
}

/// A remesh of part of the unit square: an n x n grid of cells over
/// [margin, 1 - margin]^2, two triangles each, its vertices at face points of
/// `surface`.
struct PlanarRemesh {
  TriangleMesh mesh;
  std::vector<SurfacePoint> points;
};

PlanarRemesh planar_grid(const TriangleMesh& surface, int n, double margin = 0.1) {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<Index, 3>> faces;
  PlanarRemesh remesh;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      // Off the surface's grid lines, so that each point lies inside one face.
      const double x = margin + (1 - 2 * margin) * i / n + 1e-3, y = margin + (1 - 2 * margin) * j / n + 2e-3;
      vertices.emplace_back(x, y, 0);
      remesh.points.push_back(point_on_plane(surface, x, y));
    }
  }
  const auto at = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  remesh.mesh = test::mesh_from_lists(vertices, faces);
  return remesh;
}

/// The largest distance from `mesh` of the roof ridge's points (y = 0.5, z =
/// `height`) with x in [from, to], at 101 points.
double ridge_gap(const TriangleMesh& mesh, double height, double from, double to) {
  double worst = 0;
  for (int i = 0; i <= 100; ++i) {
    const Eigen::Vector3d q(from + (to - from) * i / 100, 0.5, height);
    double nearest = std::numeric_limits<double>::infinity();
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      nearest = std::min(nearest, squared_distance_to_triangle(q, mesh.vertices.row(mesh.faces(f, 0)),
                                                               mesh.vertices.row(mesh.faces(f, 1)),
                                                               mesh.vertices.row(mesh.faces(f, 2))));
    }
    worst = std::max(worst, std::sqrt(nearest));
  }
  return worst;
}

/// Moves remesh vertex v to the face point of the plane at (x, y).
void put_vertex(const TriangleMesh& surface, PlanarRemesh& remesh, Index v, double x, double y) {
  remesh.points[static_cast<std::size_t>(v)] = point_on_plane(surface, x, y);
  remesh.mesh.vertices.row(v) = remesh.points[static_cast<std::size_t>(v)].position(surface).transpose();
}

TEST(AngleSmoothing, AVertexPushedAsideOnAPlaneGoesBackToGoodAngles) {
  const TriangleMesh surface = test::unit_square(16);
  const voronoi::GeodesicSurface prepared(surface);
  PlanarRemesh remesh = planar_grid(surface, 6);
  const Index v = 3 * 7 + 3;  // the centre, (i, j) = (3, 3): its cells are 0.8 / 6 wide
  put_vertex(surface, remesh, v, 0.5 + 0.06, 0.5 + 0.025);
  const TriangleMesh before = remesh.mesh;
  ASSERT_LT(smallest_angle_degrees(before), 25);

  const remesh::AngleSmoothingResult result =
      remesh::smooth_smallest_angles(surface, *prepared.topology(), remesh.mesh, remesh.points);
  EXPECT_GE(result.vertices_moved, 1);
  EXPECT_NEAR(result.min_angle_before, smallest_angle_degrees(before), 1e-12);
  EXPECT_NEAR(result.min_angle_after, smallest_angle_degrees(remesh.mesh), 1e-12);
  // The grid's own angles (45 degrees) are within reach: well above the bound.
  EXPECT_GE(result.min_angle_after, 40);
  EXPECT_EQ(remesh.mesh.faces, before.faces);  // the connectivity stays
  for (Index u = 0; u < remesh.mesh.num_vertices(); ++u) {
    // Each vertex where its point is, on the plane; the grid's boundary where it was.
    const Eigen::Vector3d x = remesh.mesh.vertices.row(u);
    EXPECT_LT((x - remesh.points[static_cast<std::size_t>(u)].position(surface)).norm(), 1e-15);
    EXPECT_EQ(x.z(), 0);
    const int i = u % 7, j = u / 7;
    if (i == 0 || j == 0 || i == 6 || j == 6) {
      EXPECT_EQ(x, Eigen::Vector3d(before.vertices.row(u))) << "boundary vertex " << u;
    }
  }
  // No triangle turned over: all still face +z.
  for (Index f = 0; f < remesh.mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = remesh.mesh.vertices.row(remesh.mesh.faces(f, 0));
    const Eigen::Vector3d b = remesh.mesh.vertices.row(remesh.mesh.faces(f, 1));
    const Eigen::Vector3d c = remesh.mesh.vertices.row(remesh.mesh.faces(f, 2));
    EXPECT_GT((b - a).cross(c - a).z(), 0) << "face " << f;
  }
}

TEST(AngleSmoothing, FixedVerticesAndVerticesAtSurfaceVerticesStay) {
  const TriangleMesh surface = test::unit_square(16);
  const voronoi::GeodesicSurface prepared(surface);
  PlanarRemesh remesh = planar_grid(surface, 6);
  const Index v = 3 * 7 + 3;
  put_vertex(surface, remesh, v, 0.5 + 0.06, 0.5 + 0.025);
  // The pushed vertex's neighbours, which could mend its triangles too, are
  // fixed; the vertex itself is fixed, then at a vertex of the surface.
  std::vector<std::uint8_t> fixed(static_cast<std::size_t>(remesh.mesh.num_vertices()), 0);
  for (Index f = 0; f < remesh.mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (remesh.mesh.faces(f, k) != v) continue;
      for (int m = 0; m < 3; ++m) fixed[static_cast<std::size_t>(remesh.mesh.faces(f, m))] = 1;
    }
  }
  const TriangleMesh before = remesh.mesh;
  const remesh::AngleSmoothingResult held =
      remesh::smooth_smallest_angles(surface, *prepared.topology(), remesh.mesh, remesh.points, fixed);
  EXPECT_EQ(held.vertices_moved, 0);
  EXPECT_EQ(remesh.mesh.vertices, before.vertices);
  EXPECT_EQ(held.min_angle_after, held.min_angle_before);

  fixed[static_cast<std::size_t>(v)] = 0;
  // At a vertex of the surface: (9, 8) of the 16 x 16 grid, x = 9/16, y = 1/2.
  const Index corner = 8 * 17 + 9;
  ASSERT_LT((Eigen::Vector3d(surface.vertices.row(corner)) - Eigen::Vector3d(9.0 / 16, 0.5, 0)).norm(), 1e-15);
  remesh.points[static_cast<std::size_t>(v)] = SurfacePoint::at_vertex(corner);
  remesh.mesh.vertices.row(v) = surface.vertices.row(corner);
  const TriangleMesh at_corner = remesh.mesh;
  const remesh::AngleSmoothingResult stayed =
      remesh::smooth_smallest_angles(surface, *prepared.topology(), remesh.mesh, remesh.points, fixed);
  EXPECT_EQ(stayed.vertices_moved, 0);
  EXPECT_EQ(remesh.mesh.vertices, at_corner.vertices);
  // Unfixed, off the surface's vertices, it moves.
  put_vertex(surface, remesh, v, 0.5 + 0.06, 0.5 + 0.025);
  const remesh::AngleSmoothingResult moved =
      remesh::smooth_smallest_angles(surface, *prepared.topology(), remesh.mesh, remesh.points, fixed);
  EXPECT_EQ(moved.vertices_moved, 1);
  EXPECT_GT(moved.min_angle_after, moved.min_angle_before);
}

TEST(AngleSmoothing, AVertexMovedOnASphereStaysOnItsSurface) {
  // The surface: a fine icosphere. The remesh: a coarse one, whose vertices
  // are vertices of the fine one, one of them walked a third of an edge
  // aside onto a face point of the fine one.
  const TriangleMesh surface = test::icosphere(4);
  const voronoi::GeodesicSurface prepared(surface);
  TriangleMesh remesh = test::icosphere(2);
  std::vector<SurfacePoint> points(static_cast<std::size_t>(remesh.num_vertices()));
  for (Index v = 0; v < remesh.num_vertices(); ++v) {
    // Subdivision keeps the coarse vertices first, at the same places.
    ASSERT_LT((remesh.vertices.row(v) - surface.vertices.row(v)).norm(), 1e-12);
    points[static_cast<std::size_t>(v)] = SurfacePoint::at_vertex(v);
  }
  const Index v = 20;
  // A fine face a third of a coarse edge away from v: the one whose centroid
  // is nearest to v's position pushed towards its first neighbour.
  Index neighbour = -1;
  for (Index f = 0; f < remesh.num_faces() && neighbour < 0; ++f) {
    for (int k = 0; k < 3; ++k) {
      if (remesh.faces(f, k) == v) neighbour = remesh.faces(f, (k + 1) % 3);
    }
  }
  const Eigen::Vector3d target =
      (2 * Eigen::Vector3d(remesh.vertices.row(v)) + remesh.vertices.row(neighbour).transpose()) / 3;
  Index nearest = 0;
  double best = std::numeric_limits<double>::infinity();
  for (Index f = 0; f < surface.num_faces(); ++f) {
    const Eigen::Vector3d centroid =
        (surface.vertices.row(surface.faces(f, 0)) + surface.vertices.row(surface.faces(f, 1)) +
         surface.vertices.row(surface.faces(f, 2)))
            .transpose() /
        3;
    if ((centroid - target).norm() < best) best = (centroid - target).norm(), nearest = f;
  }
  points[static_cast<std::size_t>(v)] = SurfacePoint::in_face(nearest, 0.3, 0.3, 0.4);
  remesh.vertices.row(v) = points[static_cast<std::size_t>(v)].position(surface).transpose();
  const TriangleMesh before = remesh;
  const remesh::AngleSmoothingResult result =
      remesh::smooth_smallest_angles(surface, *prepared.topology(), remesh, points, {}, {.min_angle = 45});
  ASSERT_EQ(result.vertices_moved, 1);
  EXPECT_GT(result.min_angle_after, result.min_angle_before + 5);
  for (Index u = 0; u < remesh.num_vertices(); ++u) {
    if (u != v) {
      EXPECT_EQ(Eigen::Vector3d(remesh.vertices.row(u)), Eigen::Vector3d(before.vertices.row(u)));
    }
  }
  // On the fine surface: at its point, within the fine mesh's chord error of the sphere.
  const Eigen::Vector3d x = remesh.vertices.row(v);
  EXPECT_LT((x - points[static_cast<std::size_t>(v)].position(surface)).norm(), 1e-15);
  EXPECT_LE(x.norm(), 1 + 1e-12);
  EXPECT_GT(x.norm(), 0.995);
  // Outward still: every face's normal points away from the centre.
  for (Index f = 0; f < remesh.num_faces(); ++f) {
    const Eigen::Vector3d a = remesh.vertices.row(remesh.faces(f, 0));
    const Eigen::Vector3d b = remesh.vertices.row(remesh.faces(f, 1));
    const Eigen::Vector3d c = remesh.vertices.row(remesh.faces(f, 2));
    EXPECT_GT((b - a).cross(c - a).dot(a + b + c), 0) << "face " << f;
  }
}

TEST(AngleSmoothing, AVertexOnARidgeDoesNotSlideOffIt) {
  // The surface: a roof, z = 0.3 - |y - 0.5| over the unit square, its ridge
  // along y = 0.5. The remesh: the planar grid lifted onto it, its middle
  // row on the ridge; one ridge vertex pushed along the ridge, so that its
  // triangles are poor. Sliding back along the ridge mends them; sliding
  // off it would cut the ridge, which the remesh must keep within 3 % of an
  // edge of where it was.
  TriangleMesh surface = test::unit_square(16);
  const auto roof = [](double y) { return 0.3 - std::abs(y - 0.5); };
  for (Index v = 0; v < surface.num_vertices(); ++v) surface.vertices(v, 2) = roof(surface.vertices(v, 1));
  const voronoi::GeodesicSurface prepared(surface);
  PlanarRemesh remesh = planar_grid(test::unit_square(16), 6);
  const double y_ridge = 0.5;
  for (Index v = 0; v < remesh.mesh.num_vertices(); ++v) {
    const int j = v / 7;
    if (j == 3) remesh.mesh.vertices(v, 1) = y_ridge;  // the middle row on the ridge
    remesh.points[static_cast<std::size_t>(v)] =
        point_on_plane(test::unit_square(16), remesh.mesh.vertices(v, 0), remesh.mesh.vertices(v, 1));
    remesh.mesh.vertices.row(v) = remesh.points[static_cast<std::size_t>(v)].position(surface).transpose();
  }
  const Index v = 3 * 7 + 3;
  remesh.points[static_cast<std::size_t>(v)] = point_on_plane(test::unit_square(16), 0.5 + 0.06, y_ridge);
  remesh.mesh.vertices.row(v) = remesh.points[static_cast<std::size_t>(v)].position(surface).transpose();
  const TriangleMesh before = remesh.mesh;
  ASSERT_LT(smallest_angle_degrees(before), 30);
  const remesh::AngleSmoothingResult result =
      remesh::smooth_smallest_angles(surface, *prepared.topology(), remesh.mesh, remesh.points);
  EXPECT_GE(result.vertices_moved, 1);
  EXPECT_GT(result.min_angle_after, result.min_angle_before);
  const double edge = 0.8 / 6;
  EXPECT_LE(ridge_gap(remesh.mesh, roof(y_ridge), 0.2, 0.8),
            ridge_gap(before, roof(y_ridge), 0.2, 0.8) + 0.03 * edge * 1.5);
  for (Index u = 0; u < remesh.mesh.num_vertices(); ++u) {
    const Eigen::Vector3d x = remesh.mesh.vertices.row(u);
    EXPECT_NEAR(x.z(), roof(x.y()), 1e-12) << "vertex " << u << " off the roof";
  }
}

TEST(AngleSmoothing, ARemeshWithoutSmallAnglesIsLeftAsItIs) {
  const TriangleMesh surface = test::unit_square(16);
  const voronoi::GeodesicSurface prepared(surface);
  PlanarRemesh remesh = planar_grid(surface, 6);  // 45 and 90 degrees throughout
  const TriangleMesh before = remesh.mesh;
  const remesh::AngleSmoothingResult result =
      remesh::smooth_smallest_angles(surface, *prepared.topology(), remesh.mesh, remesh.points);
  EXPECT_EQ(result.vertices_moved, 0);
  EXPECT_EQ(remesh.mesh.vertices, before.vertices);
  EXPECT_NEAR(result.min_angle_before, 45, 0.1);
  // Nor is any remesh with the bound at 0.
  put_vertex(surface, remesh, 3 * 7 + 3, 0.56, 0.525);
  const TriangleMesh pushed = remesh.mesh;
  EXPECT_EQ(
      remesh::smooth_smallest_angles(surface, *prepared.topology(), remesh.mesh, remesh.points, {}, {.min_angle = 0})
          .vertices_moved,
      0);
  EXPECT_EQ(remesh.mesh.vertices, pushed.vertices);
}

TEST(AngleSmoothing, OptionsOutOfRangeAreUsageErrors) {
  const TriangleMesh surface = test::unit_square(4);
  const voronoi::GeodesicSurface prepared(surface);
  PlanarRemesh remesh = planar_grid(surface, 2);
  const auto smooth = [&](remesh::AngleSmoothingOptions options) {
    remesh::smooth_smallest_angles(surface, *prepared.topology(), remesh.mesh, remesh.points, {}, options);
  };
  EXPECT_THROW(smooth({.min_angle = 61}), UsageError);
  EXPECT_THROW(smooth({.min_angle = -1}), UsageError);
  EXPECT_THROW(smooth({.min_angle = std::numeric_limits<double>::quiet_NaN()}), UsageError);
  EXPECT_THROW(smooth({.rounds = -1}), UsageError);
  EXPECT_THROW(smooth({.max_move = std::numeric_limits<double>::infinity()}), UsageError);
  remesh.points.pop_back();
  EXPECT_THROW(smooth({}), UsageError);
}

/// The roof z = 0.3 - |y - 0.5| over the unit square (its ridge along y =
/// 0.5), and a planar grid over nearly all of it lifted onto it, its middle
/// row at y = 0.56: the triangles between the rows at y = 0.34 and 0.56 cut
/// the ridge off.
struct RoofCase {
  TriangleMesh surface;
  PlanarRemesh remesh;
  static double roof(double y) { return 0.3 - std::abs(y - 0.5); }
  /// The largest distance of the ridge's points under the remesh from it.
  double ridge_gap() const { return geodual::ridge_gap(remesh.mesh, roof(0.5), 0.25, 0.75); }
};

RoofCase roof_case() {
  RoofCase c{test::unit_square(16), planar_grid(test::unit_square(16), 6, 0.002)};
  for (Index v = 0; v < c.surface.num_vertices(); ++v)
    c.surface.vertices(v, 2) = RoofCase::roof(c.surface.vertices(v, 1));
  for (Index v = 0; v < c.remesh.mesh.num_vertices(); ++v) {
    if (v / 7 == 3) c.remesh.mesh.vertices(v, 1) = 0.56;
    // A vertex of the boundary on a flat side pushed in, so that the
    // remesh's worst triangles (Q 0.50, no angle below 31 degrees: the floor
    // of the moves' Q) are there.
    if (v == 44) c.remesh.mesh.vertices.row(v) += Eigen::RowVector3d(0.01, -0.045, 0);
    c.remesh.points[static_cast<std::size_t>(v)] =
        point_on_plane(test::unit_square(16), c.remesh.mesh.vertices(v, 0), c.remesh.mesh.vertices(v, 1));
    c.remesh.mesh.vertices.row(v) = c.remesh.points[static_cast<std::size_t>(v)].position(c.surface).transpose();
  }
  return c;
}

double worst_q(const TriangleMesh& mesh) {
  double worst = 1;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    worst = std::min(worst, triangle_shape(mesh.vertices.row(mesh.faces(f, 0)), mesh.vertices.row(mesh.faces(f, 1)),
                                           mesh.vertices.row(mesh.faces(f, 2)))
                                .q);
  }
  return worst;
}

TEST(DeviationFitting, VerticesBesideARidgeMoveOntoItWithinTheQualityFloors) {
  RoofCase c = roof_case();
  const voronoi::GeodesicSurface prepared(c.surface);
  const TriangleMesh before = c.remesh.mesh;
  const double gap_before = c.ridge_gap();
  ASSERT_GT(gap_before, 0.02);  // the chord from y = 0.37 to 0.56 passes under the ridge
  const remesh::DeviationFittingResult result =
      remesh::fit_deviations(c.surface, *prepared.topology(), c.remesh.mesh, c.remesh.points);
  EXPECT_GE(result.vertices_moved, 1);
  EXPECT_LT(result.deviation_after, result.deviation_before);
  EXPECT_LT(c.ridge_gap(), 0.5 * gap_before);
  EXPECT_GE(smallest_angle_degrees(c.remesh.mesh), std::min(30.0, smallest_angle_degrees(before)) - 1e-9);
  EXPECT_GE(worst_q(c.remesh.mesh), worst_q(before) - 1e-12);
  for (Index u = 0; u < c.remesh.mesh.num_vertices(); ++u) {
    const Eigen::Vector3d x = c.remesh.mesh.vertices.row(u);
    EXPECT_NEAR(x.z(), RoofCase::roof(x.y()), 1e-12) << "vertex " << u << " off the roof";
    EXPECT_TRUE(x.isApprox(c.remesh.points[static_cast<std::size_t>(u)].position(c.surface), 1e-12));
  }
  // The remesh's boundary stays.
  for (const Index u : {Index{0}, Index{6}, Index{42}, Index{48}}) {
    EXPECT_EQ(c.remesh.mesh.vertices.row(u), before.vertices.row(u));
  }
}

TEST(DeviationFitting, MovesKeepToTheShapeOfTheTrianglesTheAngleSmoothingLeavesAlone) {
  RoofCase c = roof_case();
  // A sliver on a flat side, far from the ridge: the remesh's worst triangle,
  // which the angle smoothing would mend, is no floor for the moves.
  const Index pushed = 40;
  c.remesh.points[pushed] = point_on_plane(test::unit_square(16), c.remesh.mesh.vertices(pushed, 0) + 0.12,
                                           c.remesh.mesh.vertices(pushed, 1) + 0.1);
  c.remesh.mesh.vertices.row(pushed) = c.remesh.points[pushed].position(c.surface).transpose();
  const voronoi::GeodesicSurface prepared(c.surface);
  const TriangleMesh before = c.remesh.mesh;
  const auto shape = [](const TriangleMesh& mesh, Index f) {
    return triangle_shape(mesh.vertices.row(mesh.faces(f, 0)), mesh.vertices.row(mesh.faces(f, 1)),
                          mesh.vertices.row(mesh.faces(f, 2)));
  };
  double kept_worst_q = 1;  // of the triangles with no angle below 30 degrees
  for (Index f = 0; f < before.num_faces(); ++f) {
    const TriangleShape t = shape(before, f);
    if (t.min_angle() * 180 / std::numbers::pi >= 30) kept_worst_q = std::min(kept_worst_q, t.q);
  }
  ASSERT_LT(smallest_angle_degrees(before), 20);
  ASSERT_LT(worst_q(before), kept_worst_q - 0.1);
  const remesh::DeviationFittingResult result =
      remesh::fit_deviations(c.surface, *prepared.topology(), c.remesh.mesh, c.remesh.points);
  ASSERT_GE(result.vertices_moved, 1);
  // Of the triangles the moves changed: none worse than the worst kept one
  // or than the worst of them was, and no angle below 30 degrees or below
  // the smallest of theirs.
  double q_before = 1, q_after = 1, angle_before = 180, angle_after = 180;
  for (Index f = 0; f < before.num_faces(); ++f) {
    bool changed = false;
    for (int k = 0; k < 3; ++k)
      changed = changed || before.vertices.row(before.faces(f, k)) != c.remesh.mesh.vertices.row(before.faces(f, k));
    if (!changed) continue;
    q_before = std::min(q_before, shape(before, f).q);
    q_after = std::min(q_after, shape(c.remesh.mesh, f).q);
    angle_before = std::min(angle_before, shape(before, f).min_angle() * 180 / std::numbers::pi);
    angle_after = std::min(angle_after, shape(c.remesh.mesh, f).min_angle() * 180 / std::numbers::pi);
  }
  EXPECT_GE(q_after, std::min(q_before, kept_worst_q) - 1e-12);
  EXPECT_GE(angle_after, std::min(angle_before, 30.0) - 1e-9);
  EXPECT_LT(result.deviation_after, result.deviation_before);
}

/// By brute force: the largest distance from any triangle of `remesh` of the
/// vertices of `surface`'s faces and of its face centres.
double largest_distance_of_corners_and_centres(const TriangleMesh& surface, const TriangleMesh& remesh) {
  const auto from_remesh = [&](const Eigen::Vector3d& x) {
    double closest = std::numeric_limits<double>::infinity();
    for (Index f = 0; f < remesh.num_faces(); ++f) {
      closest = std::min(closest, squared_distance_to_triangle(x, remesh.vertices.row(remesh.faces(f, 0)),
                                                               remesh.vertices.row(remesh.faces(f, 1)),
                                                               remesh.vertices.row(remesh.faces(f, 2))));
    }
    return std::sqrt(closest);
  };
  double largest = 0;
  for (Index f = 0; f < surface.num_faces(); ++f) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d corner = surface.vertices.row(surface.faces(f, k));
      largest = std::max(largest, from_remesh(corner));
      centre += corner / 3;
    }
    largest = std::max(largest, from_remesh(centre));
  }
  return largest;
}

TEST(DeviationFitting, TheDistancesReportedAreTheExactOnesAndLeaveOutUnreferencedVertices) {
  RoofCase c = roof_case();
  // A scan's stray vertex, in no face, a little above the roof beside a remesh vertex.
  c.surface.vertices.conservativeResize(c.surface.num_vertices() + 1, 3);
  c.surface.vertices.row(c.surface.num_vertices() - 1) = Eigen::RowVector3d(0.5, 0.334, RoofCase::roof(0.334) + 0.15);
  const voronoi::GeodesicSurface prepared(c.surface);
  // 290 surface vertices, fewer than 8 per remesh vertex (49): the face centres count too.
  const double exact_before = largest_distance_of_corners_and_centres(c.surface, c.remesh.mesh);
  ASSERT_LT(exact_before, 0.1);
  EXPECT_NEAR(remesh::fit_deviations(c.surface, *prepared.topology(), c.remesh.mesh, c.remesh.points, {}, {.rounds = 0})
                  .deviation_before,
              exact_before, 1e-12);
  const remesh::DeviationFittingResult result =
      remesh::fit_deviations(c.surface, *prepared.topology(), c.remesh.mesh, c.remesh.points);
  EXPECT_GE(result.vertices_moved, 1);
  EXPECT_NEAR(result.deviation_before, exact_before, 1e-12);
  EXPECT_NEAR(result.deviation_after, largest_distance_of_corners_and_centres(c.surface, c.remesh.mesh), 1e-12);
  EXPECT_LT(result.deviation_after, exact_before);
}

TEST(DeviationFitting, FixedVerticesStayAndARemeshOnTheSurfaceIsLeftAsItIs) {
  RoofCase c = roof_case();
  const voronoi::GeodesicSurface prepared(c.surface);
  const TriangleMesh before = c.remesh.mesh;
  const std::vector<std::uint8_t> all(static_cast<std::size_t>(before.num_vertices()), 1);
  EXPECT_EQ(remesh::fit_deviations(c.surface, *prepared.topology(), c.remesh.mesh, c.remesh.points, all).vertices_moved,
            0);
  EXPECT_EQ(c.remesh.mesh.vertices, before.vertices);
  // A grid on a plane lies on it: nothing is farther than rounding.
  const TriangleMesh plane = test::unit_square(16);
  const voronoi::GeodesicSurface flat(plane);
  PlanarRemesh grid = planar_grid(plane, 6, 0.002);
  const TriangleMesh grid_before = grid.mesh;
  const remesh::DeviationFittingResult result = remesh::fit_deviations(plane, *flat.topology(), grid.mesh, grid.points);
  EXPECT_EQ(result.vertices_moved, 0);
  EXPECT_LT(result.deviation_before, 0.01);  // the strip round the grid that it leaves uncovered
  EXPECT_EQ(grid.mesh.vertices, grid_before.vertices);
}

TEST(DeviationFitting, OptionsOutOfRangeAreUsageErrors) {
  const TriangleMesh surface = test::unit_square(4);
  const voronoi::GeodesicSurface prepared(surface);
  PlanarRemesh remesh = planar_grid(surface, 2);
  const auto fit = [&](remesh::DeviationFittingOptions options) {
    remesh::fit_deviations(surface, *prepared.topology(), remesh.mesh, remesh.points, {}, options);
  };
  EXPECT_THROW(fit({.share = 1}), UsageError);
  EXPECT_THROW(fit({.share = -0.1}), UsageError);
  EXPECT_THROW(fit({.rounds = -1}), UsageError);
  EXPECT_THROW(fit({.reach = 0}), UsageError);
  EXPECT_THROW(fit({.min_angle = 61}), UsageError);
  EXPECT_THROW(fit({.max_q_loss = std::numeric_limits<double>::quiet_NaN()}), UsageError);
  EXPECT_THROW(fit({.max_move = std::numeric_limits<double>::infinity()}), UsageError);
  remesh.points.pop_back();
  EXPECT_THROW(fit({}), UsageError);
}

}  // namespace
}  // namespace geodual
