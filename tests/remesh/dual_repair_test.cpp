// dual_delaunay on valid surfaces that broke it: faces stored against their
// neighbours' orientation (the dual must follow one consistent orientation),
// and a spire thinner than the sites' spacing, which a cell can girdle
// (repair must go around it, not stack another band on it).

#include "remesh/analytic_surfaces.hpp"

#include "geodual/mesh/mesh_report.hpp"
#include "geodual/remesh/dual_delaunay.hpp"
#include "geodual/remesh/remesh.hpp"
#include "geodual/remesh/sample_sites.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace geodual {
namespace {

/// A closed box [0, 0.2]^3 with, on its top face, a `sides`-sided pyramid
/// spire of base radius `radius` and height 0.2 (genus 0, outward normals).
TriangleMesh box_with_spire(int sides, double radius) {
  constexpr double width = 0.2, height = 0.2, spire = 0.2;
  std::vector<Eigen::Vector3d> points = {
      {0, 0, 0},      {width, 0, 0},      {width, width, 0},      {0, width, 0},
      {0, 0, height}, {width, 0, height}, {width, width, height}, {0, width, height}};
  std::vector<std::array<Index, 3>> faces = {{0, 2, 1}, {0, 3, 2}};
  for (Index k = 0; k < 4; ++k) {
    const Index next = (k + 1) % 4;
    faces.push_back({k, next, 4 + next});
    faces.push_back({k, 4 + next, 4 + k});
  }
  const Eigen::Vector3d centre(width / 2, width / 2, height);
  const Index base = static_cast<Index>(points.size());
  for (int i = 0; i < sides; ++i) {
    const double angle = 2 * std::numbers::pi * i / sides;
    points.push_back(centre + radius * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0));
  }
  const Index apex = static_cast<Index>(points.size());
  points.push_back(centre + Eigen::Vector3d(0, 0, spire));
  for (Index i = 0; i < sides; ++i) faces.push_back({base + i, base + (i + 1) % sides, apex});
  // The top face's ring between the box's corners (4..7, at 225, 315, 45 and
  // 135 degrees round the centre) and the spire's base, zipped by angle.
  const std::array<Index, 4> corners = {6, 7, 4, 5};  // from 45 degrees on
  const double corner_angle[4] = {45, 135, 225, 315};
  int i = 0, k = 0;
  while (i < sides || k < 4) {
    const double next_inner = 360.0 * (i + 1) / sides, next_corner = k + 1 < 4 ? corner_angle[k + 1] : 405;
    if (k == 4 || (i < sides && next_inner <= next_corner)) {
      faces.push_back({base + (i + 1) % sides, base + i % sides, corners[k % 4]});
      ++i;
    } else {
      faces.push_back({corners[k % 4], corners[(k + 1) % 4], base + i % sides});
      ++k;
    }
  }
  return test::mesh_from_lists(points, faces);
}

TEST(DualRepair, TheBoxWithASpireIsAClosedOrientedSurface) {
  const MeshReport report = analyze_mesh(box_with_spire(12, 0.004));
  EXPECT_EQ(report.euler_characteristic, 2);
  EXPECT_EQ(report.nonmanifold_edges, 0);
  EXPECT_EQ(report.boundary_loops, 0);
  EXPECT_TRUE(report.oriented);
}

TEST(DualRepair, FacesStoredAgainstTheirNeighboursGiveAnOrientedDual) {
  // A sphere whose upper cap is stored reversed: orientable, not oriented.
  TriangleMesh sphere = test::icosphere(3);
  Index reversed = 0;
  for (Index f = 0; f < sphere.faces.rows(); ++f) {
    const double z = (sphere.vertices.row(sphere.faces(f, 0)) + sphere.vertices.row(sphere.faces(f, 1)) +
                      sphere.vertices.row(sphere.faces(f, 2)))
                         .z();
    if (z > 1.5) {
      std::swap(sphere.faces(f, 1), sphere.faces(f, 2));
      ++reversed;
    }
  }
  ASSERT_GT(reversed, 0);
  ASSERT_FALSE(analyze_mesh(sphere).oriented);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(sphere, 300);
  const remesh::DualMesh dual = remesh::dual_delaunay(sphere, voronoi::compute_voronoi(sphere, sites));
  EXPECT_TRUE(dual.check.valid) << (dual.check.problems.empty() ? "" : dual.check.problems[0]);
  EXPECT_EQ(dual.check.nonmanifold_edges, 0);
  const MeshReport report = analyze_mesh(dual.mesh);
  EXPECT_TRUE(report.oriented);
  EXPECT_EQ(report.euler_characteristic, 2);
  // The orientation most of the input has: outward.
  for (Index f = 0; f < dual.mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = dual.mesh.vertices.row(dual.mesh.faces(f, 0)),
                          b = dual.mesh.vertices.row(dual.mesh.faces(f, 1)),
                          c = dual.mesh.vertices.row(dual.mesh.faces(f, 2));
    ASSERT_GT((b - a).cross(c - a).dot(a + b + c), 0) << "dual triangle " << f << " faces inwards";
  }
}

TEST(DualRepair, ACellEnclosedAroundASpireIsRepairedAllRoundIt) {
  // A site at the spire's tip and one halfway down it: the tip's cell is a cap
  // that the other's cell girdles, one closed boundary with no Voronoi vertex.
  const TriangleMesh mesh = box_with_spire(12, 0.004);
  const Index apex = mesh.num_vertices() - 1;
  const Index first_spire_face = 10;  // after the box's bottom and sides
  std::vector<SurfacePoint> sites = {SurfacePoint::at_vertex(apex),
                                     SurfacePoint::in_face(first_spire_face + 3, 0.25, 0.25, 0.5),
                                     SurfacePoint::in_face(0, 0.4, 0.3, 0.3),
                                     SurfacePoint::in_face(1, 0.3, 0.3, 0.4),
                                     SurfacePoint::in_face(3, 0.3, 0.4, 0.3),
                                     SurfacePoint::in_face(6, 0.3, 0.3, 0.4),
                                     SurfacePoint::at_vertex(5)};
  const voronoi::VoronoiDiagram diagram = voronoi::compute_voronoi(mesh, sites);
  const remesh::DualMesh dual = remesh::dual_delaunay(mesh, diagram);
  ASSERT_EQ(dual.check.closed_arcs, 1);
  const voronoi::VoronoiArc* loop = nullptr;
  for (const voronoi::VoronoiArc& arc : diagram.arcs) {
    if (arc.closed) loop = &arc;
  }
  ASSERT_NE(loop, nullptr);
  // Its points lie between heights low and high on the spire.
  double low = 1, high = 0;
  for (const Eigen::Vector3d& p : diagram.polyline(*loop)) {
    low = std::min(low, p.z());
    high = std::max(high, p.z());
  }
  std::vector<Eigen::Vector3d> on_loop;
  for (const SurfacePoint& p : dual.check.repair_sites) {
    const Eigen::Vector3d x = p.position(mesh);
    if (x.z() >= low - 1e-12 && x.z() <= high + 1e-12) on_loop.push_back(x);
  }
  // Three, spread round the spire: each pair at least a sixth of the loop apart.
  ASSERT_EQ(on_loop.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_GT((on_loop[i] - on_loop[(i + 1) % 3]).norm(), loop->length / 6);
  }
}

}  // namespace
}  // namespace geodual
