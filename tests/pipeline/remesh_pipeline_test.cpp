// The C++ pipeline: every stage timed in order, the result holds every
// intermediate, and the progress callback can cancel.

#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/remesh/sizing.hpp"
#include "hard_cases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace geodual {
namespace {

constexpr const char* genus_four = "tests/data/fertility.ply";

pipeline::RemeshPipelineOptions small_options() {
  pipeline::RemeshPipelineOptions options;
  options.sites = 400;
  options.remesh.lloyd.iterations = 2;
  options.quality.samples_per_side = 20'000;
  return options;
}

TEST(RemeshPipeline, RunsEveryStageAndKeepsEveryIntermediate) {
  std::vector<pipeline::Stage> seen;
  pipeline::RemeshPipelineOptions options = small_options();
  options.progress = [&](pipeline::Stage stage, double fraction) {
    EXPECT_GE(fraction, 0.0);
    EXPECT_LE(fraction, 1.0);
    if (seen.empty() || seen.back() != stage) seen.push_back(stage);
    return true;
  };
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(genus_four, options);
  EXPECT_EQ(result.input_report.euler_characteristic, -6);
  EXPECT_EQ(result.initial_sites.size(), 400u);
  EXPECT_EQ(result.remesh.mesh.vertices.rows(), 400 + result.remesh.sites_added);
  // The warm start's sites, then each iteration's.
  EXPECT_GT(result.relaxation.warm_start_iterations, 0);
  EXPECT_EQ(result.relaxation.energy.size(), static_cast<std::size_t>(result.relaxation.iterations) + 1);
  ASSERT_TRUE(result.statistics.has_value());
  EXPECT_EQ(result.statistics->candidate.euler_characteristic, -6);
  EXPECT_GT(result.statistics->hausdorff_pct, 0);
  std::vector<pipeline::Stage> timed;
  for (const pipeline::StageTiming& timing : result.timings) {
    timed.push_back(timing.stage);
    EXPECT_GE(timing.seconds, 0);
    EXPECT_GT(timing.peak_memory_bytes, 0);
  }
  const std::vector<pipeline::Stage> expected = {pipeline::Stage::load, pipeline::Stage::sample, pipeline::Stage::relax,
                                                 pipeline::Stage::dual, pipeline::Stage::statistics};
  EXPECT_EQ(timed, expected);
  EXPECT_EQ(seen.front(), pipeline::Stage::load);
  EXPECT_EQ(seen.back(), pipeline::Stage::statistics);
}

TEST(RemeshPipeline, RelaxProgressRisesAndEndsWithTheRelaxationEvenWhenStepsAreRejected) {
  pipeline::RemeshPipelineOptions options = small_options();
  options.remesh.lloyd.iterations = 4;
  options.remesh.lloyd.tolerance = 0;
  // Undamped, unbounded Newton steps: some overshoot and are rejected, each
  // costing a diagram that is not an iteration.
  options.remesh.lloyd.newton_damping = 1e-9;
  options.remesh.lloyd.newton_max_step = 1e9;
  std::vector<pipeline::Stage> seen;
  double relax_fraction = 0;
  options.progress = [&](pipeline::Stage stage, double fraction) {
    if (seen.empty() || seen.back() != stage) seen.push_back(stage);
    if (stage == pipeline::Stage::relax) {
      EXPECT_GE(fraction, relax_fraction);
      relax_fraction = fraction;
    }
    return true;
  };
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(genus_four, options);
  ASSERT_GT(result.relaxation.diagrams, result.relaxation.iterations + 1);  // the case this test is about
  const std::vector<pipeline::Stage> expected = {pipeline::Stage::load, pipeline::Stage::sample, pipeline::Stage::relax,
                                                 pipeline::Stage::dual, pipeline::Stage::statistics};
  EXPECT_EQ(seen, expected);
  EXPECT_LE(relax_fraction, 1.0);
}

TEST(RemeshPipeline, RelaxProgressCountsEveryIterationWhenTheGeodesicToleranceIsOff) {
  // Without the geodesic tolerance's stop every iteration runs: the relax
  // stage must not report itself done after the first two diagrams.
  pipeline::RemeshPipelineOptions options = small_options();
  options.statistics = false;
  options.remesh.lloyd.iterations = 6;
  options.remesh.lloyd.tolerance = 0;
  options.remesh.lloyd.geodesic_tolerance = 0;
  std::vector<double> relax;
  options.progress = [&](pipeline::Stage stage, double fraction) {
    if (stage == pipeline::Stage::relax) relax.push_back(fraction);
    return true;
  };
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(genus_four, options);
  ASSERT_GE(result.relaxation.iterations, 4);
  ASSERT_FALSE(relax.empty());
  const auto first_done =
      std::find_if(relax.begin(), relax.end(), [](double fraction) { return fraction >= 0.99; }) - relax.begin();
  EXPECT_GT(static_cast<double>(first_done), 0.6 * static_cast<double>(relax.size()))
      << first_done << " of " << relax.size() << " reports";
}

TEST(RemeshPipeline, TheProgressCallbackCancels) {
  pipeline::RemeshPipelineOptions options = small_options();
  options.progress = [](pipeline::Stage stage, double fraction) {
    return !(stage == pipeline::Stage::relax && fraction > 0.3);
  };
  EXPECT_THROW(pipeline::run_remesh_pipeline(genus_four, options), Cancelled);
}

TEST(RemeshPipeline, GivenSitesReplaceSampling) {
  pipeline::RemeshPipelineOptions options = small_options();
  const io::LoadedMesh loaded = io::read_mesh(genus_four);
  options.given_sites = remesh::sample_sites(loaded.mesh, 300, {remesh::SamplingStrategy::fps, 4, true});
  options.statistics = false;
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(genus_four, options);
  ASSERT_EQ(result.initial_sites.size(), 300u);
  EXPECT_FALSE(result.statistics.has_value());
  for (std::size_t i = 0; i < 300; ++i) {
    EXPECT_EQ(result.initial_sites[i].element, (*options.given_sites)[i].element);
  }
  EXPECT_EQ(pipeline::stage_name(pipeline::Stage::relax), "relax");
}

TEST(RemeshPipeline, AFaceCountOrEdgeLengthSetsTheSites) {
  pipeline::RemeshPipelineOptions options = small_options();
  options.statistics = false;
  options.sites = 17;  // unused with a sizing
  options.faces = 800;
  const pipeline::RemeshPipelineResult by_faces = pipeline::run_remesh_pipeline(genus_four, options);
  // Closed, chi = -6: V = 800 / 2 - 6.
  EXPECT_EQ(by_faces.sites_for_sizing, 394);
  EXPECT_EQ(by_faces.initial_sites.size(), 394u);
  EXPECT_EQ(by_faces.remesh.mesh.num_faces(), 2 * (394 + by_faces.remesh.sites_added) + 12);  // F = 2 (V - chi)

  options.faces = 0;
  options.edge_length = 10;
  const pipeline::RemeshPipelineResult by_length = pipeline::run_remesh_pipeline(genus_four, options);
  EXPECT_EQ(by_length.sites_for_sizing, remesh::sites_for_edge_length(by_length.surface.mesh, 10));
  EXPECT_EQ(static_cast<std::int64_t>(by_length.initial_sites.size()), by_length.sites_for_sizing);

  // Without a sizing the count is options.sites and nothing is recorded.
  const pipeline::RemeshPipelineResult plain = pipeline::run_remesh_pipeline(genus_four, small_options());
  EXPECT_EQ(plain.sites_for_sizing, 0);
}

TEST(RemeshPipeline, MoreThanOneSiteSourceIsAUsageError) {
  const io::LoadedMesh loaded = io::read_mesh(genus_four);
  pipeline::RemeshPipelineOptions options = small_options();
  options.edge_length = 10;
  options.faces = 800;
  EXPECT_THROW(pipeline::run_remesh_pipeline(loaded, options), UsageError);
  options.edge_length = 0;
  options.given_sites = remesh::sample_sites(loaded.mesh, 300);
  EXPECT_THROW(pipeline::run_remesh_pipeline(loaded, options), UsageError);
  options.given_sites.reset();
  options.faces = -5;
  EXPECT_THROW(pipeline::run_remesh_pipeline(loaded, options), UsageError);
  options.faces = 0;
  options.edge_length = -1;
  EXPECT_THROW(pipeline::run_remesh_pipeline(loaded, options), UsageError);
}

TEST(RemeshPipeline, FeatureAndRepairOptionsOutOfRangeAreUsageErrorsNamingThem) {
  const io::LoadedMesh loaded = io::read_mesh(genus_four);
  const auto message = [&](auto change) {
    pipeline::RemeshPipelineOptions options = small_options();
    change(options);
    try {
      pipeline::run_remesh_pipeline(loaded, options);
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  using Options = pipeline::RemeshPipelineOptions;
  EXPECT_NE(message([](Options& o) { o.features.sampling.sharp_angle = -1; }).find("sharp angle"), std::string::npos);
  EXPECT_NE(message([](Options& o) { o.features.sampling.sharp_angle = 200; }).find("sharp angle"), std::string::npos);
  EXPECT_NE(message([](Options& o) { o.features.sampling.sharp_angle = std::nan(""); }).find("sharp angle"),
            std::string::npos);
  EXPECT_NE(message([](Options& o) { o.features.sampling.continuation_angle = -1; }).find("continuation angle"),
            std::string::npos);
  EXPECT_NE(
      message([](Options& o) { o.features.sampling.continuation_angle = std::nan(""); }).find("continuation angle"),
      std::string::npos);
  EXPECT_NE(message([](Options& o) { o.features.sampling.min_feature_length = -0.5; }).find("min feature length"),
            std::string::npos);
  EXPECT_NE(message([](Options& o) { o.features.sampling.max_share_tightened = -0.1; }).find("max share tightened"),
            std::string::npos);
  EXPECT_NE(message([](Options& o) { o.remesh.max_repair_rounds = -1; }).find("max repair rounds"), std::string::npos);
  EXPECT_NE(message([](Options& o) { o.features.retry_radius = -1; }).find("feature retry radius"), std::string::npos);
  EXPECT_NE(message([](Options& o) { o.features.max_repair_rounds = -2; }).find("max feature repair"),
            std::string::npos);
  EXPECT_NE(message([](Options& o) { o.features.max_sites_added = -0.1; }).find("max feature sites added"),
            std::string::npos);
  EXPECT_NE(message([](Options& o) { o.features.max_site_doublings = -1; }).find("max feature site doublings"),
            std::string::npos);
  EXPECT_NE(message([](Options& o) { o.features.max_site_doublings = 11; }).find("max feature site doublings"),
            std::string::npos);
  EXPECT_NE(message([](Options& o) {
              o.remesh.curvature = remesh::CurvatureDensityOptions{.max_ratio = 0.5};
            }).find("max_ratio"),
            std::string::npos);
  for (const double angle : {-1.0, 61.0, std::nan("")}) {
    EXPECT_NE(message([&](Options& o) { o.smoothing.smoothing_angle = angle; }).find("smoothing angle"),
              std::string::npos)
        << angle;
  }
  // Each is said before any work: an option the last stage reads included.
  EXPECT_NE(message([](Options& o) { o.smoothing.crease_tolerance = -1; }).find("crease tolerance"), std::string::npos);
}

/// Every vertex of the remesh is where its site is on the input (to rounding).
void expect_every_vertex_at_its_site(const io::LoadedMesh& loaded, const pipeline::RemeshPipelineResult& result) {
  const std::vector<SurfacePoint> on_input = pipeline::remesh_vertices_on_input(result);
  const double diagonal =
      (loaded.mesh.vertices.colwise().maxCoeff() - loaded.mesh.vertices.colwise().minCoeff()).norm();
  for (Index v = 0; v < result.remesh.mesh.num_vertices(); ++v) {
    const Eigen::Vector3d x = on_input[static_cast<std::size_t>(v)].position(loaded.mesh);
    EXPECT_LT((x - Eigen::Vector3d(result.remesh.mesh.vertices.row(v))).norm(), 1e-12 * diagonal) << v;
  }
}

TEST(RemeshPipeline, TheWorstTrianglesAreSmoothedAlongTheSurfaceAndTheConnectivityStays) {
  // homer at 500 sites: the dual of the relaxed sites has a few angles
  // below 30 degrees, which the last step raises by moving a few vertices
  // (to 30 where the surface under them allows: here 28.9).
  const io::LoadedMesh loaded = io::read_mesh("tests/data/homer.ply");
  pipeline::RemeshPipelineOptions options;
  options.sites = 500;
  options.statistics = false;
  options.smoothing.smoothing_angle = 0;
  const pipeline::RemeshPipelineResult plain = pipeline::run_remesh_pipeline(loaded, options);
  options.smoothing.smoothing_angle = 30;
  const pipeline::RemeshPipelineResult smoothed = pipeline::run_remesh_pipeline(loaded, options);
  const quality::TriangleQuality before = quality::triangle_quality(plain.remesh.mesh);
  const quality::TriangleQuality after = quality::triangle_quality(smoothed.remesh.mesh);
  ASSERT_LT(before.theta_min_deg, 30);
  EXPECT_EQ(plain.smoothing.vertices_moved, 0);
  EXPECT_GT(smoothed.smoothing.vertices_moved, 0);
  EXPECT_NEAR(smoothed.smoothing.min_angle_before, before.theta_min_deg, 1e-9);
  EXPECT_NEAR(smoothed.smoothing.min_angle_after, after.theta_min_deg, 1e-9);
  EXPECT_GT(after.theta_min_deg, before.theta_min_deg + 3);
  EXPECT_GE(after.q_min, before.q_min);
  EXPECT_NEAR(after.q_avg, before.q_avg, 2e-3);
  // The same triangles; only the vertices moved differ.
  EXPECT_EQ(smoothed.remesh.mesh.faces, plain.remesh.mesh.faces);
  ASSERT_EQ(smoothed.remesh.mesh.num_vertices(), plain.remesh.mesh.num_vertices());
  std::int64_t differ = 0;
  for (Index v = 0; v < plain.remesh.mesh.num_vertices(); ++v) {
    differ += plain.remesh.mesh.vertices.row(v) != smoothed.remesh.mesh.vertices.row(v);
  }
  EXPECT_EQ(differ, smoothed.smoothing.vertices_moved);
  // Every vertex, moved or not, is where its site is on the input.
  expect_every_vertex_at_its_site(loaded, smoothed);
}

TEST(RemeshPipeline, TheSmoothingDoesNotMoveTheCornersOutOfAHollowALittleAtATime) {
  // OpenSCAD's die (example006) at 2,000 sites: its dimples' rims are
  // creases whose chain sites are closer than the spacing, and the triangles
  // at the bottom of a dimple have small angles. Each move out of the
  // hollow takes the remesh only a little farther from its bottom; many of
  // them (16, of two vertices, without the bound on all the moves together)
  // cut the bottom off. The smoothing keeps every point of the surface
  // within 6 % of an edge of where the remesh was before it.
  const io::LoadedMesh loaded = io::read_mesh("tests/data/cad/example006.stl");
  pipeline::RemeshPipelineOptions options;
  options.sites = 2000;
  options.quality.samples_per_side = 100'000;
  options.smoothing.smoothing_angle = 0;
  const pipeline::RemeshPipelineResult plain = pipeline::run_remesh_pipeline(loaded, options);
  options.smoothing.smoothing_angle = 30;
  const pipeline::RemeshPipelineResult smoothed = pipeline::run_remesh_pipeline(loaded, options);
  ASSERT_TRUE(plain.statistics && smoothed.statistics);
  ASSERT_GT(smoothed.smoothing.vertices_moved, 0);
  EXPECT_GT(smoothed.smoothing.min_angle_after, smoothed.smoothing.min_angle_before);
  const double diagonal =
      (loaded.mesh.vertices.colwise().maxCoeff() - loaded.mesh.vertices.colwise().minCoeff()).norm();
  const double edge_pct = 100 * remesh::uniform_spacing(loaded.mesh, options.sites) / diagonal;
  EXPECT_LE(smoothed.statistics->hausdorff_pct, plain.statistics->hausdorff_pct + 0.06 * edge_pct);
}

TEST(RemeshPipeline, TheFittingBringsTheRemeshCloserToTheInputWithinTheQualityFloors) {
  // homer at 500 sites: the fitting moves the vertices that answer for the
  // input's points farthest from the remesh, and the Hausdorff distance
  // falls, the smallest angle stays at 30 degrees or more and the worst Q
  // does not fall below the unfitted remesh's; the triangles are the same.
  const io::LoadedMesh loaded = io::read_mesh("tests/data/homer.ply");
  pipeline::RemeshPipelineOptions options;
  options.sites = 500;
  options.smoothing.fit_deviations = false;
  const pipeline::RemeshPipelineResult plain = pipeline::run_remesh_pipeline(loaded, options);
  options.smoothing.fit_deviations = true;
  const pipeline::RemeshPipelineResult fitted = pipeline::run_remesh_pipeline(loaded, options);
  EXPECT_EQ(plain.fitting.vertices_moved, 0);
  EXPECT_GT(fitted.fitting.vertices_moved, 0);
  EXPECT_LT(fitted.fitting.deviation_after, fitted.fitting.deviation_before);
  ASSERT_TRUE(plain.statistics && fitted.statistics);
  EXPECT_LT(fitted.statistics->hausdorff_pct, plain.statistics->hausdorff_pct);
  EXPECT_GE(fitted.statistics->candidate.theta_min_deg,
            std::min(30.0, plain.statistics->candidate.theta_min_deg) - 1e-9);
  // The fitting's Q floor is the worst Q of the triangles the angle
  // smoothing leaves alone: the smoothed remesh's Qmin, but for what the
  // smoothing then does differently.
  EXPECT_GE(fitted.statistics->candidate.q_min, plain.statistics->candidate.q_min - 0.01);
  EXPECT_EQ(fitted.remesh.mesh.faces, plain.remesh.mesh.faces);
  expect_every_vertex_at_its_site(loaded, fitted);
}

// A colour field linear in space is linear on every face, so the remesh's
// vertices, which are points of the input, carry it exactly; with the sharp
// features kept too (their cut splits vertices into copies, welded again).
void expect_linear_colors_carried(io::LoadedMesh loaded, double sharp_angle) {
  const TriangleMesh& mesh = loaded.mesh;
  const Eigen::RowVector3d low = mesh.vertices.colwise().minCoeff(), size = mesh.vertices.colwise().maxCoeff() - low;
  const auto field = [&](const Eigen::RowVector3d& p) -> Eigen::RowVector3d {
    return (p - low).cwiseQuotient(size) * 0.8 + Eigen::RowVector3d::Constant(0.1);
  };
  loaded.attributes.colors.resize(mesh.num_vertices(), 3);
  for (Index v = 0; v < mesh.num_vertices(); ++v)
    loaded.attributes.colors.row(v) = field(mesh.vertices.row(v)).cast<float>();
  pipeline::RemeshPipelineOptions options = small_options();
  options.statistics = false;
  options.features.sampling.sharp_angle = sharp_angle;
  options.remesh.lloyd.iterations = 3;
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(std::move(loaded), options);
  EXPECT_EQ(result.features.empty(), sharp_angle == 0) << result.features_dropped_reason;
  const TriangleMesh& remeshed = result.remesh.mesh;
  ASSERT_EQ(result.attributes.colors.rows(), remeshed.num_vertices());
  double worst = 0;
  for (Index v = 0; v < remeshed.num_vertices(); ++v) {
    const Eigen::RowVector3d expected = field(remeshed.vertices.row(v));
    worst = std::max(worst, (result.attributes.colors.row(v).cast<double>() - expected).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-6);
}

TEST(RemeshPipeline, CarriesALinearColourFieldExactly) { expect_linear_colors_carried(io::read_mesh(genus_four), 0); }

TEST(RemeshPipeline, CarriesALinearColourFieldExactlyWithSharpFeatures) {
  const std::vector<double> steps = bench::hard_case_detail::even_steps(0.0, 1.0, 17);
  io::LoadedMesh box;
  box.mesh = bench::hard_case_detail::voxel_surface({steps, steps, steps}, [](int, int, int) { return true; });
  expect_linear_colors_carried(std::move(box), 60);
}

TEST(RemeshPipeline, DropsTheAttributesWhenAskedTo) {
  io::LoadedMesh loaded = io::read_mesh(genus_four);
  loaded.attributes.scalars.push_back(
      {"q", ValueType::float32, std::vector<double>(static_cast<std::size_t>(loaded.mesh.num_vertices()), 1.0)});
  pipeline::RemeshPipelineOptions options = small_options();
  options.statistics = false;
  options.attributes = false;
  EXPECT_TRUE(pipeline::run_remesh_pipeline(std::move(loaded), options).attributes.empty());
}

}  // namespace
}  // namespace geodual
