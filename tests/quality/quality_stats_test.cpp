// Quality statistics and mesh distances against closed forms and independent
// oracles: hand-built triangles (Heron's formula), the regular icosahedron, a
// torus and a plane grid, nested convex shapes (Hausdorff exact at a vertex),
// a brute-force point-to-triangle distance (CGAL's), and the real bunny scan
// against the data set manifest.

#include "remesh/analytic_surfaces.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/quality/quality_stats.hpp"

#include <CGAL/Simple_cartesian.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace geodual::quality {
namespace {

using Vec = Eigen::Vector3d;

TriangleMesh make_mesh(const std::vector<Vec>& points, const std::vector<std::array<Index, 3>>& faces) {
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) mesh.vertices.row(static_cast<Eigen::Index>(i)) = points[i];
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) mesh.faces(static_cast<Eigen::Index>(f), k) = faces[f][k];
  }
  return mesh;
}

TriangleMesh transformed(TriangleMesh mesh, double scale, const Vec& centre, const Vec& shift) {
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    const Vec p = mesh.vertices.row(v);
    mesh.vertices.row(v) = centre + scale * (p - centre) + shift;
  }
  return mesh;
}

/// Regular icosahedron with edge 2 (vertices (0, +-1, +-phi) cyclically), faces
/// found as the triples of mutually adjacent vertices, oriented outwards.
TriangleMesh icosahedron() {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec> p;
  for (const double a : {-1.0, 1.0}) {
    for (const double b : {-phi, phi}) {
      p.emplace_back(0, a, b);
      p.emplace_back(a, b, 0);
      p.emplace_back(b, 0, a);
    }
  }
  const auto adjacent = [&](std::size_t i, std::size_t j) { return std::abs((p[i] - p[j]).norm() - 2.0) < 1e-9; };
  std::vector<std::array<Index, 3>> faces;
  for (std::size_t i = 0; i < 12; ++i) {
    for (std::size_t j = i + 1; j < 12; ++j) {
      for (std::size_t k = j + 1; k < 12; ++k) {
        if (!adjacent(i, j) || !adjacent(j, k) || !adjacent(i, k)) continue;
        const bool outward = (p[j] - p[i]).cross(p[k] - p[i]).dot(p[i] + p[j] + p[k]) > 0;
        faces.push_back(outward ? std::array<Index, 3>{Index(i), Index(j), Index(k)}
                                : std::array<Index, 3>{Index(i), Index(k), Index(j)});
      }
    }
  }
  return make_mesh(p, faces);
}

/// An n x n grid of squares on the plane spanned by u and v (from the
/// origin, side 1), each square split by the same diagonal.
TriangleMesh plane_grid(int n, const Vec& u = Vec::UnitX(), const Vec& v = Vec::UnitY()) {
  std::vector<Vec> points;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) points.push_back(u * i / n + v * j / n);
  }
  std::vector<std::array<Index, 3>> faces;
  const auto id = [n](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return make_mesh(points, faces);
}

/// A torus as an n x m periodic grid, each quad split by the same diagonal:
/// every vertex has valence 6.
TriangleMesh torus(int n, int m) {
  std::vector<Vec> points;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n, b = 2 * std::numbers::pi * j / m;
      points.emplace_back((2 + std::cos(b)) * std::cos(a), (2 + std::cos(b)) * std::sin(a), std::sin(b));
    }
  }
  std::vector<std::array<Index, 3>> faces;
  const auto id = [n, m](int i, int j) { return static_cast<Index>((j % m) * n + (i % n)); };
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return make_mesh(points, faces);
}

/// Both meshes as one (two components).
TriangleMesh combined(const TriangleMesh& first, const TriangleMesh& second) {
  TriangleMesh mesh;
  mesh.vertices.resize(first.vertices.rows() + second.vertices.rows(), 3);
  mesh.vertices << first.vertices, second.vertices;
  mesh.faces.resize(first.faces.rows() + second.faces.rows(), 3);
  mesh.faces << first.faces, (second.faces.array() + first.num_vertices()).matrix();
  return mesh;
}

/// The unit cube [0, 1]^3, faces counter-clockwise seen from outside.
TriangleMesh unit_cube() {
  std::vector<Vec> p;
  for (int k = 0; k < 8; ++k) p.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  const std::vector<std::array<Index, 3>> faces = {
      {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},  // z = 0, z = 1
      {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},  // y = 0, y = 1
      {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5},  // x = 0, x = 1
  };
  return make_mesh(p, faces);
}

