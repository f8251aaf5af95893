// The cut to a manifold at non-manifold edges: which faces stay joined.

#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "remesh/analytic_surfaces.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <numbers>
#include <vector>

namespace geodual {
namespace {

/// Triangle lists with vertices shared by position, so that grids built
/// apart share the vertices where they meet.
class MeshBuilder {
 public:
  /// A grid of n x m squares over point(u, v), u and v in [0, 1], two
  /// triangles each, oriented by the parametrisation.
  void grid(int n, int m, const std::function<Eigen::Vector3d(double, double)>& point) {
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) {
        const Index a = vertex(point(double(i) / n, double(j) / m));
        const Index b = vertex(point(double(i + 1) / n, double(j) / m));
        const Index c = vertex(point(double(i + 1) / n, double(j + 1) / m));
        const Index d = vertex(point(double(i) / n, double(j + 1) / m));
        faces_.push_back({a, b, c});
        faces_.push_back({a, c, d});
      }
    }
  }
  Index vertex(const Eigen::Vector3d& p) {
    // Rounded so that grid points computed two ways meet.
    const std::array<long long, 3> key = {std::llround(p.x() * 1e9), std::llround(p.y() * 1e9),
                                          std::llround(p.z() * 1e9)};
    const auto [at, inserted] = index_.try_emplace(key, static_cast<Index>(points_.size()));
    if (inserted) points_.push_back(p);
    return at->second;
  }
  void face(Index a, Index b, Index c) { faces_.push_back({a, b, c}); }
  TriangleMesh mesh() const { return test::mesh_from_lists(points_, faces_); }

 private:
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<Index, 3>> faces_;
  std::map<std::array<long long, 3>, Index> index_;
};

/// Expects `cut` to be an orientable 2-manifold of `pieces` pieces with
/// Euler characteristic `chi` and `loops` boundary loops.
void expect_orientable_manifold(const TriangleMesh& cut, std::int64_t pieces, std::int64_t chi, std::int64_t loops) {
  const MeshReport report = analyze_mesh(cut);
  EXPECT_EQ(report.nonmanifold_edges, 0);
  EXPECT_EQ(report.nonmanifold_vertices, 0);
  EXPECT_EQ(report.components, pieces);
  EXPECT_EQ(report.euler_characteristic, chi);
  EXPECT_EQ(report.boundary_loops, loops);
  EXPECT_TRUE(report.genus.has_value());  // orientable
}

TEST(ManifoldCut, AFlapGluedOntoASurfaceLeavesTheSurfaceWhole) {
  // A T-junction: a vertical flap standing on a plane along 8 of its edges.
  // The plane's two faces at each junction edge continue each other and stay
  // joined; the flap gets a boundary there. (Before: the plane was slit open
  // along the junction, a hole the remesh had to keep.)
  for (const bool flap_reversed : {false, true}) {
    SCOPED_TRACE(flap_reversed ? "flap reversed" : "flap");
    MeshBuilder builder;
    builder.grid(16, 8, [](double u, double v) { return Eigen::Vector3d(2 * u, v, 0); });
    builder.grid(8, 4,
                 [&](double u, double v) { return Eigen::Vector3d(0.5 + u, 0.5, flap_reversed ? -0.5 * v : 0.5 * v); });
    const TriangleMesh mesh = builder.mesh();
    ASSERT_EQ(analyze_mesh(mesh).nonmanifold_edges, 8);
    const remesh::ManifoldCut cut = remesh::cut_to_manifold(mesh);
    expect_orientable_manifold(cut.mesh, 2, 2, 2);  // two disks
    EXPECT_EQ(cut.vertices_split, 9);               // the junction's vertices, one copy for the flap
  }
}

TEST(ManifoldCut, TwoSheetsCrossingAtEdgesEachStayWhole) {
  // A vertical sheet through a horizontal one, sharing 8 edges: 4 faces at
  // each, two per sheet.
  MeshBuilder builder;
  builder.grid(16, 8, [](double u, double v) { return Eigen::Vector3d(2 * u, v, 0); });
  builder.grid(8, 8, [](double u, double v) { return Eigen::Vector3d(0.5 + u, 0.5, v - 0.5); });
  const TriangleMesh mesh = builder.mesh();
  ASSERT_EQ(analyze_mesh(mesh).nonmanifold_edges, 8);
  expect_orientable_manifold(remesh::cut_to_manifold(mesh).mesh, 2, 2, 2);
}

