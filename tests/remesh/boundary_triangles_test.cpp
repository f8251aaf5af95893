// The dual closed along the mesh boundary between the sites on it
// (DualOptions::close_boundary_stretches, remesh/src/dual/boundary_triangles.hpp),
// on hand-built planar cases: a strip narrower than the sites' spacing,
// whose cells meet at no Voronoi vertex, becomes the zigzag between its two
// sides; a site off the boundary whose cell reaches it leaves the dual's
// boundary to the sites on it; a site all but on the boundary's line gets no
// sliver.

#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/remesh/dual_delaunay.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <set>
#include <utility>
#include <vector>

namespace geodual {
namespace {

/// The rectangle [0, nx h] x [0, ny h] in z = 0 as a grid of squares of side
/// h, two triangles each, counter-clockwise seen from +z; vertex (i, j) is
/// j (nx + 1) + i.
TriangleMesh rectangle(int nx, int ny, double h) {
  TriangleMesh mesh;
  mesh.vertices.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) mesh.vertices.row(j * (nx + 1) + i) << i * h, j * h, 0;
  }
  mesh.faces.resize(2 * nx * ny, 3);
  Index f = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Index a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      mesh.faces.row(f++) << a, b, d;
      mesh.faces.row(f++) << a, d, c;
    }
  }
  return mesh;
}

/// The sites of `dual` on its boundary edges.
std::set<Index> dual_boundary_vertices(const TriangleMesh& dual) {
  const MeshTopology topology = build_mesh_topology(dual);
  std::set<Index> vertices;
  for (Index e = 0; e < topology.num_edges(); ++e) {
    if (topology.is_boundary_edge(e))
      vertices.insert(topology.edge_vertices[e].begin(), topology.edge_vertices[e].end());
  }
  return vertices;
}