/// Q from Heron's formula, independently of the library's cross product.
double heron_quality(double a, double b, double c) {
  const double s = (a + b + c) / 2;
  const double area = std::sqrt(s * (s - a) * (s - b) * (s - c));
  return 6 / std::sqrt(3.0) * area / (s * std::max({a, b, c}));
}

/// Distance from p to the nearest triangle, by CGAL's point-triangle distance
/// over every triangle (the library uses its own, through an AABB tree).
double brute_distance(const Vec& p, const TriangleMesh& mesh) {
  using Kernel = CGAL::Simple_cartesian<double>;
  const auto point = [](const Vec& v) { return Kernel::Point_3(v.x(), v.y(), v.z()); };
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Kernel::Triangle_3 triangle(point(mesh.vertices.row(mesh.faces(f, 0))),
                                      point(mesh.vertices.row(mesh.faces(f, 1))),
                                      point(mesh.vertices.row(mesh.faces(f, 2))));
    best = std::min(best, CGAL::squared_distance(point(p), triangle));
  }
  return std::sqrt(best);
}

QualityOptions samples(std::int64_t count, std::uint64_t seed = 1) {
  QualityOptions options;
  options.samples_per_side = count;
  options.seed = seed;
  return options;
}

// ---------------------------------------------------------------- elements

TEST(TriangleQuality, EquilateralTriangle) {
  const double side = 3.0;
  const TriangleMesh mesh =
      make_mesh({Vec(0, 0, 0), Vec(side, 0, 0), Vec(side / 2, side * std::sqrt(3.0) / 2, 0)}, {{0, 1, 2}});
  const TriangleQuality q = triangle_quality(mesh);
  EXPECT_NEAR(q.q_min, 1.0, 1e-14);
  EXPECT_NEAR(q.q_avg, 1.0, 1e-14);
  EXPECT_NEAR(q.theta_min_deg, 60.0, 1e-12);
  EXPECT_NEAR(q.theta_min_avg_deg, 60.0, 1e-12);
  EXPECT_EQ(q.pct_angles_lt30, 0.0);
  EXPECT_EQ(q.p30, 0.0);
  EXPECT_NEAR(q.area, std::sqrt(3.0) / 4 * side * side, 1e-12);
  EXPECT_EQ(q.degenerate_faces, 0);
  EXPECT_EQ(q.boundary_loops, 1);
  EXPECT_EQ(q.euler_characteristic, 1);
  EXPECT_EQ(q.interior_vertices, 0);
  EXPECT_FALSE(q.pct_valence6.has_value());
}

TEST(TriangleQuality, RightIsoscelesAndThinTriangles) {
  // Right isosceles: angles 45, 45, 90 and Q = sqrt(3) (sqrt(2) - 1).
  const TriangleMesh right = make_mesh({Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0)}, {{0, 1, 2}});
  const TriangleQuality q = triangle_quality(right);
  EXPECT_NEAR(q.q_min, std::sqrt(3.0) * (std::sqrt(2.0) - 1), 1e-14);
  EXPECT_NEAR(q.q_min, heron_quality(1, 1, std::sqrt(2.0)), 1e-14);
  EXPECT_NEAR(q.theta_min_deg, 45.0, 1e-12);
  EXPECT_EQ(q.pct_angles_lt30, 0.0);

  // Beside it, a thin right triangle with legs 1 and 0.2: one angle of
  // atan(0.2) = 11.31 degrees. One angle in six is below 30 degrees, and one
  // face in two, so P30 = 100 * 1 / (3 * 2).
  const TriangleMesh both = make_mesh(
      {Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), Vec(5, 0, 1), Vec(6, 0, 1), Vec(5, 0, 1.2)}, {{0, 1, 2}, {3, 4, 5}});
  const TriangleQuality q2 = triangle_quality(both);
  const double thin_q = heron_quality(1, 0.2, std::sqrt(1.04));
  EXPECT_NEAR(q2.q_min, thin_q, 1e-14);
  EXPECT_NEAR(q2.q_avg, (thin_q + heron_quality(1, 1, std::sqrt(2.0))) / 2, 1e-14);
  EXPECT_NEAR(q2.theta_min_deg, std::atan(0.2) * 180 / std::numbers::pi, 1e-12);
  EXPECT_NEAR(q2.theta_min_avg_deg, (45 + std::atan(0.2) * 180 / std::numbers::pi) / 2, 1e-12);
  EXPECT_NEAR(q2.pct_angles_lt30, 100.0 / 6, 1e-12);
  EXPECT_NEAR(q2.p30, 100.0 / 6, 1e-12);
  EXPECT_NEAR(q2.area, 0.5 + 0.1, 1e-14);
  EXPECT_EQ(q2.components, 2);
}

