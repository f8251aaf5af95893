// Edge flips onto given segments: a flip where one makes the segment an
// edge, none where the new triangles would fold or be thinner than the bound,
// and the mesh's orientation and counts kept.

#include "remesh/analytic_surfaces.hpp"

#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/remesh/follow_segments.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <span>

namespace geodual {
namespace {

bool has_edge(const TriangleMesh& mesh, Index a, Index b) {
  const MeshTopology topology = build_mesh_topology(mesh);
  const std::array<Index, 2> pair{std::min(a, b), std::max(a, b)};
  return std::find(topology.edge_vertices.begin(), topology.edge_vertices.end(), pair) != topology.edge_vertices.end();
}

/// Two triangles (0, 1, 2) and (2, 1, 3) sharing the edge 1-2: a quad 0-1-3-2 with vertex 3 at `far`.
TriangleMesh two_triangles(const Eigen::Vector3d& far) {
  return test::mesh_from_lists({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, far}, {{0, 1, 2}, {2, 1, 3}});
}

TEST(FollowSegments, FlipsTheSharedEdgeOntoTheOtherDiagonal) {
  TriangleMesh mesh = two_triangles({1, 1, 0});
  const std::array<Index, 2> segment{0, 3};
  const remesh::FollowedSegments followed = remesh::follow_segments(mesh, std::span(&segment, 1));
  EXPECT_EQ(followed.segments, 1);
  EXPECT_EQ(followed.edges, 1);
  EXPECT_EQ(followed.flipped, 1);
  EXPECT_TRUE(has_edge(mesh, 0, 3));
  EXPECT_FALSE(has_edge(mesh, 1, 2));
  ASSERT_EQ(mesh.num_faces(), 2);
  for (Index f = 0; f < 2; ++f) {  // still facing +z, as both faces did
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    EXPECT_GT((b - a).cross(c - a).z(), 0);
  }
}

TEST(FollowSegments, AnEdgeAlreadyThereIsCountedAndLeftAlone) {
  TriangleMesh mesh = two_triangles({1, 1, 0});
  const TriangleMesh before = mesh;
  const std::array<Index, 2> segment{2, 1};
  const remesh::FollowedSegments followed = remesh::follow_segments(mesh, std::span(&segment, 1));
  EXPECT_EQ(followed.edges, 1);
  EXPECT_EQ(followed.flipped, 0);
  EXPECT_EQ(mesh.faces, before.faces);
}

TEST(FollowSegments, NoFlipThatWouldFoldOrMakeAThinnerTriangle) {
  // A dart: the quad 0-1-3-2 is reflex at 1, so that 0-3 leaves it.
  TriangleMesh dart = two_triangles({2, -0.5, 0});
  const std::array<Index, 2> segment{0, 3};
  const TriangleMesh before = dart;
  EXPECT_EQ(remesh::follow_segments(dart, std::span(&segment, 1)).edges, 0);
  EXPECT_EQ(dart.faces, before.faces);
  // A flat quad whose other diagonal makes a 3-degree angle at 3, where the old triangles' smallest is 6.
  TriangleMesh thin = test::mesh_from_lists({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {10, 10, 0}}, {{0, 1, 2}, {2, 1, 3}});
  EXPECT_EQ(remesh::follow_segments(thin, std::span(&segment, 1)).edges, 0);
  EXPECT_EQ(remesh::follow_segments(thin, std::span(&segment, 1), {.min_angle_degrees = 0}).flipped, 1);
}

TEST(FollowSegments, ASegmentThatCrossesSeveralEdgesIsRecoveredByAsManyFlips) {
  // A hexagon a(0), d1, d2, b(3), c2, c1 fanned so that the segment 0-3
  // along y = 0 crosses the edges c1-d1, c1-d2 and c2-d2.
  const std::vector<Eigen::Vector3d> vertices = {{0, 0, 0}, {1, -1, 0}, {2, -1, 0}, {3, 0, 0}, {2, 1, 0}, {1, 1, 0}};
  const std::vector<std::array<Index, 3>> faces = {{0, 1, 5}, {5, 1, 2}, {5, 2, 4}, {4, 2, 3}};
  const std::array<Index, 2> segment{0, 3};
  TriangleMesh bounded = test::mesh_from_lists(vertices, faces);
  EXPECT_EQ(remesh::follow_segments(bounded, std::span(&segment, 1), {.max_flips = 2}).edges, 0);
  EXPECT_EQ(bounded.faces, test::mesh_from_lists(vertices, faces).faces);  // undone
  TriangleMesh mesh = test::mesh_from_lists(vertices, faces);
  const remesh::FollowedSegments followed =
      remesh::follow_segments(mesh, std::span(&segment, 1), {.min_angle_degrees = 0});
  EXPECT_EQ(followed.edges, 1);
  EXPECT_EQ(followed.flipped, 3);
  EXPECT_TRUE(has_edge(mesh, 0, 3));
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    EXPECT_GT((b - a).cross(c - a).z(), 0);
  }
}

}  // namespace
}  // namespace geodual
