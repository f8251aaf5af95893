// The remesh under an error bound (RemeshPipelineOptions::max_error_pct):
// remeshed again with more sites where it strayed, until the Hausdorff
// distance is within the bound, or the site limit stops it.

#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"

#include "remesh/analytic_surfaces.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace geodual {
namespace {

/// The bump's direction from the centre.
const Eigen::Vector3d kBump = Eigen::Vector3d(1, 2, 3).normalized();

/// The unit sphere (icosphere, 5,120 faces) pushed out into a narrow bump
/// (height 0.3, angular width 0.12) towards kBump: round but for one place a
/// coarse remesh cuts through.
io::LoadedMesh sphere_with_bump() {
  io::LoadedMesh loaded;
  loaded.mesh = test::icosphere(4);
  TriangleMesh& mesh = loaded.mesh;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d p = mesh.vertices.row(v).transpose();
    const double angle = std::acos(std::clamp(p.dot(kBump), -1.0, 1.0));
    mesh.vertices.row(v) *= 1 + 0.3 * std::exp(-angle * angle / (2 * 0.12 * 0.12));
  }
  return loaded;
}

pipeline::RemeshPipelineOptions bounded(double max_error_pct) {
  pipeline::RemeshPipelineOptions options;
  options.sites = 60;
  options.quality.samples_per_side = 20'000;
  options.max_error_pct = max_error_pct;
  return options;
}

/// The share of the remesh's vertices within 0.3 radians of the bump's axis.
double share_near_bump(const TriangleMesh& mesh) {
  int near = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    near += mesh.vertices.row(v).normalized().dot(kBump.transpose()) > std::cos(0.3);
  }
  return double(near) / double(mesh.num_vertices());
}

TEST(ErrorBound, RefinesWhereTheRemeshStraysUntilTheBoundHolds) {
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(sphere_with_bump(), bounded(0.5));
  const std::vector<pipeline::ErrorRound>& rounds = result.error_rounds;
  ASSERT_GE(rounds.size(), 2u);  // 60 sites cut through the bump
  EXPECT_EQ(rounds.front().sites, 60);
  EXPECT_GT(rounds.front().hausdorff_pct, 2.0);
  for (std::size_t r = 1; r < rounds.size(); ++r) EXPECT_GT(rounds[r].sites, rounds[r - 1].sites);
  EXPECT_TRUE(result.error_bound_met);
  ASSERT_TRUE(result.statistics.has_value());
  EXPECT_LE(result.statistics->hausdorff_pct, 0.5);
  EXPECT_EQ(result.statistics->hausdorff_pct, rounds.back().hausdorff_pct);  // the last round's remesh
  EXPECT_EQ(result.statistics->candidate.euler_characteristic, 2);
  // The sites went to the bump: far denser there than on a uniform remesh of
  // the same sphere.
  pipeline::RemeshPipelineOptions uniform = bounded(0);
  uniform.sites = rounds.back().sites;
  const double uniform_share = share_near_bump(pipeline::run_remesh_pipeline(sphere_with_bump(), uniform).remesh.mesh);
  EXPECT_GT(share_near_bump(result.remesh.mesh), 3 * uniform_share);
  // Every round's stages are timed.
  EXPECT_EQ(result.timings.size(), 4 * rounds.size());
}

TEST(ErrorBound, WhereARemeshKeptNoFeaturesTheNextStartsFromItsSites) {
  // Sharp features are on by default; the sphere has none. The rounds after
  // the first start from the last remesh's sites (relaxed: face points) and
  // add sites at the input's vertices where it strayed most, rather than
  // sampling afresh, which would lose the sites the last round put there.
  const pipeline::RemeshPipelineOptions options = bounded(0.5);
  ASSERT_GT(options.features.sampling.sharp_angle, 0);
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(sphere_with_bump(), options);
  ASSERT_GE(result.error_rounds.size(), 2u);
  EXPECT_TRUE(result.features.empty());
  const io::LoadedMesh input = sphere_with_bump();
  int at_vertices = 0, at_bump = 0;
  for (const SurfacePoint& site : result.initial_sites) {
    if (site.kind != SurfacePoint::Kind::vertex) continue;
    ++at_vertices;
    at_bump += input.mesh.vertices.row(site.element).normalized().dot(kBump.transpose()) > std::cos(0.3);
  }
  // The last round's start: the round before's sites (it needed no repair
  // on the sphere), and those added at vertices, some of them at the bump.
  const std::int64_t before = result.error_rounds[result.error_rounds.size() - 2].sites;
  EXPECT_EQ(static_cast<std::int64_t>(result.initial_sites.size()) - at_vertices, before);
  EXPECT_GT(at_vertices, 0);
  EXPECT_LE(at_vertices, result.error_rounds.back().sites - before);
  EXPECT_GT(at_bump, 0);
}