TEST(TriangleQuality, DegenerateFacesCountAsZero) {
  // An equilateral triangle, a face with a repeated index, and a face of three
  // collinear points: the last two have Q = 0 and angles (0, 0, 180).
  const double h = std::sqrt(3.0) / 2;
  const TriangleMesh mesh =
      make_mesh({Vec(0, 0, 0), Vec(1, 0, 0), Vec(0.5, h, 0), Vec(3, 0, 0), Vec(4, 0, 0), Vec(5, 0, 0)},
                {{0, 1, 2}, {3, 4, 4}, {3, 4, 5}});
  const TriangleQuality q = triangle_quality(mesh);
  EXPECT_EQ(q.degenerate_faces, 2);
  EXPECT_EQ(q.degenerate_faces, analyze_mesh(mesh).degenerate_faces);
  EXPECT_EQ(q.q_min, 0.0);
  EXPECT_NEAR(q.q_avg, 1.0 / 3, 1e-14);
  EXPECT_EQ(q.theta_min_deg, 0.0);
  EXPECT_NEAR(q.theta_min_avg_deg, 20.0, 1e-12);
  EXPECT_NEAR(q.pct_angles_lt30, 100.0 * 4 / 9, 1e-12);
  EXPECT_NEAR(q.p30, 100.0 * 2 / 9, 1e-12);
  EXPECT_NEAR(q.area, h / 2, 1e-15);
}