/// Expects `given` to be build_mesh_topology(mesh), field by field.
void expect_topology_of(const TriangleMesh& mesh, const MeshTopology& given) {
  const MeshTopology built = build_mesh_topology(mesh);
  EXPECT_EQ(given.edge_vertices, built.edge_vertices);
  EXPECT_EQ(given.edge_face_begin, built.edge_face_begin);
  EXPECT_EQ(given.edge_face_list, built.edge_face_list);
  EXPECT_EQ(given.face_edges, built.face_edges);
  EXPECT_EQ(given.vertex_on_boundary, built.vertex_on_boundary);
  EXPECT_EQ(given.corner_fan, built.corner_fan);
  EXPECT_EQ(given.face_component, built.face_component);
  EXPECT_EQ(given.vertex_component, built.vertex_component);
  EXPECT_EQ(given.edge_boundary_loop, built.edge_boundary_loop);
  ASSERT_EQ(given.num_components(), built.num_components());
  for (Index c = 0; c < built.num_components(); ++c) {
    EXPECT_EQ(given.components[c].euler_characteristic(), built.components[c].euler_characteristic());
    EXPECT_EQ(given.components[c].boundary_loops, built.components[c].boundary_loops);
  }
}

TEST(ManifoldCut, TheTopologyItGivesIsTheCutMeshsWhetherItCutOrNot) {
  // A plane alone: nothing to cut, the input's topology is handed on.
  MeshBuilder plane;
  plane.grid(8, 8, [](double u, double v) { return Eigen::Vector3d(u, v, 0); });
  MeshTopology topology;
  const TriangleMesh plane_mesh = plane.mesh();
  const remesh::ManifoldCut whole = remesh::cut_to_manifold(plane_mesh, {}, topology);
  EXPECT_EQ(whole.vertices_split, 0);
  EXPECT_EQ(whole.faces_disabled, 0);
  expect_topology_of(whole.mesh, topology);
  // Crossing sheets: split vertices, a topology of its own.
  MeshBuilder crossing;
  crossing.grid(16, 8, [](double u, double v) { return Eigen::Vector3d(2 * u, v, 0); });
  crossing.grid(8, 8, [](double u, double v) { return Eigen::Vector3d(0.5 + u, 0.5, v - 0.5); });
  const TriangleMesh crossing_mesh = crossing.mesh();
  const remesh::ManifoldCut cut = remesh::cut_to_manifold(crossing_mesh, {}, topology);
  EXPECT_GT(cut.vertices_split, 0);
  expect_topology_of(cut.mesh, topology);
  EXPECT_EQ(topology.num_components(), 2);
  // A scrap disabled (a lone triangle far off): a topology without it.
  MeshBuilder scrap;
  scrap.grid(8, 8, [](double u, double v) { return Eigen::Vector3d(u, v, 0); });
  scrap.face(scrap.vertex({5, 5, 5}), scrap.vertex({5.001, 5, 5}), scrap.vertex({5, 5.001, 5}));
  const TriangleMesh scrap_mesh = scrap.mesh();
  const remesh::ManifoldCut scrapped = remesh::cut_to_manifold(scrap_mesh, {}, topology);
  EXPECT_EQ(scrapped.faces_disabled, 1);
  expect_topology_of(scrapped.mesh, topology);
  EXPECT_EQ(topology.num_components(), 1);
}

TEST(ManifoldCut, NoJoinAtANonManifoldEdgeMakesAPieceNonOrientable) {
  // A band closed with a half twist, stored open at its seam (the faces there
  // run their edge the same way), and a flap on one of its rungs. Joining
  // the band's two faces at that rung, the most nearly coplanar pair, would
  // close a Moebius band: the flap joins one of them instead, and the band
  // stays a strip.
  const int n = 24, rung = n / 2;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * i / n;
    const Eigen::Vector3d centre(std::cos(t), std::sin(t), 0);
    const Eigen::Vector3d across = 0.2 * (std::cos(t / 2) * centre + std::sin(t / 2) * Eigen::Vector3d::UnitZ());
    points.push_back(centre + across);  // top i: 2 i
    points.push_back(centre - across);  // bottom i: 2 i + 1
  }
  std::vector<std::array<Index, 3>> faces;
  for (int i = 0; i < n; ++i) {
    const Index top = 2 * i, bottom = 2 * i + 1;
    // The half twist: past the last rung, top and bottom swap.
    const Index next_top = i + 1 < n ? 2 * (i + 1) : 1, next_bottom = i + 1 < n ? 2 * (i + 1) + 1 : 0;
    faces.push_back({top, bottom, next_bottom});
    faces.push_back({top, next_bottom, next_top});
  }
  // The flap's tip: outwards from the rung's middle, across the band.
  const double t = 2 * std::numbers::pi * rung / n;
  points.push_back(0.5 * (points[2 * rung] + points[2 * rung + 1]) +
                   0.3 * Eigen::Vector3d(std::cos(t), std::sin(t), 0));
  faces.push_back({2 * rung, 2 * rung + 1, static_cast<Index>(points.size() - 1)});
  const TriangleMesh mesh = test::mesh_from_lists(points, faces);
  ASSERT_EQ(analyze_mesh(mesh).nonmanifold_edges, 1);
  ASSERT_FALSE(analyze_mesh(mesh).genus.has_value());
  remesh::ManifoldCutOptions keep_all;
  keep_all.min_component_faces = 0;
  // A strip with the flap on one end: a disk.
  expect_orientable_manifold(remesh::cut_to_manifold(mesh, keep_all).mesh, 1, 1, 1);
}

}  // namespace
}  // namespace geodual
