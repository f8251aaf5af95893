// normal_turn_degrees and sharp_edges on hand-built folds: a flat pair, a
// right-angled fold, a fold stored misoriented, a needle and a boundary edge;
// and sharp_edges against its definition on folds of every angle.

#include "mesh/small_meshes.hpp"

#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/sharp_edges.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace geodual {
namespace {

using test::make_mesh;

/// The edge between vertices a and b.
Index edge_of(const MeshTopology& topology, Index a, Index b) {
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto [u, v] = topology.edge_vertices[static_cast<std::size_t>(e)];
    if ((u == a && v == b) || (u == b && v == a)) return e;
  }
  return -1;
}

TEST(SharpEdges, FlatPairTurnsByNothingAndRightFoldByNinety) {
  // Two faces on the shared edge 0-1; the fourth vertex flat, then raised.
  const TriangleMesh flat = make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}}, {{0, 1, 2}, {1, 0, 3}});
  const TriangleMesh fold = make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, 0, 1}}, {{0, 1, 2}, {1, 0, 3}});
  const MeshTopology flat_topology = build_mesh_topology(flat), fold_topology = build_mesh_topology(fold);
  EXPECT_NEAR(normal_turn_degrees(flat, flat_topology, edge_of(flat_topology, 0, 1)), 0.0, 1e-12);
  EXPECT_NEAR(normal_turn_degrees(fold, fold_topology, edge_of(fold_topology, 0, 1)), 90.0, 1e-12);
  EXPECT_TRUE(sharp_edges(flat, flat_topology, 30).empty());
  EXPECT_EQ(sharp_edges(fold, fold_topology, 89.9), std::vector<Index>{edge_of(fold_topology, 0, 1)});
  EXPECT_TRUE(sharp_edges(fold, fold_topology, 90.1).empty());
}

TEST(SharpEdges, MisorientedFaceIsJudgedAsIfFlipped) {
  // The second face runs 0 -> 1 as the first does: its normal counts flipped.
  const TriangleMesh flat = make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}}, {{0, 1, 2}, {0, 1, 3}});
  const MeshTopology topology = build_mesh_topology(flat);
  EXPECT_NEAR(normal_turn_degrees(flat, topology, edge_of(topology, 0, 1)), 0.0, 1e-12);
}

TEST(SharpEdges, BoundaryEdgesAndFacesWithoutAreaAreNeverSharp) {
  // Face 1 is collinear (no normal); edge 1-2 of face 0 has one face.
  const TriangleMesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {2, 0, 0}}, {{0, 1, 2}, {1, 0, 3}});
  const MeshTopology topology = build_mesh_topology(mesh);
  EXPECT_TRUE(std::isnan(normal_turn_degrees(mesh, topology, edge_of(topology, 0, 1))));
  EXPECT_TRUE(std::isnan(normal_turn_degrees(mesh, topology, edge_of(topology, 1, 2))));
  EXPECT_TRUE(sharp_edges(mesh, topology, 1).empty());
}

TEST(SharpEdges, AreExactlyTheEdgesWhoseNormalsTurnByTheAngleOrMore) {
  // Separate folds turning by every half degree from 0 to 179.5 and by a
  // hair either side of each angle asked, half of them stored misoriented:
  // sharp_edges is its definition, normal_turn_degrees >= the angle.
  const std::vector<double> angles = {1e-3, 30, 60, 90, 179};
  std::vector<double> turns;
  for (int k = 0; k < 360; ++k) turns.push_back(0.5 * k);
  for (const double angle : angles) {
    for (const double hair : {-1e-9, -1e-12, 0.0, 1e-12, 1e-9}) turns.push_back(angle + hair);
  }
  TriangleMesh folds;
  folds.vertices.resize(4 * static_cast<Eigen::Index>(turns.size()), 3);
  folds.faces.resize(2 * static_cast<Eigen::Index>(turns.size()), 3);
  for (Index i = 0; i < static_cast<Index>(turns.size()); ++i) {
    const double turn = turns[static_cast<std::size_t>(i)] * std::numbers::pi / 180, z = 3.0 * i;
    folds.vertices.row(4 * i) << 0, 0, z;
    folds.vertices.row(4 * i + 1) << 1, 0, z;
    folds.vertices.row(4 * i + 2) << 0.5, 1, z;
    folds.vertices.row(4 * i + 3) << 0.5, -std::cos(turn), z + std::sin(turn);
    folds.faces.row(2 * i) << 4 * i, 4 * i + 1, 4 * i + 2;
    if (i % 2 == 0) {
      folds.faces.row(2 * i + 1) << 4 * i + 1, 4 * i, 4 * i + 3;
    } else {
      folds.faces.row(2 * i + 1) << 4 * i, 4 * i + 1, 4 * i + 3;  // misoriented
    }
  }
  const MeshTopology topology = build_mesh_topology(folds);
  for (const double angle : angles) {
    SCOPED_TRACE(angle);
    std::vector<Index> by_definition;
    for (Index e = 0; e < topology.num_edges(); ++e) {
      if (normal_turn_degrees(folds, topology, e) >= angle) by_definition.push_back(e);
    }
    EXPECT_FALSE(by_definition.empty());
    EXPECT_EQ(sharp_edges(folds, topology, angle), by_definition);
  }
}

}  // namespace
}  // namespace geodual