TEST(TriangleQuality, RegularIcosahedron) {
  const TriangleMesh mesh = icosahedron();
  ASSERT_EQ(mesh.num_faces(), 20);
  const TriangleQuality q = triangle_quality(mesh);
  EXPECT_NEAR(q.q_min, 1.0, 1e-12);
  EXPECT_NEAR(q.theta_min_deg, 60.0, 1e-9);
  EXPECT_EQ(q.euler_characteristic, 2);
  ASSERT_TRUE(q.genus.has_value());
  EXPECT_EQ(*q.genus, 0.0);
  EXPECT_EQ(q.boundary_loops, 0);
  EXPECT_EQ(q.nonmanifold_edges, 0);
  EXPECT_EQ(q.interior_vertices, 12);
  ASSERT_EQ(q.valence_histogram.size(), 6U);
  EXPECT_EQ(q.valence_histogram[5], 12);
  ASSERT_TRUE(q.pct_valence6.has_value());
  EXPECT_EQ(*q.pct_valence6, 0.0);
  // Edge a = 2: area 5 sqrt(3) a^2, volume 5/12 (3 + sqrt(5)) a^3.
  EXPECT_NEAR(q.area, 20 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(q.volume, 5.0 / 12 * (3 + std::sqrt(5.0)) * 8, 1e-12);
}

TEST(TriangleQuality, TorusGridIsAllValenceSix) {
  const TriangleMesh mesh = torus(16, 9);
  const TriangleQuality q = triangle_quality(mesh);
  EXPECT_EQ(q.euler_characteristic, 0);
  ASSERT_TRUE(q.genus.has_value());
  EXPECT_EQ(*q.genus, 1.0);
  EXPECT_EQ(q.boundary_loops, 0);
  EXPECT_EQ(q.interior_vertices, 16 * 9);
  ASSERT_EQ(q.valence_histogram.size(), 7U);
  EXPECT_EQ(q.valence_histogram[6], 16 * 9);
  EXPECT_EQ(q.pct_valence6.value_or(-1), 100.0);
  // Oriented outwards; inscribed in the smooth torus (R = 2, r = 1), whose
  // volume 2 pi^2 R r^2 it approaches (about 0.9 of it at this resolution).
  const double smooth = 2 * std::numbers::pi * std::numbers::pi * 2;
  EXPECT_GT(q.volume, 0.8 * smooth);
  EXPECT_LT(q.volume, smooth);
}

TEST(TriangleQuality, OpenSquareGrid) {
  const int n = 10;
  const TriangleQuality q = triangle_quality(plane_grid(n));
  EXPECT_EQ(q.boundary_loops, 1);
  EXPECT_EQ(q.euler_characteristic, 1);
  ASSERT_TRUE(q.genus.has_value());
  EXPECT_EQ(*q.genus, 0.0);
  EXPECT_EQ(q.interior_vertices, (n - 1) * (n - 1));
  EXPECT_EQ(q.pct_valence6.value_or(-1), 100.0);
  EXPECT_NEAR(q.area, 1.0, 1e-14);
  EXPECT_NEAR(q.volume, 0.0, 1e-15);  // flat: every cone from the centre is flat
  EXPECT_NEAR(q.q_min, std::sqrt(3.0) * (std::sqrt(2.0) - 1), 1e-12);
  EXPECT_NEAR(q.q_avg, q.q_min, 1e-12);
}

TEST(TriangleQuality, NonManifoldEdgeHasNoInteriorVertex) {
  // Three triangles on the edge (0, 1).
  const TriangleMesh mesh = make_mesh({Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), Vec(0, -1, 0), Vec(0, 0, 1)},
                                      {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const TriangleQuality q = triangle_quality(mesh);
  EXPECT_EQ(q.nonmanifold_edges, 1);
  EXPECT_FALSE(q.genus.has_value());
  EXPECT_EQ(q.interior_vertices, 0);
  EXPECT_FALSE(q.pct_valence6.has_value());
}

TEST(TriangleQuality, CubeVolumeFollowsOrientation) {
  TriangleMesh cube = unit_cube();
  EXPECT_NEAR(triangle_quality(cube).volume, 1.0, 1e-15);
  EXPECT_NEAR(triangle_quality(cube).area, 6.0, 1e-15);
  // Far from the origin the volume stays exact (taken from the bbox centre).
  EXPECT_NEAR(triangle_quality(transformed(cube, 1.0, Vec::Zero(), Vec(1e6, -2e6, 3e6))).volume, 1.0, 1e-9);
  cube.faces.col(1).swap(cube.faces.col(2));
  EXPECT_NEAR(triangle_quality(cube).volume, -1.0, 1e-15);
}

TEST(TriangleQuality, BadMeshesAreErrors) {
  EXPECT_THROW(triangle_quality(TriangleMesh{}), Error);
  TriangleMesh mesh = make_mesh({Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0)}, {{0, 1, 3}});
  EXPECT_THROW(triangle_quality(mesh), Error);
  mesh.faces(0, 2) = -1;
  EXPECT_THROW(triangle_quality(mesh), Error);
  mesh.faces(0, 2) = 2;
  mesh.vertices(1, 1) = std::numeric_limits<double>::quiet_NaN();
  try {
    triangle_quality(mesh);
    FAIL() << "a NaN coordinate must be refused";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("vertex 1"), std::string::npos) << error.what();
  }
}

// ---------------------------------------------------------------- distances

TEST(CompareMeshes, MeshAgainstItselfIsZero) {
  const TriangleMesh sphere = test::icosphere(2);
  const QualityReport report = compare_meshes(sphere, sphere, samples(20000));
  EXPECT_LT(report.hausdorff, 1e-15);
  EXPECT_LT(report.rms, 1e-15);
  EXPECT_EQ(report.area_change_pct, 0.0);
  EXPECT_EQ(report.volume_change_pct.value_or(-1), 0.0);
  EXPECT_EQ(report.reference_samples, sphere.num_vertices() + 20000);
  EXPECT_EQ(report.candidate_samples, sphere.num_vertices() + 20000);
}

TEST(CompareMeshes, TranslatedPlaneIsAtTheTranslation) {
  // A tilted plane and its copy moved by t along the normal: every point of
  // either is exactly t from the other.
  const Vec u = Vec(1, 2, 2).normalized();
  const Vec v = u.cross(Vec(0, 0, 1)).normalized();
  const Vec normal = u.cross(v);
  const double t = 0.0375;
  const TriangleMesh plane = plane_grid(7, u, v);
  const TriangleMesh moved = transformed(plane, 1.0, Vec::Zero(), t * normal);
  const QualityReport report = compare_meshes(plane, moved, samples(20000));
  EXPECT_NEAR(report.hausdorff, t, 1e-9);
  EXPECT_NEAR(report.hausdorff_reference_to_candidate, t, 1e-9);
  EXPECT_NEAR(report.hausdorff_candidate_to_reference, t, 1e-9);
  EXPECT_NEAR(report.rms, t, 1e-9);
  const Vec low = plane.vertices.colwise().minCoeff(), high = plane.vertices.colwise().maxCoeff();
  EXPECT_NEAR(report.hausdorff_pct, 100 * t / (high - low).norm(), 1e-7);  // of the axis-aligned bbox
  EXPECT_NEAR(report.area_change_pct, 0.0, 1e-12);
}

