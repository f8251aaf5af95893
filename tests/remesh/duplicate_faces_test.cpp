// Duplicate faces (a CAD soup's second copy of a triangle, in either
// orientation, by index or by position) add no surface: the cut to a
// manifold disables the copies and keeps the first, so that the surface
// stays whole, and many copies cost next to nothing.

#include "hard_cases.hpp"
#include "remesh/analytic_surfaces.hpp"

#include "geodual/mesh/mesh_report.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/remesh/remesh.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <vector>

namespace geodual::remesh {
namespace {

double area(const TriangleMesh& mesh) {
  double sum = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    sum += 0.5 * (b - a).cross(c - a).norm();
  }
  return sum;
}

bool disabled(const ManifoldCut& cut, Index f) {
  return cut.mesh.faces(f, 0) == cut.mesh.faces(f, 1) && cut.mesh.faces(f, 1) == cut.mesh.faces(f, 2);
}

TEST(DuplicateFaces, TheCopiesOfASoupAreDisabledAndTheSurfaceStaysWhole) {
  // A torus of 9,600 faces, then a copy of every tenth face, every other
  // copy flipped. Cutting along the copies' edges left eight annuli, each
  // original and copy a one-face scrap: 18 % of the area.
  const TriangleMesh soup = bench::duplicate_soup();
  constexpr Index torus_faces = 9600;
  ASSERT_EQ(soup.num_faces(), torus_faces + 960);
  const ManifoldCut cut = cut_to_manifold(soup);
  EXPECT_EQ(cut.duplicates_disabled, 960);
  EXPECT_EQ(cut.faces_disabled, 960);
  EXPECT_EQ(cut.vertices_split, 0);
  ASSERT_EQ(cut.copy_of.size(), static_cast<std::size_t>(soup.num_faces()));
  for (Index f = 0; f < torus_faces; ++f) {
    ASSERT_EQ(cut.mesh.faces.row(f), soup.faces.row(f)) << "face " << f;
    ASSERT_EQ(cut.copy_of[f], -1) << "face " << f;
  }
  for (Index f = torus_faces; f < soup.num_faces(); ++f) {
    ASSERT_TRUE(disabled(cut, f)) << "face " << f;
    ASSERT_EQ(cut.copy_of[f], 10 * (f - torus_faces)) << "face " << f;
  }
  const MeshTopology topology = build_mesh_topology(cut.mesh);
  ASSERT_EQ(topology.num_components(), 1);
  EXPECT_EQ(topology.components[0].euler_characteristic(), 0);
  EXPECT_EQ(topology.num_boundary_loops, 0);
}

TEST(DuplicateFaces, TheRemeshOfASoupIsTheWholeTorus) {
  const TriangleMesh soup = bench::duplicate_soup();
  const ManifoldCut cut = cut_to_manifold(soup);
  const RemeshResult result = remesh_from_sites(soup, sample_sites(cut.mesh, 400));
  const MeshReport out = analyze_mesh(result.dual.mesh);
  EXPECT_EQ(out.components, 1);
  EXPECT_EQ(out.euler_characteristic, 0);
  EXPECT_EQ(out.boundary_loops, 0);
  const double torus_area = area(cut.mesh);
  EXPECT_NEAR(area(result.dual.mesh), torus_area, 0.03 * torus_area);
}

TEST(DuplicateFaces, CopiesByPositionAreDisabledTouchingPiecesStayApart) {
  // An icosphere, then copies of its first ten faces on vertices of their
  // own at the same positions (an unwelded soup), every other one flipped.
  const TriangleMesh sphere = test::icosphere(2);
  TriangleMesh mesh;
  mesh.vertices.resize(sphere.num_vertices() + 30, 3);
  mesh.faces.resize(sphere.num_faces() + 10, 3);
  mesh.vertices.topRows(sphere.num_vertices()) = sphere.vertices;
  mesh.faces.topRows(sphere.num_faces()) = sphere.faces;
  for (Index i = 0; i < 10; ++i) {
    for (int k = 0; k < 3; ++k)
      mesh.vertices.row(sphere.num_vertices() + 3 * i + k) = sphere.vertices.row(sphere.faces(i, k));
    const Index first = sphere.num_vertices() + 3 * i;
    mesh.faces.row(sphere.num_faces() + i) = i % 2 == 0 ? Eigen::Matrix<Index, 1, 3>(first, first + 1, first + 2)
                                                        : Eigen::Matrix<Index, 1, 3>(first, first + 2, first + 1);
  }
  const ManifoldCut cut = cut_to_manifold(mesh);
  EXPECT_EQ(cut.duplicates_disabled, 10);
  ASSERT_EQ(cut.copy_of.size(), static_cast<std::size_t>(mesh.num_faces()));
  for (Index i = 0; i < 10; ++i) {
    EXPECT_TRUE(disabled(cut, sphere.num_faces() + i));
    EXPECT_EQ(cut.copy_of[sphere.num_faces() + i], i);
  }
  EXPECT_EQ(cut.mesh.faces.topRows(sphere.num_faces()), sphere.faces);

  // Two tetrahedra touching at one point, each with its own vertex there:
  // no copies, nothing welded, nothing cut.
  const TriangleMesh tetrahedra =
      test::mesh_from_lists({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}},
                            {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {4, 5, 6}, {4, 7, 5}, {4, 6, 7}, {5, 7, 6}});
  const ManifoldCut apart = cut_to_manifold(tetrahedra);
  EXPECT_EQ(apart.faces_disabled, 0);
  EXPECT_EQ(apart.vertices_split, 0);
  EXPECT_EQ(apart.mesh.faces, tetrahedra.faces);
}

TEST(DuplicateFaces, AMillionCopiesCostNextToNothing) {
  // An icosphere plus 10^6 copies of its first face: the copies made every
  // stage walk a million-face edge (minutes); now they are disabled first.
  const TriangleMesh sphere = test::icosphere(4);
  constexpr Index copies = 1'000'000;
  TriangleMesh mesh;
  mesh.vertices = sphere.vertices;
  mesh.faces.resize(sphere.num_faces() + copies, 3);
  mesh.faces.topRows(sphere.num_faces()) = sphere.faces;
  mesh.faces.bottomRows(copies).rowwise() = sphere.faces.row(0);
  const ManifoldCut cut = cut_to_manifold(mesh);
  const std::vector<SurfacePoint> sites = sample_sites(cut.mesh, 500);
  EXPECT_EQ(cut.duplicates_disabled, copies);
  EXPECT_EQ(cut.vertices_split, 0);
  EXPECT_EQ(cut.mesh.faces.topRows(sphere.num_faces()), sphere.faces);
  ASSERT_EQ(sites.size(), 500u);
  for (const SurfacePoint& site : sites) ASSERT_LT(site.element, sphere.num_faces());
}

}  // namespace
}  // namespace geodual::remesh
