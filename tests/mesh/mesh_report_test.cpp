// analyze_mesh on small hand-built meshes whose counts are known by hand.

#include "mesh/small_meshes.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_report.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <vector>

namespace geodual {
namespace {

using test::make_mesh;

/// Appends a face to a mesh.
void add_face(TriangleMesh& mesh, Index a, Index b, Index c) {
  mesh.faces.conservativeResize(mesh.faces.rows() + 1, 3);
  mesh.faces.row(mesh.faces.rows() - 1) << a, b, c;
}

TriangleMesh tetrahedron() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

/// A rows x cols grid of quads, two triangles each, on the unit square;
/// with wrap, its opposite sides are glued into a torus.
TriangleMesh grid(int rows, int cols, bool wrap) {
  const int vertex_rows = wrap ? rows : rows + 1;
  const int vertex_cols = wrap ? cols : cols + 1;
  TriangleMesh mesh;
  mesh.vertices.resize(vertex_rows * vertex_cols, 3);
  for (int i = 0; i < vertex_rows; ++i) {
    for (int j = 0; j < vertex_cols; ++j) {
      if (wrap) {  // a torus in space, so that no two vertices coincide
        const double u = 2 * std::numbers::pi * i / rows;
        const double w = 2 * std::numbers::pi * j / cols;
        mesh.vertices.row(i * vertex_cols + j) << (2 + std::cos(w)) * std::cos(u), (2 + std::cos(w)) * std::sin(u),
            std::sin(w);
      } else {
        mesh.vertices.row(i * vertex_cols + j) << j, i, 0;
      }
    }
  }
  const auto id = [&](int i, int j) { return (i % vertex_rows) * vertex_cols + (j % vertex_cols); };
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      add_face(mesh, id(i, j), id(i, j + 1), id(i + 1, j + 1));
      add_face(mesh, id(i, j), id(i + 1, j + 1), id(i + 1, j));
    }
  }
  return mesh;
}

void expect_clean(const MeshReport& report) {
  EXPECT_EQ(report.nonmanifold_edges, 0);
  EXPECT_EQ(report.nonmanifold_vertices, 0);
  EXPECT_EQ(report.degenerate_faces, 0);
  EXPECT_EQ(report.duplicate_faces, 0);
  EXPECT_EQ(report.duplicate_vertices, 0);
  EXPECT_EQ(report.unreferenced_vertices, 0);
}

TEST(MeshReport, TetrahedronIsAClosedGenusZeroSurface) {
  const MeshReport report = analyze_mesh(tetrahedron());
  EXPECT_EQ(report.vertices, 4);
  EXPECT_EQ(report.faces, 4);
  EXPECT_EQ(report.edges, 6);
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.boundary_edges, 0);
  EXPECT_EQ(report.boundary_loops, 0);
  EXPECT_EQ(report.euler_characteristic, 2);
  ASSERT_TRUE(report.genus.has_value());
  EXPECT_EQ(*report.genus, 0.0);
  EXPECT_TRUE(report.oriented);
  expect_clean(report);
  EXPECT_EQ(report.bbox_min, Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(report.bbox_max, Eigen::Vector3d(1, 1, 1));
  EXPECT_DOUBLE_EQ(report.bbox_diagonal, std::sqrt(3.0));
}

TEST(MeshReport, OpenSquareHasOneBoundaryLoop) {
  const MeshReport report = analyze_mesh(grid(1, 1, false));
  EXPECT_EQ(report.vertices, 4);
  EXPECT_EQ(report.faces, 2);
  EXPECT_EQ(report.edges, 5);
  EXPECT_EQ(report.boundary_edges, 4);
  EXPECT_EQ(report.boundary_loops, 1);
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.euler_characteristic, 1);
  ASSERT_TRUE(report.genus.has_value());
  EXPECT_EQ(*report.genus, 0.0);
  EXPECT_TRUE(report.oriented);
  expect_clean(report);
}

TEST(MeshReport, LargerOpenGridStillHasOneLoop) {
  const MeshReport report = analyze_mesh(grid(5, 7, false));
  EXPECT_EQ(report.boundary_edges, 2 * (5 + 7));
  EXPECT_EQ(report.boundary_loops, 1);
  EXPECT_EQ(report.euler_characteristic, 1);
  EXPECT_EQ(report.genus, 0.0);
}

TEST(MeshReport, TwoDisjointTrianglesAreTwoComponents) {
  const MeshReport report = analyze_mesh(
      make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}}, {{0, 1, 2}, {3, 4, 5}}));
  EXPECT_EQ(report.components, 2);
  EXPECT_EQ(report.boundary_loops, 2);
  EXPECT_EQ(report.boundary_edges, 6);
  EXPECT_EQ(report.euler_characteristic, 2);
  EXPECT_EQ(report.genus, 0.0);  // two discs: (2*2 - 2 - 2) / 2
  expect_clean(report);
}