TEST(ErrorBound, ALaterRemeshMovesOnlyTheSitesNearThoseAdded) {
  // Refined locally (the default), the last remesh relaxes the sites within
  // two spacings of those added, on the restricted diagram alone, with one
  // exact diagram; the sites farther away stay where the last remesh had
  // them. Relaxed anew, every site moves.
  pipeline::RemeshPipelineOptions options = bounded(0.5);
  options.sites = 400;
  options.max_error_rounds = 2;
  ASSERT_TRUE(options.refine_locally);
  const pipeline::RemeshPipelineResult local = pipeline::run_remesh_pipeline(sphere_with_bump(), options);
  ASSERT_EQ(local.error_rounds.size(), 2u);
  EXPECT_LT(local.error_rounds.back().hausdorff_pct, local.error_rounds.front().hausdorff_pct);
  EXPECT_EQ(local.relaxation.iterations, 0);
  EXPECT_GT(local.relaxation.warm_start_iterations, 0);
  EXPECT_EQ(local.relaxation.diagrams, 1);
  const TriangleMesh& surface = local.surface.mesh;
  std::vector<Eigen::Vector3d> added;  // the sites added, at the input's vertices
  for (const SurfacePoint& site : local.initial_sites) {
    if (site.kind == SurfacePoint::Kind::vertex) added.push_back(site.position(surface));
  }
  ASSERT_GT(added.size(), 0u);
  const double spacing = std::sqrt(local.statistics->reference.area / static_cast<double>(local.initial_sites.size()));
  int far = 0, near_moved = 0;
  for (std::size_t i = 0; i < local.initial_sites.size(); ++i) {
    const Eigen::Vector3d p = local.initial_sites[i].position(surface);
    double nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& a : added) nearest = std::min(nearest, (p - a).norm());
    const bool same = local.relaxation.sites[i].position(surface) == p;
    if (nearest > 2.5 * spacing) {
      ++far;
      EXPECT_TRUE(same) << "site " << i << ", " << nearest / spacing << " spacings from the nearest added, moved";
    } else {
      near_moved += !same;
    }
  }
  EXPECT_GT(far, static_cast<int>(local.initial_sites.size()) / 3);
  EXPECT_GT(near_moved, static_cast<int>(added.size()));

  options.refine_locally = false;
  const pipeline::RemeshPipelineResult anew = pipeline::run_remesh_pipeline(sphere_with_bump(), options);
  ASSERT_EQ(anew.error_rounds.size(), 2u);
  int moved = 0;
  for (std::size_t i = 0; i < anew.initial_sites.size(); ++i) {
    moved += anew.relaxation.sites[i].position(surface) != anew.initial_sites[i].position(surface);
  }
  EXPECT_GT(moved, static_cast<int>(anew.initial_sites.size()) * 9 / 10);
}

TEST(ErrorBound, TheSiteLimitStopsItWithTheClosestRemesh) {
  pipeline::RemeshPipelineOptions options = bounded(0.5);
  options.max_sites = 150;
  std::vector<std::pair<int, std::int64_t>> announced;  // on_error_round's calls
  options.on_error_round = [&](int round, std::int64_t sites) { announced.emplace_back(round, sites); };
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(sphere_with_bump(), options);
  const std::vector<pipeline::ErrorRound>& rounds = result.error_rounds;
  ASSERT_EQ(rounds.size(), 2u);
  EXPECT_EQ(rounds.back().sites, 150);
  // Each remesh announced before it was made, numbered from 1, with its sites.
  ASSERT_EQ(announced.size(), rounds.size());
  for (std::size_t k = 0; k < rounds.size(); ++k) {
    EXPECT_EQ(announced[k].first, static_cast<int>(k) + 1);
    EXPECT_EQ(announced[k].second, rounds[k].sites);
  }
  EXPECT_FALSE(result.error_bound_met);
  double closest = rounds.front().hausdorff_pct;
  for (const pipeline::ErrorRound& round : rounds) closest = std::min(closest, round.hausdorff_pct);
  EXPECT_GT(closest, 0.5);
  EXPECT_EQ(result.statistics->hausdorff_pct, closest);

  // One round only: the first remesh, as without a bound but for the verdict.
  options.max_error_rounds = 1;
  const pipeline::RemeshPipelineResult once = pipeline::run_remesh_pipeline(sphere_with_bump(), options);
  EXPECT_EQ(once.error_rounds.size(), 1u);
  EXPECT_FALSE(once.error_bound_met);
  const pipeline::RemeshPipelineResult unbounded = pipeline::run_remesh_pipeline(sphere_with_bump(), bounded(0));
  EXPECT_TRUE(unbounded.error_rounds.empty());
  EXPECT_TRUE(unbounded.error_bound_met);
  EXPECT_EQ(once.remesh.mesh.vertices, unbounded.remesh.mesh.vertices);
}

TEST(ErrorBound, RefusesWhatItCannotWorkWith) {
  for (const double bad : {-1.0, 101.0, std::nan("")}) {
    EXPECT_THROW(pipeline::run_remesh_pipeline(sphere_with_bump(), bounded(bad)), UsageError) << bad;
  }
  pipeline::RemeshPipelineOptions no_statistics = bounded(0.5);
  no_statistics.statistics = false;
  EXPECT_THROW(pipeline::run_remesh_pipeline(sphere_with_bump(), no_statistics), UsageError);
  pipeline::RemeshPipelineOptions given = bounded(0.5);
  given.given_sites = std::vector<SurfacePoint>{SurfacePoint::at_vertex(0), SurfacePoint::at_vertex(1)};
  EXPECT_THROW(pipeline::run_remesh_pipeline(sphere_with_bump(), given), UsageError);
  pipeline::RemeshPipelineOptions no_rounds = bounded(0.5);
  no_rounds.max_error_rounds = 0;
  EXPECT_THROW(pipeline::run_remesh_pipeline(sphere_with_bump(), no_rounds), UsageError);
}

}  // namespace
}  // namespace geodual
