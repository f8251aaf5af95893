// Curvature-adapted sizing: the density of curvature_density, and Lloyd
// relaxation towards the weighted CVT of a density (LloydOptions::density).

#include "remesh/analytic_surfaces.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/remesh/curvature_density.hpp"
#include "geodual/remesh/lloyd.hpp"
#include "geodual/remesh/remesh.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace geodual {
namespace {

TriangleMesh scan(const std::string& name) { return io::read_mesh("tests/data/" + name).mesh; }

/// The unit disk with a Gaussian bump of height `height` and width 0.25 at
/// its centre: curved there, flat towards the rim.
TriangleMesh bump(double height) {
  TriangleMesh mesh = test::disk(48, 192);
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const double r2 = mesh.vertices(v, 0) * mesh.vertices(v, 0) + mesh.vertices(v, 1) * mesh.vertices(v, 1);
    mesh.vertices(v, 2) = height * std::exp(-r2 / (0.25 * 0.25));
  }
  return mesh;
}

double radius(const TriangleMesh& mesh, Index v) { return std::hypot(mesh.vertices(v, 0), mesh.vertices(v, 1)); }

TEST(CurvatureDensity, FlatIsUniformAndBentIsDenser) {
  const double spacing = 0.1;
  const std::vector<double> flat = remesh::curvature_density(test::disk(24, 96), {.spacing = spacing});
  for (const double rho : flat) EXPECT_EQ(rho, 1.0);

  const TriangleMesh mesh = bump(0.3);
  const std::vector<double> rho = remesh::curvature_density(mesh, {.strength = 1, .spacing = spacing});
  double centre = 0, rim = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    EXPECT_GE(rho[v], 1.0);
    EXPECT_LE(rho[v], 16.0);
    if (radius(mesh, v) < 0.15) centre = std::max(centre, rho[v]);
    if (radius(mesh, v) > 0.8) rim = std::max(rim, rho[v]);
  }
  EXPECT_GT(centre, 2.0);
  EXPECT_LT(rim, 1.05);

  // Stronger means denser; the cap holds; strength 0 is uniform.
  const std::vector<double> strong =
      remesh::curvature_density(mesh, {.strength = 8, .spacing = spacing, .max_ratio = 3});
  const std::vector<double> none = remesh::curvature_density(mesh, {.strength = 0, .spacing = spacing});
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    EXPECT_LE(strong[v], 3.0);
    EXPECT_EQ(none[v], 1.0);
  }
  EXPECT_GT(*std::max_element(strong.begin(), strong.end()), 2.5);

  EXPECT_THROW((void)remesh::curvature_density(mesh, {.spacing = 0}), UsageError);
  EXPECT_THROW((void)remesh::curvature_density(mesh, {.strength = -1, .spacing = spacing}), UsageError);
  EXPECT_THROW((void)remesh::curvature_density(mesh, {.spacing = spacing, .max_ratio = 0.5}), UsageError);
}

/// rho = 16^((x + 1) / 2): 1 at x = -1, 16 at x = 1, smooth.
std::vector<double> ramp(const TriangleMesh& mesh) {
  std::vector<double> rho(static_cast<std::size_t>(mesh.num_vertices()));
  for (Index v = 0; v < mesh.num_vertices(); ++v) rho[v] = std::pow(16.0, (mesh.vertices(v, 0) + 1) / 2);
  return rho;
}

/// Sites with x > 0 over sites with x < 0.
double right_over_left(const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites) {
  double right = 0, left = 0;
  for (const SurfacePoint& site : sites) (site.position(mesh).x() > 0 ? right : left) += 1;
  return right / left;
}

TEST(WeightedLloyd, SitesGatherWhereTheDensityIsLargeAsRhoToTheHalf) {
  // A weighted CVT in 2D has about rho^(1/2) sites per unit area (spacing
  // rho^(-1/4)), so on the unit disk under the ramp the right half should
  // hold int_right rho^(1/2) / int_left rho^(1/2) times the sites of the left.
  const TriangleMesh disk = test::disk(40, 160);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(disk, 300, {.sites_on_boundary = false});
  remesh::LloydOptions uniform;
  uniform.iterations = 30;
  uniform.tolerance = uniform.geodesic_tolerance = 0;
  uniform.warm_start_iterations = 0;  // the weighted geodesic steps alone
  remesh::LloydOptions weighted = uniform;
  weighted.density = ramp(disk);
  const remesh::LloydResult plain = remesh::lloyd_relax(disk, sites, uniform);
  const remesh::LloydResult relaxed = remesh::lloyd_relax(disk, sites, weighted);

  double right = 0, left = 0;  // int rho^(1/2) over each half, midpoint rule on a fine grid
  const int n = 800;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = -1 + (i + 0.5) * 2.0 / n, y = -1 + (j + 0.5) * 2.0 / n;
      if (x * x + y * y > 1) continue;
      (x > 0 ? right : left) += std::pow(16.0, (x + 1) / 4);
    }
  }
  const double predicted = right / left;  // about 1.8
  const double before = right_over_left(disk, plain.sites), after = right_over_left(disk, relaxed.sites);
  std::printf("right/left sites: uniform CVT %.3f, weighted CVT %.3f, predicted %.3f\n", before, after, predicted);
  EXPECT_NEAR(before, 1.0, 0.15);
  EXPECT_NEAR(after, predicted, 0.2 * predicted);

  // The weighted energy never rises, and the weighted relaxation ends lower
  // in it than the uniform CVT's sites are.
  ASSERT_GE(relaxed.energy.size(), 10u);
  for (std::size_t i = 1; i < relaxed.energy.size(); ++i) EXPECT_LE(relaxed.energy[i], relaxed.energy[i - 1]);
  remesh::LloydOptions measure_only = weighted;
  measure_only.iterations = 0;
  const double uniform_sites_energy = remesh::lloyd_relax(disk, plain.sites, measure_only).energy.front();
  EXPECT_LT(relaxed.energy.back(), uniform_sites_energy);
}

