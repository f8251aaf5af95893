// A remesh keeps every piece and every hole: sample_sites_for_topology gives
// every component its minimum (4 sites, 3 per boundary loop), raising the
// count where it is too small, and says how many it added and why.

#include "analytic_surfaces.hpp"
#include "hard_cases.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/remesh/remesh.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace geodual::remesh {
namespace {

TEST(SitesForTopology, SitesGivenOnAPiecesBorderStandForHalfACellOfItsArea) {
  // Two unit squares; the first has a given site at each of its 40 border
  // vertices (as a crease's sites are on the cut's border), and 200 more are
  // placed. Shared by area alone, each square gets 100 of them. With the
  // given sites standing for half a cell each (20 in all), the squares share
  // 220 by area, the first less its 20: 90 and 110.
  const TriangleMesh square = test::unit_square(10);
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<Index, 3>> faces;
  for (const double shift : {0.0, 3.0}) {
    const auto offset = static_cast<Index>(vertices.size());
    for (Index v = 0; v < square.num_vertices(); ++v) {
      vertices.push_back(square.vertices.row(v).transpose() + Eigen::Vector3d(shift, 0, 0));
    }
    for (Index f = 0; f < square.num_faces(); ++f) {
      faces.push_back({square.faces(f, 0) + offset, square.faces(f, 1) + offset, square.faces(f, 2) + offset});
    }
  }
  const TriangleMesh mesh = test::mesh_from_lists(vertices, faces);
  std::vector<SurfacePoint> given;
  for (int j = 0; j <= 10; ++j) {
    for (int i = 0; i <= 10; ++i) {
      if (i == 0 || i == 10 || j == 0 || j == 10) given.push_back(SurfacePoint::at_vertex(j * 11 + i));
    }
  }
  ASSERT_EQ(given.size(), 40u);
  const auto on_first_square = [&](const SampledSites& sampled) {
    std::int64_t count = 0;
    for (std::size_t s = given.size(); s < sampled.sites.size(); ++s) {
      count += sampled.sites[s].position(mesh).x() < 2 ? 1 : 0;
    }
    return count;
  };
  const SampledSites by_area = sample_sites_around(mesh, 200, given, {}, GivenSiteShare::none);
  ASSERT_EQ(by_area.sites.size(), 240u);
  EXPECT_EQ(on_first_square(by_area), 100);
  const SampledSites half_cells = sample_sites_around(mesh, 200, given);
  ASSERT_EQ(half_cells.sites.size(), 240u);
  EXPECT_EQ(on_first_square(half_cells), 90);
}

TEST(SitesForTopology, EveryPieceOfAnAssemblyGetsItsSitesAndIsRemeshed) {
  // 47 closed pieces: 188 sites at least. With 10, 40 or 100 sites the
  // remesh used to keep 3, 10 and 25 of them.
  const TriangleMesh mesh = cut_to_manifold(bench::assembly_47()).mesh;
  const MeshTopology topology = build_mesh_topology(mesh);
  ASSERT_EQ(topology.num_components(), 47);
  for (const std::int64_t count : {10, 100}) {
    SCOPED_TRACE(std::to_string(count) + " sites asked");
    const SampledSites sampled = sample_sites_for_topology(mesh, count);
    ASSERT_EQ(sampled.sites.size(), 188u);
    EXPECT_EQ(sampled.sites_added_for_topology, 188 - count);
    EXPECT_NE(sampled.topology_reason.find("raised to 188"), std::string::npos) << sampled.topology_reason;
    EXPECT_NE(sampled.topology_reason.find("47 pieces"), std::string::npos) << sampled.topology_reason;
    std::vector<int> per_piece(47, 0);
    for (const SurfacePoint& site : sampled.sites) ++per_piece[topology.face_component[site.element]];
    for (int c = 0; c < 47; ++c) EXPECT_GE(per_piece[c], 4) << "piece " << c;
  }
  RemeshOptions options;
  options.lloyd.iterations = 3;
  const RemeshResult result = remesh_from_sites(mesh, sample_sites_for_topology(mesh, 40).sites, options);
  const MeshReport out = analyze_mesh(result.dual.mesh);
  EXPECT_EQ(out.components, 47);
  EXPECT_EQ(out.euler_characteristic, 94);
  EXPECT_EQ(out.boundary_loops, 0);
}

TEST(SitesForTopology, BoundaryLoopsGetTheirSites) {
  // Six loops: 18 sites.
  const TriangleMesh plate = bench::plate_with_holes();
  const SampledSites sampled = sample_sites_for_topology(plate, 10);
  EXPECT_EQ(sampled.sites.size(), 18u);
  EXPECT_EQ(sampled.sites_added_for_topology, 8);
  EXPECT_EQ(sampled.boundary_loops, 6);
  EXPECT_NE(sampled.topology_reason.find("6 boundary loops"), std::string::npos) << sampled.topology_reason;
  // sample_sites keeps to the count asked and says what is missing.
  EXPECT_THROW(sample_sites(plate, 10), UsageError);
}

TEST(SitesForTopology, EnoughSitesAreTheSitesOfSampleSites) {
  const TriangleMesh mesh = cut_to_manifold(bench::assembly_47()).mesh;
  for (const SamplingStrategy strategy : {SamplingStrategy::random, SamplingStrategy::poisson, SamplingStrategy::fps}) {
    const SamplingOptions options{.strategy = strategy, .seed = 7};
    const SampledSites sampled = sample_sites_for_topology(mesh, 300, options);
    EXPECT_EQ(sampled.sites_added_for_topology, 0);
    EXPECT_TRUE(sampled.topology_reason.empty());
    const std::vector<SurfacePoint> plain = sample_sites(mesh, 300, options);
    ASSERT_EQ(sampled.sites.size(), plain.size());
    for (std::size_t i = 0; i < plain.size(); ++i) {
      ASSERT_EQ(sampled.sites[i].element, plain[i].element) << i;
      ASSERT_EQ(sampled.sites[i].barycentric, plain[i].barycentric) << i;
    }
  }
  EXPECT_THROW(sample_sites_for_topology(mesh, 3), UsageError);
}

}  // namespace
}  // namespace geodual::remesh