TEST(CompareMeshes, ScaledSphereHausdorffIsExact) {
  // Nested convex polyhedra P and sP (circumradius 1): the farthest points are
  // the vertices of sP, at exactly s - 1 from P.
  const double s = 1.1;
  const TriangleMesh sphere = test::icosphere(2);
  const TriangleMesh larger = transformed(sphere, s, Vec::Zero(), Vec::Zero());
  const QualityReport report = compare_meshes(sphere, larger, samples(20000));
  EXPECT_NEAR(report.hausdorff, s - 1, 1e-12);
  EXPECT_NEAR(report.hausdorff_candidate_to_reference, s - 1, 1e-12);
  EXPECT_LE(report.hausdorff_reference_to_candidate, s - 1 + 1e-12);
  // Every face lies at least r_in from the centre: every distance is at least s r_in - 1.
  double r_in = 1.0;
  for (Index f = 0; f < sphere.num_faces(); ++f) {
    const Vec a = sphere.vertices.row(sphere.faces(f, 0)), b = sphere.vertices.row(sphere.faces(f, 1)),
              c = sphere.vertices.row(sphere.faces(f, 2));
    r_in = std::min(r_in, std::abs((b - a).cross(c - a).normalized().dot(a)));
  }
  EXPECT_GT(report.rms, s * r_in - 1);
  EXPECT_LT(report.rms, s - 1);
  const Vec low = sphere.vertices.colwise().minCoeff(), high = sphere.vertices.colwise().maxCoeff();
  EXPECT_NEAR(report.hausdorff_pct, 100 * (s - 1) / (high - low).norm(), 1e-10);
  EXPECT_NEAR(report.area_change_pct, 100 * (s * s - 1), 1e-10);
  EXPECT_NEAR(report.volume_change_pct.value_or(0), 100 * (s * s * s - 1), 1e-10);
}

TEST(CompareMeshes, ScaledCubeAreaVolumeAndDistances) {
  // [0, 1]^3 against the same cube doubled about its centre, [-0.5, 1.5]^3.
  const TriangleMesh cube = unit_cube();
  const TriangleMesh doubled = transformed(cube, 2.0, Vec(0.5, 0.5, 0.5), Vec::Zero());
  const QualityReport report = compare_meshes(cube, doubled, samples(5000));
  EXPECT_NEAR(report.area_change_pct, 300.0, 1e-12);
  EXPECT_NEAR(report.volume_change_pct.value_or(0), 700.0, 1e-12);
  EXPECT_NEAR(report.hausdorff_reference_to_candidate, 0.5, 1e-12);                 // every point is 0.5 inside
  EXPECT_NEAR(report.hausdorff_candidate_to_reference, std::sqrt(3.0) / 2, 1e-12);  // corner to corner
  EXPECT_NEAR(report.hausdorff, std::sqrt(3.0) / 2, 1e-12);
  EXPECT_NEAR(report.hausdorff_pct, 100 * 0.5, 1e-10);  // diagonal sqrt(3)
}

