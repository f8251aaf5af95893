// The restricted Voronoi diagram of Lloyd's warm start: on a plane it is the
// geodesic diagram (an independent computation from the exact geodesics),
// its cells tile a closed surface, and threads do not change it.

#include "../../remesh/src/relax/restricted_voronoi.hpp"
#include "remesh/analytic_surfaces.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/remesh/sample_sites.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include "geodual/mesh/error.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <map>
#include <utility>

namespace geodual {
namespace {

double surface_area(const TriangleMesh& mesh) {
  double area = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    area += (b - a).cross(c - a).norm() / 2;
  }
  return area;
}

TEST(RestrictedVoronoi, IsTheGeodesicDiagramOnAPlane) {
  // On a flat convex disk geodesic distance is Euclidean distance, so the
  // engine's exact diagram and the restricted one must agree: cell areas,
  // first moments, energies and the length of each shared boundary.
  const TriangleMesh disk = test::disk(24, 96);
  const std::vector<SurfacePoint> sites =
      remesh::sample_sites(disk, 150, {.strategy = remesh::SamplingStrategy::poisson});
  const voronoi::VoronoiDiagram geodesic = voronoi::compute_voronoi(disk, sites);
  const remesh::detail::RestrictedCells restricted = remesh::detail::restricted_voronoi(
      remesh::detail::prepare_restricted_surface(disk, *geodesic.field.topology, {}), sites);
  const double area = surface_area(disk);
  for (std::size_t s = 0; s < sites.size(); ++s) {
    SCOPED_TRACE(s);
    EXPECT_NEAR(restricted.area[s], geodesic.cell_area[s], 1e-10 * area);
    EXPECT_NEAR(restricted.mass[s], restricted.area[s], 1e-14 * area);  // no density: rho = 1
    EXPECT_NEAR(restricted.energy[s], geodesic.cell_energy[s], 1e-9 * geodesic.cell_energy[s]);
    // On a plane the log map at the site is x - site.
    EXPECT_LT((restricted.moment[s] - geodesic.cell_log_moment[s]).norm(), 1e-10 * area);
  }
  std::map<std::pair<Index, Index>, double> length;
  for (const auto& boundary : restricted.boundaries) {
    ASSERT_LT(boundary.site, boundary.other);
    for (Index k = boundary.begin; k < boundary.end; k += 2) {
      length[{boundary.site, boundary.other}] += (restricted.segment_ends[k + 1] - restricted.segment_ends[k]).norm();
    }
  }
  EXPECT_EQ(length.size(), geodesic.adjacency.size());
  for (const voronoi::CellAdjacency& pair : geodesic.adjacency) {
    const double restricted_length = length[std::pair(pair.site_a, pair.site_b)];
    EXPECT_NEAR(restricted_length, pair.boundary_length, 1e-9) << pair.site_a << " " << pair.site_b;
  }
}

TEST(RestrictedVoronoi, CellsTileAClosedSurface) {
  const TriangleMesh sphere = test::icosphere(4);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(sphere, 300);
  const voronoi::GeodesicField topology = voronoi::compute_geodesic_field(sphere, sites);
  const remesh::detail::RestrictedCells cells = remesh::detail::restricted_voronoi(
      remesh::detail::prepare_restricted_surface(sphere, *topology.topology, {}), sites);
  double total = 0;
  for (std::size_t s = 0; s < sites.size(); ++s) {
    EXPECT_GT(cells.area[s], 0);
    total += cells.area[s];
  }
  EXPECT_NEAR(total, surface_area(sphere), 1e-12 * surface_area(sphere));
  // A density doubles the mass where it is 2, the moments and energies with it.
  const std::vector<double> two(static_cast<std::size_t>(sphere.num_vertices()), 2.0);
  const remesh::detail::RestrictedCells weighted = remesh::detail::restricted_voronoi(
      remesh::detail::prepare_restricted_surface(sphere, *topology.topology, two), sites);
  for (std::size_t s = 0; s < sites.size(); ++s) {
    EXPECT_DOUBLE_EQ(weighted.area[s], cells.area[s]);
    EXPECT_NEAR(weighted.mass[s], 2 * cells.mass[s], 1e-12 * cells.mass[s]);
    EXPECT_NEAR(weighted.energy[s], 2 * cells.energy[s], 1e-12 * cells.energy[s]);
  }
}

TEST(RestrictedVoronoi, VertexSitesNeedASurfacePreparedForThem) {
  // A site at a vertex starts its cell from the faces round it: with them
  // kept, its cell is as large as its neighbours'; without them, an error.
  const TriangleMesh sphere = test::icosphere(3);
  std::vector<SurfacePoint> sites = remesh::sample_sites(sphere, 50);
  sites.push_back(SurfacePoint::at_vertex(0));
  const voronoi::GeodesicField topology = voronoi::compute_geodesic_field(sphere, sites);
  const remesh::detail::RestrictedCells cells = remesh::detail::restricted_voronoi(
      remesh::detail::prepare_restricted_surface(sphere, *topology.topology, {}, true), sites);
  EXPECT_GT(cells.area.back(), 0.1 * surface_area(sphere) / 51);
  EXPECT_THROW(remesh::detail::restricted_voronoi(
                   remesh::detail::prepare_restricted_surface(sphere, *topology.topology, {}, false), sites),
               Error);
}

TEST(RestrictedVoronoi, OfTwoSitesAtOnePlaceTheFirstTakesTheCell) {
  const TriangleMesh sphere = test::icosphere(3);
  std::vector<SurfacePoint> sites = remesh::sample_sites(sphere, 50);
  const voronoi::GeodesicField topology = voronoi::compute_geodesic_field(sphere, sites);
  const remesh::detail::RestrictedCells single = remesh::detail::restricted_voronoi(
      remesh::detail::prepare_restricted_surface(sphere, *topology.topology, {}), sites);
  sites.push_back(sites[7]);
  const remesh::detail::RestrictedCells doubled = remesh::detail::restricted_voronoi(
      remesh::detail::prepare_restricted_surface(sphere, *topology.topology, {}), sites);
  EXPECT_EQ(doubled.area.back(), 0.0);
  EXPECT_EQ(doubled.mass.back(), 0.0);
  EXPECT_NEAR(doubled.area[7], single.area[7], 1e-12);
}

TEST(RestrictedVoronoi, CellsAskedForAloneAreThoseOfTheWholeDiagram) {
  // Each cell is cut by every site either way: the cells flagged come out
  // bit for bit as in the whole diagram, with the boundaries whose first
  // site is flagged; the others are left empty.
  const TriangleMesh sphere = test::icosphere(4);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(sphere, 300);
  const voronoi::GeodesicField topology = voronoi::compute_geodesic_field(sphere, std::span(sites).first(1));
  const remesh::detail::RestrictedSurface surface =
      remesh::detail::prepare_restricted_surface(sphere, *topology.topology, {});
  const remesh::detail::RestrictedCells whole = remesh::detail::restricted_voronoi(surface, sites);
  std::vector<std::uint8_t> only(sites.size(), 0);
  for (std::size_t s = 0; s < sites.size(); s += 3) only[s] = 1;
  const remesh::detail::RestrictedCells some = remesh::detail::restricted_voronoi(surface, sites, only);
  for (std::size_t s = 0; s < sites.size(); ++s) {
    SCOPED_TRACE(s);
    if (only[s]) {
      EXPECT_EQ(some.area[s], whole.area[s]);
      EXPECT_EQ(some.mass[s], whole.mass[s]);
      EXPECT_EQ(some.moment[s], whole.moment[s]);
      EXPECT_EQ(some.energy[s], whole.energy[s]);
    } else {
      EXPECT_EQ(some.area[s], 0.0);
      EXPECT_EQ(some.energy[s], 0.0);
    }
  }
  std::vector<remesh::detail::RestrictedBoundary> expected;
  for (const remesh::detail::RestrictedBoundary& boundary : whole.boundaries) {
    if (only[boundary.site]) expected.push_back(boundary);
  }
  ASSERT_EQ(some.boundaries.size(), expected.size());
  ASSERT_GT(expected.size(), 100u);
  for (std::size_t b = 0; b < expected.size(); ++b) {
    const remesh::detail::RestrictedBoundary &got = some.boundaries[b], &want = expected[b];
    ASSERT_EQ(std::pair(got.site, got.other), std::pair(want.site, want.other));
    EXPECT_EQ(got.density, want.density);
    ASSERT_EQ(got.end - got.begin, want.end - want.begin);
    for (Index k = 0; k < got.end - got.begin; ++k) {
      EXPECT_EQ(some.segment_ends[got.begin + k], whole.segment_ends[want.begin + k]);
    }
  }
  EXPECT_THROW(remesh::detail::restricted_voronoi(surface, sites, std::vector<std::uint8_t>(3, 1)), Error);
}

TEST(RestrictedVoronoi, OneOrTwoThreadsGiveTheSameCells) {
  const TriangleMesh mesh = io::read_mesh("tests/data/bunny.ply").mesh;
  const std::vector<SurfacePoint> sites = remesh::sample_sites(mesh, 2000);
  const voronoi::GeodesicField topology = voronoi::compute_geodesic_field(mesh, std::span(sites).first(1));
  remesh::detail::RestrictedCells one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = remesh::detail::restricted_voronoi(remesh::detail::prepare_restricted_surface(mesh, *topology.topology, {}),
                                             sites);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = remesh::detail::restricted_voronoi(remesh::detail::prepare_restricted_surface(mesh, *topology.topology, {}),
                                             sites);
  }
  EXPECT_EQ(one.area, two.area);
  EXPECT_EQ(one.moment, two.moment);
  EXPECT_EQ(one.energy, two.energy);
  EXPECT_EQ(one.segment_ends, two.segment_ends);
  ASSERT_EQ(one.boundaries.size(), two.boundaries.size());
  // The scan's holes and cut-off pieces aside, the cells cover it.
  double total = 0;
  for (const double a : one.area) total += a;
  EXPECT_GT(total, 0.99 * surface_area(mesh));
  EXPECT_LE(total, surface_area(mesh) * (1 + 1e-12));
}

}  // namespace
}  // namespace geodual