TEST(WeightedLloyd, ConstantDensityIsTheUnweightedRelaxation) {
  const TriangleMesh mesh = bump(0.3);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(mesh, 200);
  remesh::LloydOptions plain;
  plain.iterations = 4;
  remesh::LloydOptions ones = plain;
  ones.density.assign(static_cast<std::size_t>(mesh.num_vertices()), 1.0);
  const remesh::LloydResult a = remesh::lloyd_relax(mesh, sites, plain), b = remesh::lloyd_relax(mesh, sites, ones);
  EXPECT_EQ(a.energy, b.energy);
  ASSERT_EQ(a.sites.size(), b.sites.size());
  for (std::size_t i = 0; i < a.sites.size(); ++i) EXPECT_EQ(a.sites[i].barycentric, b.sites[i].barycentric);
}

TEST(WeightedLloyd, BadDensitiesAreRefused) {
  const TriangleMesh disk = test::disk(8, 32);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(disk, 20);
  remesh::LloydOptions options;
  options.density.assign(static_cast<std::size_t>(disk.num_vertices()) - 1, 1.0);
  EXPECT_THROW((void)remesh::lloyd_relax(disk, sites, options), UsageError);
  options.density.assign(static_cast<std::size_t>(disk.num_vertices()), 1.0);
  options.density[3] = 0;
  EXPECT_THROW((void)remesh::lloyd_relax(disk, sites, options), UsageError);
  options.density[3] = std::nan("");
  EXPECT_THROW((void)remesh::lloyd_relax(disk, sites, options), UsageError);
}

TEST(WeightedLloyd, CurvatureAdaptedRemeshKeepsCountTopologyAndShrinksEdgesWhereBent) {
  const TriangleMesh mesh = scan("bunny.ply");
  const std::int64_t count = 1500;
  const std::vector<SurfacePoint> sites =
      remesh::sample_sites(mesh, count, {.strategy = remesh::SamplingStrategy::poisson});
  remesh::RemeshOptions options;
  options.lloyd.iterations = 8;
  options.curvature = remesh::CurvatureDensityOptions{.strength = 1};
  const remesh::RemeshResult result = remesh::remesh_from_sites(mesh, sites, options);
  EXPECT_EQ(result.dual.mesh.num_vertices(), count + result.dual.sites_added);
  for (std::size_t i = 1; i < result.relaxation.energy.size(); ++i)
    EXPECT_LE(result.relaxation.energy[i], result.relaxation.energy[i - 1]);
  const MeshReport in = analyze_mesh(mesh), out = analyze_mesh(result.dual.mesh);
  EXPECT_EQ(out.euler_characteristic, in.euler_characteristic);
  EXPECT_EQ(out.boundary_loops, in.boundary_loops);

  // Mean edge length around the remesh's vertices where the density is in
  // its top and bottom quarters (rho at the site's face, mean of its corners).
  const std::vector<double> rho = remesh::curvature_density(mesh, {.spacing = remesh::uniform_spacing(mesh, count)});
  std::vector<double> at(result.dual.sites.size()), length(result.dual.sites.size(), 0),
      edges(result.dual.sites.size(), 0);
  for (std::size_t i = 0; i < result.dual.sites.size(); ++i) {
    const SurfacePoint& s = result.dual.sites[i];
    at[i] = s.kind == SurfacePoint::Kind::vertex
                ? rho[s.element]
                : (rho[mesh.faces(s.element, 0)] + rho[mesh.faces(s.element, 1)] + rho[mesh.faces(s.element, 2)]) / 3;
  }
  for (Index f = 0; f < result.dual.mesh.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const Index a = result.dual.mesh.faces(f, c), b = result.dual.mesh.faces(f, (c + 1) % 3);
      const double l = (result.dual.mesh.vertices.row(a) - result.dual.mesh.vertices.row(b)).norm();
      length[a] += l, edges[a] += 1, length[b] += l, edges[b] += 1;
    }
  }
  std::vector<double> sorted = at;
  std::sort(sorted.begin(), sorted.end());
  const double low = sorted[sorted.size() / 4], high = sorted[3 * sorted.size() / 4];
  double sum_low = 0, n_low = 0, sum_high = 0, n_high = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    if (edges[i] == 0) continue;
    if (at[i] <= low) sum_low += length[i] / edges[i], n_low += 1;
    if (at[i] >= high) sum_high += length[i] / edges[i], n_high += 1;
  }
  ASSERT_GT(n_low, 0);
  ASSERT_GT(n_high, 0);
  EXPECT_LT(sum_high / n_high, 0.9 * sum_low / n_low);
}

}  // namespace
}  // namespace geodual