TEST(CompareMeshes, VerticesOnlyMatchBruteForce) {
  // With no samples, the figures are over the vertices alone: check them
  // against a brute-force distance to every triangle. The reference is a bumpy
  // sphere plus a grid of points above a needle triangle and an obtuse one of
  // the candidate, so that the nearest points fall on faces, edges and
  // vertices alike.
  TriangleMesh a = combined(test::icosphere(3), transformed(plane_grid(7), 2.0, Vec::Zero(), Vec(1.2, -1.0, 0.3)));
  TriangleMesh b = combined(test::icosphere(1), make_mesh({Vec(1.5, 0, 0), Vec(2.5, 0, 0), Vec(2.5, 1e-6, 0),
                                                           Vec(1.4, 0.2, 0.1), Vec(3.3, 0.4, -0.1), Vec(2.0, 0.5, 0.0)},
                                                          {{0, 1, 2}, {3, 4, 5}}));
  for (Index v = 0; v < 642; ++v) a.vertices.row(v) *= 1.0 + 0.05 * std::sin(3.0 * v);
  for (Index v = 0; v < 42; ++v) {
    b.vertices.row(v) = b.vertices.row(v) * (1.0 + 0.04 * std::cos(5.0 * v)) + Eigen::RowVector3d(0.01, -0.02, 0.03);
  }
  const QualityReport report = compare_meshes(a, b, samples(0));
  double forward = 0, backward = 0, sum = 0;
  for (Index v = 0; v < a.num_vertices(); ++v) {
    const double d = brute_distance(a.vertices.row(v), b);
    forward = std::max(forward, d);
    sum += d * d;
  }
  for (Index v = 0; v < b.num_vertices(); ++v) {
    const double d = brute_distance(b.vertices.row(v), a);
    backward = std::max(backward, d);
    sum += d * d;
  }
  EXPECT_NEAR(report.hausdorff_reference_to_candidate, forward, 1e-13);
  EXPECT_NEAR(report.hausdorff_candidate_to_reference, backward, 1e-13);
  EXPECT_NEAR(report.rms, std::sqrt(sum / (a.num_vertices() + b.num_vertices())), 1e-13);
  // Where it is reached: a vertex of the side whose maximum is larger, at
  // that distance from the other side.
  const bool forward_larger = forward >= backward;
  EXPECT_NEAR(brute_distance(report.hausdorff_point, forward_larger ? b : a), report.hausdorff, 1e-13);
  EXPECT_EQ(report.reference_samples, a.num_vertices());
  EXPECT_GT(report.hausdorff, 0.01);
}