TEST(MeshReport, BowTiePinchVertexIsNonManifold) {
  // Two triangles that share only vertex 0.
  const MeshReport report =
      analyze_mesh(make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}));
  EXPECT_EQ(report.nonmanifold_vertices, 1);
  EXPECT_EQ(report.nonmanifold_edges, 0);
  EXPECT_EQ(report.components, 1);  // joined at the pinch vertex
  EXPECT_EQ(report.boundary_edges, 6);
  EXPECT_EQ(report.boundary_loops, 1);  // one figure eight through the pinch
  EXPECT_EQ(report.euler_characteristic, 1);
  EXPECT_FALSE(report.genus.has_value());
}

TEST(MeshReport, TwoFansOfAClosedSurfaceTouchingAtAVertex) {
  // Two tetrahedra glued at one vertex (vertex 0): two closed fans there.
  TriangleMesh mesh =
      make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}},
                {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 5, 4}, {0, 4, 6}, {0, 6, 5}, {4, 5, 6}});
  const MeshReport report = analyze_mesh(mesh);
  EXPECT_EQ(report.nonmanifold_vertices, 1);
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.boundary_loops, 0);
  EXPECT_EQ(report.euler_characteristic, 7 - 12 + 8);
  EXPECT_FALSE(report.genus.has_value());
}

TEST(MeshReport, FinEdgeIsNonManifoldButItsVerticesAreNot) {
  // Three triangles on edge (0, 1).
  const MeshReport report = analyze_mesh(
      make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}));
  EXPECT_EQ(report.nonmanifold_edges, 1);
  EXPECT_EQ(report.nonmanifold_vertices, 0);
  EXPECT_EQ(report.edges, 7);
  EXPECT_EQ(report.boundary_edges, 6);
  EXPECT_EQ(report.components, 1);
  EXPECT_FALSE(report.oriented);  // (0, 1) is used twice in the same direction
  EXPECT_FALSE(report.genus.has_value());
}

TEST(MeshReport, DuplicateFaceIsCountedOnceAndMakesItsEdgesNonManifold) {
  TriangleMesh mesh = tetrahedron();
  add_face(mesh, 1, 0, 2);  // the vertex set of face 0, {0, 1, 2}, in another order
  const MeshReport report = analyze_mesh(mesh);
  EXPECT_EQ(report.duplicate_faces, 1);
  EXPECT_EQ(report.nonmanifold_edges, 3);
  EXPECT_EQ(report.nonmanifold_vertices, 0);
  EXPECT_FALSE(report.genus.has_value());
}

TEST(MeshReport, EachRepeatOfAFaceCounts) {
  TriangleMesh mesh = tetrahedron();
  add_face(mesh, 0, 2, 1);
  add_face(mesh, 2, 1, 0);
  add_face(mesh, 1, 2, 3);
  EXPECT_EQ(analyze_mesh(mesh).duplicate_faces, 3);
}

TEST(MeshReport, ZeroAreaFaceIsDegenerate) {
  // Vertex 4 lies on the segment from vertex 0 to vertex 1.
  TriangleMesh mesh =
      make_mesh({{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
  add_face(mesh, 0, 4, 1);
  const MeshReport report = analyze_mesh(mesh);
  EXPECT_EQ(report.degenerate_faces, 1);
  EXPECT_EQ(report.faces, 5);
}

TEST(MeshReport, RepeatedIndexAndCoincidentCornersAreDegenerate) {
  TriangleMesh mesh = tetrahedron();
  add_face(mesh, 0, 0, 1);  // repeated index
  mesh.vertices.conservativeResize(5, 3);
  mesh.vertices.row(4) = mesh.vertices.row(3);
  add_face(mesh, 3, 4, 1);  // two corners at the same position
  const MeshReport report = analyze_mesh(mesh);
  EXPECT_EQ(report.degenerate_faces, 2);
  EXPECT_EQ(report.duplicate_vertices, 1);
}

TEST(MeshReport, FaceOnASingleVertexFormsNoFan) {
  TriangleMesh mesh = tetrahedron();
  add_face(mesh, 2, 2, 2);
  const MeshReport report = analyze_mesh(mesh);
  EXPECT_EQ(report.nonmanifold_vertices, 0);
  EXPECT_EQ(report.degenerate_faces, 1);
  EXPECT_EQ(report.edges, 6);
}

TEST(MeshReport, UnreferencedVertexIsCountedAndLeftOutOfTheBox) {
  TriangleMesh mesh = tetrahedron();
  mesh.vertices.conservativeResize(5, 3);
  mesh.vertices.row(4) << 10, 10, 10;
  const MeshReport report = analyze_mesh(mesh);
  EXPECT_EQ(report.vertices, 5);
  EXPECT_EQ(report.unreferenced_vertices, 1);
  EXPECT_EQ(report.euler_characteristic, 2);  // counts referenced vertices only
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.bbox_max, Eigen::Vector3d(1, 1, 1));
  EXPECT_EQ(report.genus, 0.0);
}

TEST(MeshReport, DuplicateVerticesCompareExactPositions) {
  TriangleMesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-0.0, 0, 0}, {1, 0, 1e-300}}, {{0, 1, 2}});
  // -0 equals +0; 1e-300 differs from 0.
  EXPECT_EQ(analyze_mesh(mesh).duplicate_vertices, 1);
}

