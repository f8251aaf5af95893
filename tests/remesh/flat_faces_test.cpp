// Faces whose cross product is not zero but whose edge lengths give no area
// (needles thinner than the rounding of their lengths: CAD surfaces have
// them) are flat to the geodesic engine, which refuses a site on them.
// Sampling must never put a site there, by the engine's own test.

#include "../../remesh/src/common/surface_walk.hpp"
#include "remesh/analytic_surfaces.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/remesh/remesh.hpp"
#include "geodual/remesh/sample_sites.hpp"
#include "geodual/voronoi/geodesic_field.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace geodual::remesh {
namespace {

/// The unit square as an n x n grid of two triangles per cell, and under
/// each cell of the bottom row a needle (a, m, b): a and b the cell's lower
/// corners, m their midpoint moved 1e-17 below y = 0. The needles carry the
/// bottom boundary; their area is ~1e-17 of a cell's.
struct NeedleSquare {
  TriangleMesh mesh;
  std::vector<Index> needles;
};

NeedleSquare needle_square(int n) {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<Index, 3>> faces;
  auto grid = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) vertices.emplace_back(double(i) / n, double(j) / n, 0.0);
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      faces.push_back({grid(i, j), grid(i + 1, j), grid(i + 1, j + 1)});
      faces.push_back({grid(i, j), grid(i + 1, j + 1), grid(i, j + 1)});
    }
  }
  NeedleSquare square;
  for (int i = 0; i < n; ++i) {
    const auto m = static_cast<Index>(vertices.size());
    vertices.emplace_back((i + 0.5) / n, -1e-17 / n, 0.0);
    square.needles.push_back(static_cast<Index>(faces.size()));
    faces.push_back({grid(i, 0), m, grid(i + 1, 0)});
  }
  square.mesh = test::mesh_from_lists(vertices, faces);
  return square;
}

TEST(FlatFaces, NeedlesHaveACrossProductButNoGeodesicArea) {
  const NeedleSquare square = needle_square(8);
  const TriangleMesh& mesh = square.mesh;
  for (const Index f : square.needles) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    EXPECT_GT((b - a).cross(c - a).z(), 0.0) << "face " << f;  // oriented like the grid, not zero
    EXPECT_FALSE(has_positive_area(mesh, f)) << "face " << f;
  }
  for (Index f = 0; f < 2 * 8 * 8; ++f) EXPECT_TRUE(has_positive_area(mesh, f)) << "face " << f;
  // The engine refuses a site inside a needle, and says so.
  const Index needle = square.needles[3];
  try {
    voronoi::compute_geodesic_field(mesh, std::vector{SurfacePoint::in_face(needle, 0.25, 0.5, 0.25)});
    FAIL() << "a site inside a needle was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("has zero area"), std::string::npos) << e.what();
  }
}

TEST(FlatFaces, SamplingPutsNoSiteOnThem) {
  // The bottom boundary runs along the needles only: boundary sites there
  // went into the needles before, and the engine refused them.
  const NeedleSquare square = needle_square(16);
  const TriangleMesh& mesh = square.mesh;
  for (const SamplingStrategy strategy : {SamplingStrategy::random, SamplingStrategy::poisson, SamplingStrategy::fps}) {
    for (const std::int64_t count : {40, 200}) {
      SCOPED_TRACE("strategy " + std::to_string(static_cast<int>(strategy)) + ", " + std::to_string(count) + " sites");
      const std::vector<SurfacePoint> sites = sample_sites(mesh, count, {.strategy = strategy});
      ASSERT_EQ(static_cast<std::int64_t>(sites.size()), count);
      for (const SurfacePoint& site : sites) {
        if (site.kind == SurfacePoint::Kind::face) {
          EXPECT_TRUE(has_positive_area(mesh, site.element)) << "a site on face " << site.element;
        }
      }
      EXPECT_NO_THROW(voronoi::compute_geodesic_field(mesh, sites));
    }
  }
}

TEST(FlatFaces, AWalkNeverEndsInOne) {
  // Lloyd's steps walk the sites over the surface: walks from the bottom
  // row's cells straight down run into the needles and stop at the boundary
  // beyond them, on the cell they left.
  const NeedleSquare square = needle_square(8);
  const TriangleMesh& mesh = square.mesh;
  const voronoi::GeodesicField field =
      voronoi::compute_geodesic_field(mesh, std::vector{SurfacePoint::in_face(40, 1.0 / 3, 1.0 / 3, 1.0 / 3)});
  for (Index cell = 0; cell < 16; cell += 2) {  // the lower triangle of each bottom cell
    const SurfacePoint start = SurfacePoint::in_face(cell, 0.4, 0.4, 0.2);
    for (const double length : {0.1, 0.2, 1.0}) {
      const SurfacePoint end =
          detail::walk_on_surface(mesh, *field.topology, start, Eigen::Vector3d(0.1, -1, 0), length);
      ASSERT_EQ(end.kind, SurfacePoint::Kind::face);
      EXPECT_TRUE(has_positive_area(mesh, end.element)) << "from face " << cell << ", length " << length;
      EXPECT_GE(end.position(mesh).y(), -1e-12);
    }
  }
}

TEST(FlatFaces, TheSquareRemeshes) {
  const NeedleSquare square = needle_square(16);
  const std::vector<SurfacePoint> sites = sample_sites(square.mesh, 100);
  RemeshOptions options;
  options.lloyd.iterations = 3;  // Lloyd moves the sites too: still never onto a needle
  const RemeshResult result = remesh_from_sites(square.mesh, sites, options);
  EXPECT_TRUE(result.dual.check.valid);
  EXPECT_GE(result.dual.mesh.num_faces(), 100);
}

}  // namespace
}  // namespace geodual::remesh