TEST(CompareMeshes, SamplesAreAreaUniform) {
  // Reference: the unit square as a fan of four triangles of very different
  // areas (0.025, 0.05, 0.475, 0.45) around (0.9, 0.05). Candidate: its lower
  // half. A reference point at height y is max(0, y - 0.5) from the
  // candidate, so area-uniform samples have E[d^2] = 1/24, Var[d^2] = 1/160 -
  // 1/576; candidate points are on the reference (d = 0).
  const TriangleMesh square = make_mesh({Vec(0, 0, 0), Vec(1, 0, 0), Vec(1, 1, 0), Vec(0, 1, 0), Vec(0.9, 0.05, 0)},
                                        {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
  const TriangleMesh half =
      make_mesh({Vec(0, 0, 0), Vec(1, 0, 0), Vec(1, 0.5, 0), Vec(0, 0.5, 0)}, {{0, 1, 2}, {0, 2, 3}});
  const std::int64_t n = 200000;
  const QualityReport report = compare_meshes(square, half, samples(n));
  EXPECT_NEAR(report.hausdorff_reference_to_candidate, 0.5, 1e-15);  // the corners (0, 1) and (1, 1)
  EXPECT_LT(report.hausdorff_candidate_to_reference, 1e-15);
  const double points = static_cast<double>(report.reference_samples + report.candidate_samples);
  ASSERT_EQ(points, 2.0 * n + 5 + 4);
  // Squared distances of the reference's samples: all of them less the two corners'.
  const double sample_mean = (report.rms * report.rms * points - 2 * 0.25) / static_cast<double>(n);
  const double sigma = std::sqrt((1.0 / 160 - 1.0 / 576) / static_cast<double>(n));
  EXPECT_NEAR(sample_mean, 1.0 / 24, 5 * sigma);
}

TEST(CompareMeshes, DeterministicForAnyThreadCount) {
  const TriangleMesh sphere = test::icosphere(3);
  TriangleMesh bumpy = sphere;
  for (Index v = 0; v < bumpy.num_vertices(); ++v) bumpy.vertices.row(v) *= 1.0 + 0.02 * std::sin(7.0 * v);
  const QualityReport many = compare_meshes(sphere, bumpy, samples(50000, 7));
  const QualityReport again = compare_meshes(sphere, bumpy, samples(50000, 7));
  QualityReport one;
  {
    const tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = compare_meshes(sphere, bumpy, samples(50000, 7));
  }
  for (const QualityReport* other : std::array<const QualityReport*, 2>{&again, &one}) {
    EXPECT_EQ(many.hausdorff, other->hausdorff);
    EXPECT_EQ(many.hausdorff_reference_to_candidate, other->hausdorff_reference_to_candidate);
    EXPECT_EQ(many.hausdorff_candidate_to_reference, other->hausdorff_candidate_to_reference);
    EXPECT_EQ(many.rms, other->rms);
    EXPECT_EQ(many.hausdorff_point, other->hausdorff_point);
  }
  // Another seed draws other samples: the same figure up to sampling noise.
  const QualityReport reseeded = compare_meshes(sphere, bumpy, samples(50000, 8));
  EXPECT_NE(many.rms, reseeded.rms);
  EXPECT_NEAR(many.rms, reseeded.rms, 0.02 * many.rms);
}

TEST(CompareMeshes, DeviationAtVerticesLocatesTheDistanceAndPeaksAtTheHausdorff) {
  // A flat 10 x 10 grid with one vertex raised into a spike, against the flat
  // square: the distance is the spike's, on the faces around it only.
  TriangleMesh spiked = plane_grid(10);
  const Index spike = 5 * 11 + 5;
  spiked.vertices(spike, 2) = 0.3;
  const TriangleMesh flat = plane_grid(1);
  QualityOptions options = samples(20000);
  EXPECT_TRUE(compare_meshes(spiked, flat, options).deviation_at_vertices.empty());  // not asked

  options.deviation_at_vertices = true;
  const QualityReport report = compare_meshes(spiked, flat, options);
  const std::vector<double>& deviation = report.deviation_at_vertices;
  ASSERT_EQ(deviation.size(), static_cast<std::size_t>(spiked.num_vertices()));
  EXPECT_DOUBLE_EQ(deviation[spike], 0.3);
  EXPECT_DOUBLE_EQ(*std::max_element(deviation.begin(), deviation.end()), report.hausdorff);
  // It is reached at the spike's tip, a vertex of the reference.
  EXPECT_EQ(report.hausdorff_point, Eigen::Vector3d(spiked.vertices.row(spike)));
  for (Index v = 0; v < spiked.num_vertices(); ++v) {
    // The spike's one-ring (the grid's diagonals run from (i, j) to (i + 1, j + 1)).
    const Index di = v % 11 - 5, dj = v / 11 - 5;
    const bool around_spike = std::abs(di) + std::abs(dj) == 1 || (di == dj && std::abs(di) == 1);
    if (v == spike) continue;
    if (around_spike) {
      EXPECT_GT(deviation[v], 0.0) << "vertex " << v;  // its faces' samples are off the flat square
      EXPECT_LT(deviation[v], 0.3) << "vertex " << v;
    } else {
      EXPECT_LT(deviation[v], 1e-15) << "vertex " << v;  // rounding only
    }
  }
  // The other way round, the flat square's samples over the spike are
  // charged to the spike's faces; its far corners see nothing.
  const QualityReport reverse = compare_meshes(flat, spiked, options);
  ASSERT_EQ(reverse.deviation_at_vertices.size(), 4u);
  EXPECT_DOUBLE_EQ(*std::max_element(reverse.deviation_at_vertices.begin(), reverse.deviation_at_vertices.end()),
                   reverse.hausdorff);
  // The same bits on one thread.
  const tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
  EXPECT_EQ(compare_meshes(spiked, flat, options).deviation_at_vertices, deviation);
}

TEST(CompareMeshes, ProgressChangesNothingAndCancels) {
  const TriangleMesh sphere = test::icosphere(3);
  TriangleMesh bumpy = sphere;
  for (Index v = 0; v < bumpy.num_vertices(); ++v) bumpy.vertices.row(v) *= 1.0 + 0.02 * std::sin(7.0 * v);
  const QualityReport plain = compare_meshes(sphere, bumpy, samples(200000, 7));
  QualityOptions watched = samples(200000, 7);
  std::vector<double> fractions;
  watched.progress = [&fractions](double fraction) {
    fractions.push_back(fraction);
    return true;
  };
  const QualityReport reported = compare_meshes(sphere, bumpy, watched);
  EXPECT_EQ(plain.hausdorff_reference_to_candidate, reported.hausdorff_reference_to_candidate);
  EXPECT_EQ(plain.hausdorff_candidate_to_reference, reported.hausdorff_candidate_to_reference);
  EXPECT_EQ(plain.rms, reported.rms);
  // Asked every block of 4096 queries the calling thread runs (about 100 blocks).
  ASSERT_GT(fractions.size(), 20U);
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));

  // Refused once past half way: Cancelled, and never asked again.
  for (const int threads : {0, 1}) {
    QualityOptions cancelling = samples(200000, 7);
    int calls_after_refusal = 0;
    bool refused = false;
    cancelling.progress = [&](double fraction) {
      if (refused) ++calls_after_refusal;
      refused = refused || fraction >= 0.5;
      return !refused;
    };
    std::optional<tbb::global_control> single;
    if (threads == 1) single.emplace(tbb::global_control::max_allowed_parallelism, 1);
    EXPECT_THROW(compare_meshes(sphere, bumpy, cancelling), Cancelled);
    EXPECT_TRUE(refused);
    EXPECT_EQ(calls_after_refusal, 0);
  }
}