TEST(MeshReport, TorusGridHasGenusOne) {
  const MeshReport report = analyze_mesh(grid(8, 6, true));
  EXPECT_EQ(report.vertices, 48);
  EXPECT_EQ(report.faces, 96);
  EXPECT_EQ(report.edges, 144);
  EXPECT_EQ(report.euler_characteristic, 0);
  EXPECT_EQ(report.boundary_loops, 0);
  ASSERT_TRUE(report.genus.has_value());
  EXPECT_EQ(*report.genus, 1.0);
  EXPECT_TRUE(report.oriented);
  expect_clean(report);
}

TEST(MeshReport, FlippedFaceLosesOrientationButNotGenus) {
  TriangleMesh mesh = tetrahedron();
  mesh.faces.row(3) << 1, 3, 2;
  const MeshReport report = analyze_mesh(mesh);
  EXPECT_FALSE(report.oriented);
  ASSERT_TRUE(report.genus.has_value());  // still orientable
  EXPECT_EQ(*report.genus, 0.0);
}

TEST(MeshReport, MoebiusStripIsNotOrientable) {
  // A strip of 4 quads whose ends are glued with a half twist.
  TriangleMesh mesh;
  const int segments = 4;
  mesh.vertices.resize(2 * segments, 3);
  for (int i = 0; i < segments; ++i) {
    const double angle = std::numbers::pi * i / segments;
    mesh.vertices.row(2 * i) << std::cos(2 * angle), std::sin(2 * angle), std::cos(angle);
    mesh.vertices.row(2 * i + 1) << std::cos(2 * angle) * 0.5, std::sin(2 * angle) * 0.5, -std::cos(angle);
  }
  for (int i = 0; i < segments; ++i) {
    const Index a = 2 * i;
    const Index b = 2 * i + 1;
    // The last quad joins the first column swapped: the half twist.
    const Index c = i + 1 < segments ? 2 * (i + 1) : 1;
    const Index d = i + 1 < segments ? 2 * (i + 1) + 1 : 0;
    add_face(mesh, a, c, b);
    add_face(mesh, b, c, d);
  }
  const MeshReport report = analyze_mesh(mesh);
  EXPECT_EQ(report.nonmanifold_edges, 0);
  EXPECT_EQ(report.nonmanifold_vertices, 0);
  EXPECT_EQ(report.boundary_loops, 1);
  EXPECT_FALSE(report.oriented);
  EXPECT_FALSE(report.genus.has_value());
}

TEST(MeshReport, EmptyMeshHasNoGenus) {
  const MeshReport report = analyze_mesh(TriangleMesh{});
  EXPECT_EQ(report.vertices, 0);
  EXPECT_EQ(report.faces, 0);
  EXPECT_EQ(report.components, 0);
  EXPECT_EQ(report.bbox_diagonal, 0.0);
  EXPECT_FALSE(report.genus.has_value());
}

TEST(MeshReport, VerticesWithoutFaces) {
  TriangleMesh mesh;
  mesh.vertices.resize(3, 3);
  mesh.vertices.setZero();
  const MeshReport report = analyze_mesh(mesh);
  EXPECT_EQ(report.unreferenced_vertices, 3);
  EXPECT_EQ(report.duplicate_vertices, 2);
  EXPECT_EQ(report.components, 0);
}

TEST(MeshReport, IndexOutOfRangeThrowsNamingTheFace) {
  TriangleMesh mesh = tetrahedron();
  mesh.faces(2, 1) = 4;
  try {
    analyze_mesh(mesh);
    FAIL() << "expected geodual::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("face 2"), std::string::npos) << error.what();
  }
  mesh.faces(2, 1) = -1;
  EXPECT_THROW(analyze_mesh(mesh), Error);
}

TEST(MeshReport, NanCoordinatesDoNotBreakTheAnalysis) {
  TriangleMesh mesh = tetrahedron();
  mesh.vertices(1, 0) = std::nan("");
  const MeshReport report = analyze_mesh(mesh);
  EXPECT_EQ(report.faces, 4);
  EXPECT_EQ(report.edges, 6);
}

}  // namespace
}  // namespace geodual
