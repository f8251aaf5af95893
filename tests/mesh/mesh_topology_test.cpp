// MeshTopology on small meshes whose connectivity is known by hand, and
// against analyze_mesh (the defect report) on the same meshes.

#include "mesh/small_meshes.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/mesh/mesh_topology.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace geodual {
namespace {

using test::make_mesh;

/// A square split along its diagonal 0-2.
TriangleMesh square() { return make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}); }

TriangleMesh tetrahedron() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
}

/// Two triangles that share only vertex 2 (a pinch).
TriangleMesh bowtie() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0, 2, 0}, {1, 2, 0}}, {{0, 1, 2}, {2, 4, 3}});
}

TEST(MeshTopology, EdgesAndTheirFaces) {
  const MeshTopology t = build_mesh_topology(square());
  ASSERT_EQ(t.num_edges(), 5);
  // Sorted by vertex pair: (0,1) (0,2) (0,3) (1,2) (2,3).
  const std::vector<std::array<Index, 2>> expected = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {2, 3}};
  EXPECT_EQ(t.edge_vertices, expected);
  const Index diagonal = 1;
  ASSERT_EQ(t.edge_faces(diagonal).size(), 2U);
  EXPECT_EQ(t.edge_faces(diagonal)[0], 0);
  EXPECT_EQ(t.edge_faces(diagonal)[1], 1);
  for (Index e = 0; e < t.num_edges(); ++e) EXPECT_EQ(t.is_boundary_edge(e), e != diagonal) << e;
  // Edge k of a face joins its corners k and k + 1.
  const TriangleMesh mesh = square();
  for (Index f = 0; f < 2; ++f) {
    for (int k = 0; k < 3; ++k) {
      const auto [a, b] = t.edge_vertices[t.face_edges[f][k]];
      const Index u = mesh.faces(f, k), w = mesh.faces(f, (k + 1) % 3);
      EXPECT_EQ(a, std::min(u, w));
      EXPECT_EQ(b, std::max(u, w));
    }
  }
  EXPECT_EQ(t.num_fans(), 4);
  EXPECT_EQ(t.num_components(), 1);
  EXPECT_EQ(t.num_boundary_loops, 1);
  EXPECT_EQ(t.components[0].euler_characteristic(), 1);
  for (const std::uint8_t on_boundary : t.vertex_on_boundary) EXPECT_TRUE(on_boundary);
  // Edges by their ends, in either order; -1 for a pair that is no edge.
  EXPECT_EQ(t.find_edge(2, 0), diagonal);
  EXPECT_EQ(t.find_edge(0, 2), diagonal);
  EXPECT_EQ(t.find_edge(3, 2), 4);
  EXPECT_EQ(t.find_edge(1, 3), -1);
  EXPECT_EQ(t.find_edge(0, 7), -1);
}

TEST(MeshTopology, ClosedSurfaceHasNoBoundary) {
  const MeshTopology t = build_mesh_topology(tetrahedron());
  EXPECT_EQ(t.num_edges(), 6);
  for (Index e = 0; e < t.num_edges(); ++e) EXPECT_EQ(t.edge_faces(e).size(), 2U);
  EXPECT_EQ(t.num_boundary_loops, 0);
  EXPECT_EQ(t.num_fans(), 4);
  EXPECT_EQ(t.components[0].euler_characteristic(), 2);
}

TEST(MeshTopology, PinchVertexHasTwoFans) {
  const MeshTopology t = build_mesh_topology(bowtie());
  EXPECT_EQ(t.num_components(), 1);             // joined through the shared vertex
  EXPECT_EQ(t.num_fans(), 6);                   // vertex 2 has two
  EXPECT_NE(t.corner_fan[2], t.corner_fan[3]);  // corner 2 of face 0, corner 0 of face 1
  EXPECT_EQ(t.fan_vertex[t.corner_fan[2]], 2);
  EXPECT_EQ(t.fan_vertex[t.corner_fan[3]], 2);
  EXPECT_EQ(t.num_boundary_loops, 1);  // a figure eight counts once
}

TEST(MeshTopology, NonManifoldEdgeSplitsFans) {
  // Three triangles on the edge 0-1.
  const MeshTopology t = build_mesh_topology(
      make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}));
  ASSERT_EQ(t.edge_vertices[0], (std::array<Index, 2>{0, 1}));
  EXPECT_EQ(t.edge_faces(0).size(), 3U);
  EXPECT_FALSE(t.is_manifold_edge(0));
  EXPECT_FALSE(t.is_boundary_edge(0));
  EXPECT_EQ(t.num_fans(), 9);  // no face is joined to another around any vertex
}

TEST(MeshTopology, DegenerateFacesAndUnreferencedVerticesTakeNoPart) {
  const MeshTopology t =
      build_mesh_topology(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}, {9, 0, 0}, {9, 1, 0}, {10, 0, 0}},
                                    {{0, 1, 1}, {4, 6, 5}, {0, 1, 2}}));
  EXPECT_EQ(t.face_edges[0], (std::array<Index, 3>{-1, -1, -1}));
  EXPECT_EQ(t.face_component[0], -1);
  EXPECT_EQ(t.corner_fan[0], -1);
  EXPECT_EQ(t.num_components(), 2);
  EXPECT_EQ(t.face_component[1], 0);  // numbered in the order of their first face
  EXPECT_EQ(t.face_component[2], 1);
  EXPECT_EQ(t.vertex_component[3], -1);
  EXPECT_EQ(t.vertex_component[0], 1);
  EXPECT_EQ(t.num_edges(), 6);
  EXPECT_EQ(t.num_boundary_loops, 2);
  EXPECT_EQ(t.components[1].boundary_loops, 1);
}

TEST(MeshTopology, AgreesWithTheMeshReport) {
  for (const TriangleMesh& mesh : {square(), tetrahedron(), bowtie()}) {
    const MeshTopology t = build_mesh_topology(mesh);
    const MeshReport report = analyze_mesh(mesh);
    EXPECT_EQ(t.num_edges(), report.edges);
    EXPECT_EQ(t.num_components(), report.components);
    EXPECT_EQ(t.num_boundary_loops, report.boundary_loops);
    std::int64_t euler = 0;
    for (const ComponentCounts& c : t.components) euler += c.euler_characteristic();
    EXPECT_EQ(euler, report.euler_characteristic);
  }
}

TEST(MeshTopology, FaceOutOfRangeIsAnError) {
  TriangleMesh mesh = square();
  mesh.faces(1, 2) = 7;
  try {
    build_mesh_topology(mesh);
    FAIL() << "expected geodual::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("face 1 refers to vertex 7"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace geodual