TEST(CompareMeshes, CancelsWhileBuildingATree) {
  // 2 x 120^2 = 28,800 triangles: the reference's tree build is asked many
  // times (phase 0.10 to 0.15), not only once before it starts.
  const TriangleMesh grid = plane_grid(120);
  QualityOptions cancelling = samples(1000);
  int asked_in_build = 0;
  bool asked_later = false;
  cancelling.progress = [&](double fraction) {
    if (fraction >= 0.15) asked_later = true;
    if (fraction >= 0.1 && fraction < 0.15) ++asked_in_build;
    return asked_in_build < 3;
  };
  EXPECT_THROW(compare_meshes(grid, grid, cancelling), Cancelled);
  EXPECT_EQ(asked_in_build, 3);
  EXPECT_FALSE(asked_later);
}

TEST(CompareMeshes, BadRequestsAreErrors) {
  const TriangleMesh cube = unit_cube();
  EXPECT_THROW(compare_meshes(cube, cube, samples(-1)), Error);
  EXPECT_THROW(compare_meshes(cube, cube, samples(max_samples_per_side + 1)), Error);
  const TriangleMesh flat = make_mesh({Vec(0, 0, 0), Vec(1, 0, 0), Vec(2, 0, 0)}, {{0, 1, 2}, {0, 1, 1}});
  try {
    compare_meshes(cube, flat, samples(10));
    FAIL() << "a candidate without area must be refused";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()).rfind("candidate mesh: ", 0), 0U) << error.what();
  }
  try {
    compare_meshes(TriangleMesh{}, cube, samples(10));
    FAIL() << "an empty reference must be refused";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()).rfind("reference mesh: ", 0), 0U) << error.what();
  }
}

TEST(CompareMeshes, BunnyScanAgainstItself) {
  const TriangleMesh bunny = io::read_mesh("tests/data/bunny.ply").mesh;
  const QualityReport report = compare_meshes(bunny, bunny, samples(20000));
  const TriangleQuality& q = report.candidate;
  // MANIFEST.tsv: min angle 0.4949 degrees, chi = -3, 5 boundary loops, genus 0.
  EXPECT_NEAR(q.theta_min_deg, 0.4949, 5e-5);
  EXPECT_EQ(q.euler_characteristic, -3);
  EXPECT_EQ(q.boundary_loops, 5);
  EXPECT_EQ(q.genus.value_or(-1), 0.0);
  EXPECT_EQ(q.degenerate_faces, 0);
  EXPECT_NEAR(q.bbox_diagonal, 0.250246, 1e-6);
  EXPECT_LT(q.q_min, q.q_avg);
  EXPECT_LT(q.q_avg, 1.0);
  EXPECT_LT(q.theta_min_avg_deg, 60.0);
  EXPECT_LE(q.p30, q.pct_angles_lt30);
  EXPECT_LT(q.interior_vertices, 35947 - 1113);  // boundary and unreferenced vertices are not interior
  EXPECT_LT(report.hausdorff_pct, 1e-10);
  EXPECT_LT(report.rms_pct, 1e-10);
  EXPECT_EQ(report.area_change_pct, 0.0);
  EXPECT_EQ(report.reference_samples, 35947 - 1113 + 20000);  // referenced vertices + samples
}

}  // namespace
}  // namespace geodual::quality

namespace geodual::quality {
namespace {

TEST(FaceQuality, OneForEquilateralZeroForDegenerate) {
  TriangleMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0.5, std::sqrt(3.0) / 2, 0, 2, 0, 0;
  mesh.faces.resize(3, 3);
  mesh.faces << 0, 1, 2, 0, 1, 3, 0, 0, 2;
  EXPECT_NEAR(face_quality(mesh, 0), 1.0, 1e-15);
  EXPECT_EQ(face_quality(mesh, 1), 0.0);  // collinear corners
  EXPECT_EQ(face_quality(mesh, 2), 0.0);  // a repeated index
}

}  // namespace
}  // namespace geodual::quality