TEST(BoundaryTriangles, AStripNarrowerThanTheSpacingBecomesTheZigzagBetweenItsSides) {
  // 10 x 0.25, sites 1 apart on each side, the top ones half a step along.
  constexpr int nx = 40;
  const TriangleMesh strip = rectangle(nx, 1, 0.25);
  std::vector<SurfacePoint> sites;
  for (int i = 2; i < nx; i += 4) sites.push_back(SurfacePoint::at_vertex(i));             // bottom: x = 0.5, 1.5 ...
  for (int i = 4; i < nx; i += 4) sites.push_back(SurfacePoint::at_vertex((nx + 1) + i));  // top: x = 1, 2 ...
  const voronoi::VoronoiDiagram diagram = voronoi::compute_voronoi(strip, sites);
  ASSERT_TRUE(diagram.vertices.empty()) << "the cells span the strip and meet at no Voronoi vertex";

  const remesh::DualMesh plain = remesh::dual_delaunay(strip, diagram);
  EXPECT_FALSE(plain.check.valid);
  EXPECT_EQ(plain.mesh.num_faces(), 0);

  const remesh::DualMesh closed = remesh::dual_delaunay(strip, diagram, {.close_boundary_stretches = true});
  EXPECT_TRUE(closed.check.valid) << remesh::problems_line(closed.check.problems);
  // The zigzag: every site a corner, one triangle per site but two.
  ASSERT_EQ(closed.mesh.num_faces(), static_cast<Index>(sites.size()) - 2);
  const MeshTopology topology = build_mesh_topology(closed.mesh);
  ASSERT_EQ(topology.components.size(), 1u);
  EXPECT_EQ(topology.components[0].euler_characteristic(), 1);
  EXPECT_EQ(topology.components[0].boundary_loops, 1);
  for (Index t = 0; t < closed.mesh.num_faces(); ++t) {
    // Two corners on one side, consecutive there, the third on the other,
    // and facing +z as the strip does.
    const Eigen::Vector3d a = closed.mesh.vertices.row(closed.mesh.faces(t, 0));
    const Eigen::Vector3d b = closed.mesh.vertices.row(closed.mesh.faces(t, 1));
    const Eigen::Vector3d c = closed.mesh.vertices.row(closed.mesh.faces(t, 2));
    EXPECT_GT((b - a).cross(c - a).z(), 0) << "triangle " << t;
    const int top = (a.y() > 0.125) + (b.y() > 0.125) + (c.y() > 0.125);
    EXPECT_TRUE(top == 1 || top == 2) << "triangle " << t;
    for (const auto& [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      if (std::abs(p.y() - q.y()) < 1e-12) {
        EXPECT_NEAR(std::abs(p.x() - q.x()), 1.0, 1e-12) << "triangle " << t;
      }
    }
  }
}

TEST(BoundaryTriangles, ACellReachingTheBoundaryBetweenTwoOfItsSitesLeavesTheBoundaryToThem) {
  // The square [0, 4]^2 with sites at its corners and the middles of three
  // sides (the bottom one has none), and four inside, one 0.5 above the
  // bottom side's middle, whose cell reaches the bottom side between its
  // corners (the triangle on the three: angles of 14 degrees at the corners).
  const TriangleMesh square = rectangle(16, 16, 0.25);
  const auto at = [](int i, int j) { return SurfacePoint::at_vertex(j * 17 + i); };
  std::vector<SurfacePoint> sites = {at(0, 0), at(16, 0), at(16, 8), at(16, 16), at(8, 16), at(0, 16), at(0, 8)};
  const std::size_t on_border = sites.size();
  for (const auto& [i, j] : {std::pair{8, 2}, std::pair{5, 6}, std::pair{11, 6}, std::pair{8, 11}}) {
    sites.push_back(at(i, j));
  }
  const voronoi::VoronoiDiagram diagram = voronoi::compute_voronoi(square, sites);
  const remesh::DualMesh plain = remesh::dual_delaunay(square, diagram);
  ASSERT_TRUE(dual_boundary_vertices(plain.mesh).contains(static_cast<Index>(on_border)))
      << "the site above the bottom side is on the plain dual's boundary";

  const remesh::DualMesh closed = remesh::dual_delaunay(square, diagram, {.close_boundary_stretches = true});
  EXPECT_TRUE(closed.check.valid) << remesh::problems_line(closed.check.problems);
  for (const Index v : dual_boundary_vertices(closed.mesh)) {
    EXPECT_LT(static_cast<std::size_t>(v), on_border) << "site " << v << " is inside the square";
  }
  EXPECT_EQ(closed.mesh.num_faces(), plain.mesh.num_faces() + 1);  // the bottom corners and the site above
}

TEST(BoundaryTriangles, ASiteAllButOnTheBoundaryLineGetsNoSliver) {
  // The rectangle [0, 2] x [0, 1] with a site at each corner, one a
  // hundredth above the bottom side's middle (a triangle on it and the
  // bottom corners would have angles of 0.6 degrees) and one at the centre,
  // whose cell reaches the top side between its corners (26.6 degrees).
  const TriangleMesh rect = rectangle(200, 100, 0.01);
  const auto at = [](int i, int j) { return SurfacePoint::at_vertex(j * 201 + i); };
  const std::vector<SurfacePoint> sites = {at(0, 0), at(200, 0), at(200, 100), at(0, 100), at(100, 1), at(100, 50)};
  const voronoi::VoronoiDiagram diagram = voronoi::compute_voronoi(rect, sites);
  const remesh::DualMesh plain = remesh::dual_delaunay(rect, diagram);
  const remesh::DualMesh closed = remesh::dual_delaunay(rect, diagram, {.close_boundary_stretches = true});
  EXPECT_EQ(closed.mesh.num_faces(), plain.mesh.num_faces() + 1);
  EXPECT_TRUE(dual_boundary_vertices(closed.mesh).contains(4)) << "the bottom stretch is left open";
  EXPECT_FALSE(dual_boundary_vertices(closed.mesh).contains(5)) << "the top stretch is closed";
}

}  // namespace
}  // namespace geodual
