// Closing the weld's cracks on their own vertices (remesh/src/dual/crack_fill.hpp):
// holes cut into a closed sphere come back closed, oriented as their
// neighbours; holes that are too long, or no simple cycle, are refused and
// the mesh left as it was.

#include "../../remesh/src/dual/crack_fill.hpp"

#include "analytic_surfaces.hpp"
#include "geodual/mesh/mesh_topology.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace geodual::remesh {
namespace {

/// `mesh` without the faces in `removed`.
TriangleMesh without_faces(const TriangleMesh& mesh, const std::set<Index>& removed) {
  TriangleMesh cut;
  cut.vertices = mesh.vertices;
  cut.faces.resize(mesh.num_faces() - static_cast<Index>(removed.size()), 3);
  Index row = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!removed.contains(f)) cut.faces.row(row++) = mesh.faces.row(f);
  }
  return cut;
}

/// Every edge has two faces, which run along it in opposite directions.
bool closed_and_oriented(const TriangleMesh& mesh) {
  std::map<std::pair<Index, Index>, int> half_edges;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) ++half_edges[{mesh.faces(f, k), mesh.faces(f, (k + 1) % 3)}];
  }
  return std::all_of(half_edges.begin(), half_edges.end(), [&](const auto& entry) {
    const auto opposite = half_edges.find({entry.first.second, entry.first.first});
    return entry.second == 1 && opposite != half_edges.end() && opposite->second == 1;
  });
}

/// The vertices of the boundary edges of `mesh`.
std::vector<Index> boundary_vertices(const TriangleMesh& mesh) {
  const MeshTopology topology = build_mesh_topology(mesh);
  std::vector<Index> vertices;
  for (Index e = 0; e < topology.num_edges(); ++e) {
    if (!topology.is_boundary_edge(e)) continue;
    vertices.insert(vertices.end(), topology.edge_vertices[e].begin(), topology.edge_vertices[e].end());
  }
  return vertices;
}

/// The faces round vertex v, in no particular order.
std::set<Index> faces_at(const TriangleMesh& mesh, Index v) {
  std::set<Index> faces;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (mesh.faces(f, 0) == v || mesh.faces(f, 1) == v || mesh.faces(f, 2) == v) faces.insert(f);
  }
  return faces;
}

TEST(CrackFill, ATriangularCrackIsClosedByOneTriangleOrientedAsItsNeighbours) {
  const TriangleMesh sphere = test::icosphere(2);
  TriangleMesh mesh = without_faces(sphere, {7});
  ASSERT_FALSE(closed_and_oriented(mesh));
  const std::optional<CrackFill> fill = close_cracks(mesh, boundary_vertices(mesh));
  ASSERT_TRUE(fill.has_value());
  EXPECT_EQ(fill->holes, 1);
  EXPECT_EQ(fill->triangles, 1);
  EXPECT_EQ(mesh.num_faces(), sphere.num_faces());
  EXPECT_TRUE(closed_and_oriented(mesh));
}

TEST(CrackFill, AHoleOfAVertexFanIsClosedWithoutItsCentre) {
  // The five or six faces round one vertex: a loop of as many edges, closed
  // by two fewer triangles on the loop's own vertices; the centre is left in
  // no triangle, and the other holes far from it are closed alike.
  const TriangleMesh sphere = test::icosphere(2);
  const std::set<Index> fan = faces_at(sphere, 20);
  TriangleMesh mesh = without_faces(sphere, fan);
  const std::optional<CrackFill> fill = close_cracks(mesh, boundary_vertices(mesh));
  ASSERT_TRUE(fill.has_value());
  EXPECT_EQ(fill->holes, 1);
  EXPECT_EQ(fill->triangles, static_cast<std::int64_t>(fan.size()) - 2);
  EXPECT_TRUE(faces_at(mesh, 20).empty());
  EXPECT_TRUE(closed_and_oriented(mesh));
}

TEST(CrackFill, OnlyTheLoopsThroughCrackVerticesAreClosed) {
  // Two triangular holes; only one is named by its vertices.
  const TriangleMesh sphere = test::icosphere(2);
  TriangleMesh mesh = without_faces(sphere, {3, 100});
  const std::vector<Index> first{sphere.faces(3, 0), sphere.faces(3, 1), sphere.faces(3, 2)};
  const std::optional<CrackFill> fill = close_cracks(mesh, first);
  ASSERT_TRUE(fill.has_value());
  EXPECT_EQ(fill->holes, 1);
  EXPECT_EQ(mesh.num_faces(), sphere.num_faces() - 1);
  EXPECT_EQ(boundary_vertices(mesh).size(), 6u);  // the other hole's three edges, two ends each
}

TEST(CrackFill, ALoopLongerThanTheBoundIsRefusedAndTheMeshKept) {
  const TriangleMesh sphere = test::icosphere(2);
  const std::set<Index> fan = faces_at(sphere, 20);
  TriangleMesh mesh = without_faces(sphere, fan);
  const TriangleMesh before = mesh;
  EXPECT_FALSE(close_cracks(mesh, boundary_vertices(mesh), static_cast<int>(fan.size()) - 1).has_value());
  EXPECT_EQ(mesh.faces, before.faces);
}

TEST(CrackFill, TwoHolesTouchingAtAVertexAreNoSimpleCycleAndAreRefused) {
  // Two faces of one fan that share only its centre: their holes make one
  // boundary loop through the centre twice.
  const TriangleMesh sphere = test::icosphere(2);
  const std::set<Index> fan = faces_at(sphere, 20);
  const auto shares_an_edge = [&](Index f, Index g) {
    int shared = 0;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) shared += sphere.faces(f, i) == sphere.faces(g, j);
    }
    return shared == 2;
  };
  const Index first = *fan.begin();
  const auto second =
      std::find_if(fan.begin(), fan.end(), [&](Index g) { return g != first && !shares_an_edge(first, g); });
  ASSERT_NE(second, fan.end());
  TriangleMesh mesh = without_faces(sphere, {first, *second});
  const TriangleMesh before = mesh;
  EXPECT_FALSE(close_cracks(mesh, boundary_vertices(mesh)).has_value());
  EXPECT_EQ(mesh.faces, before.faces);
}

}  // namespace
}  // namespace geodual::remesh
