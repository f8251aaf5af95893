// Scraps (pieces too small to remesh) are small relative to the surface,
// never the whole of it: a mesh of a few faces remeshes, or fails naming the
// site count, and a small piece beside a large one is still dropped.

#include "remesh/analytic_surfaces.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/remesh/remesh.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace geodual::remesh {
namespace {

TriangleMesh tetrahedron() {
  return test::mesh_from_lists({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                               {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

/// A square of two triangles (one boundary loop).
TriangleMesh square() {
  return test::mesh_from_lists({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
}

/// `b` appended to `a`, moved by `offset`.
TriangleMesh beside(const TriangleMesh& a, const TriangleMesh& b, const Eigen::Vector3d& offset) {
  TriangleMesh out;
  out.vertices.resize(a.vertices.rows() + b.vertices.rows(), 3);
  out.vertices << a.vertices, b.vertices.rowwise() + offset.transpose();
  out.faces.resize(a.faces.rows() + b.faces.rows(), 3);
  out.faces << a.faces, b.faces.array() + static_cast<Index>(a.vertices.rows());
  return out;
}

/// What the remesh pipeline does: cut, sample on the cut surface, remesh.
RemeshResult remesh_mesh(const TriangleMesh& mesh, std::int64_t count) {
  const ManifoldCut cut = cut_to_manifold(mesh);
  const std::vector<SurfacePoint> sites = sample_sites(cut.mesh, count);
  return remesh_from_sites(cut.mesh, sites);
}

TEST(SmallPieces, AMeshOfAFewFacesIsNoScrap) {
  for (const auto& [name, mesh] : {std::pair{"tetrahedron", tetrahedron()}, std::pair{"square", square()}}) {
    SCOPED_TRACE(name);
    const ManifoldCut cut = cut_to_manifold(mesh);
    EXPECT_EQ(cut.faces_disabled, 0);
    EXPECT_EQ(cut.mesh.faces, mesh.faces);
  }
}

TEST(SmallPieces, ScrapsAreNeverTheWholeSurface) {
  // Two equal tetrahedra: neither is small beside the other. 300 lone
  // triangles: each is small beside the rest, but dropping them all would
  // drop everything.
  const TriangleMesh two = beside(tetrahedron(), tetrahedron(), {3, 0, 0});
  EXPECT_EQ(cut_to_manifold(two).faces_disabled, 0);
  TriangleMesh soup = test::mesh_from_lists({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  const TriangleMesh triangle = soup;
  for (int i = 1; i < 300; ++i) soup = beside(soup, triangle, {2.0 * i, 0, 0});
  EXPECT_EQ(cut_to_manifold(soup).faces_disabled, 0);
}

TEST(SmallPieces, ASmallPieceBesideALargeOneIsAScrap) {
  // A tetrahedron of edge 0.01 beside the unit sphere: a 4-face scrap.
  const TriangleMesh sphere = test::icosphere(3);
  TriangleMesh small = tetrahedron();
  small.vertices *= 0.01;
  const TriangleMesh mesh = beside(sphere, small, {3, 0, 0});
  const ManifoldCut cut = cut_to_manifold(mesh);
  EXPECT_EQ(cut.faces_disabled, 4);
  for (Index f = sphere.num_faces(); f < mesh.num_faces(); ++f) {
    EXPECT_EQ(cut.mesh.faces(f, 0), cut.mesh.faces(f, 1)) << "face " << f;
  }
  // The same tetrahedron at the sphere's size is no scrap.
  small.vertices *= 100;
  EXPECT_EQ(cut_to_manifold(beside(sphere, small, {3, 0, 0})).faces_disabled, 0);
}

TEST(SmallPieces, GivenSitesMustReachEveryPiece) {
  // Two spheres side by side; sites on the first only. The second would
  // vanish from the remesh without a word.
  const TriangleMesh sphere = test::icosphere(3);
  const TriangleMesh two = beside(sphere, sphere, Eigen::Vector3d(3, 0, 0));
  std::vector<SurfacePoint> sites = sample_sites(sphere, 100);
  EXPECT_NO_THROW(require_a_site_on_every_piece(sphere, sites));
  try {
    (void)remesh_from_sites(two, sites);
    ADD_FAILURE() << "a piece without sites was left out silently";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("1 of 2 pieces of the surface hold no site"), std::string::npos)
        << error.what();
  }
  // A vertex site on the second sphere is enough to pass the check.
  sites.push_back(SurfacePoint::at_vertex(static_cast<Index>(sphere.vertices.rows())));
  EXPECT_NO_THROW(require_a_site_on_every_piece(two, sites));
}

TEST(SmallPieces, ATetrahedronRemeshes) {
  const TriangleMesh mesh = tetrahedron();
  for (const std::int64_t count : {4, 20, 200}) {
    SCOPED_TRACE(std::to_string(count) + " sites");
    const RemeshResult result = remesh_mesh(mesh, count);
    EXPECT_TRUE(result.dual.check.valid);
    const MeshReport out = analyze_mesh(result.dual.mesh);
    EXPECT_EQ(out.components, 1);
    EXPECT_EQ(out.euler_characteristic, 2);
    EXPECT_EQ(out.boundary_loops, 0);
    EXPECT_EQ(result.faces_disabled, 0);
  }
}

TEST(SmallPieces, ASquareOfTwoFacesRemeshesOrNamesTheSiteCount) {
  const TriangleMesh mesh = square();
  // Too few sites for its boundary loop: the message says how many are needed.
  try {
    remesh_mesh(mesh, 2);
    FAIL() << "2 sites were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("site count 2"), std::string::npos) << e.what();
  }
  for (const std::int64_t count : {10, 100}) {
    SCOPED_TRACE(std::to_string(count) + " sites");
    const RemeshResult result = remesh_mesh(mesh, count);
    EXPECT_TRUE(result.dual.check.valid);
    const MeshReport out = analyze_mesh(result.dual.mesh);
    EXPECT_EQ(out.components, 1);
    EXPECT_EQ(out.euler_characteristic, 1);
    EXPECT_EQ(out.boundary_loops, 1);
  }
}

}  // namespace
}  // namespace geodual::remesh
