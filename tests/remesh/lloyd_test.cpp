// Lloyd relaxation: the energy never rises, quality improves on a real scan,
// flat cells move to their centroids, and threads do not change the result.

#include "remesh/analytic_surfaces.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/quality/quality_stats.hpp"
#include "geodual/remesh/curvature_density.hpp"
#include "geodual/remesh/lloyd.hpp"
#include "geodual/remesh/remesh.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

namespace geodual {
namespace {

TriangleMesh scan(const std::string& name) { return io::read_mesh("tests/data/" + name).mesh; }

TEST(Lloyd, EnergyNeverRisesAndQualityImprovesOnAScan) {
  const TriangleMesh mesh = scan("bunny.ply");
  // Random sites: a start that relaxation has much to improve on.
  const std::vector<SurfacePoint> sites =
      remesh::sample_sites(mesh, 1500, {.strategy = remesh::SamplingStrategy::random});
  remesh::RemeshOptions none, some;
  none.lloyd.iterations = 0;
  some.lloyd.iterations = 6;
  some.lloyd.geodesic_tolerance = 0;  // the exact iterations, even after a converged warm start
  const remesh::RemeshResult before = remesh::remesh_from_sites(mesh, sites, none);
  const remesh::RemeshResult after = remesh::remesh_from_sites(mesh, sites, some);
  ASSERT_GE(after.relaxation.energy.size(), 2u);
  for (std::size_t i = 1; i < after.relaxation.energy.size(); ++i)
    EXPECT_LE(after.relaxation.energy[i], after.relaxation.energy[i - 1]);
  // `before` has the given sites' energy; the warm start alone lowers it.
  EXPECT_LT(after.relaxation.energy.front(), before.relaxation.energy.front());
  EXPECT_LT(after.relaxation.energy.back(), 0.8 * before.relaxation.energy.front());
  const quality::TriangleQuality q0 = quality::triangle_quality(before.dual.mesh),
                                 q1 = quality::triangle_quality(after.dual.mesh);
  EXPECT_GT(q1.q_avg, q0.q_avg + 0.1);
  EXPECT_GT(q1.theta_min_deg, q0.theta_min_deg);
  EXPECT_LT(q1.pct_angles_lt30, q0.pct_angles_lt30);
  // Still a faithful remesh: bunny's topology.
  const MeshReport in = analyze_mesh(mesh), out = analyze_mesh(after.dual.mesh);
  EXPECT_EQ(out.euler_characteristic, in.euler_characteristic);
  EXPECT_EQ(out.boundary_loops, in.boundary_loops);
  EXPECT_EQ(out.nonmanifold_edges, 0);
}

TEST(Lloyd, BoundarySitesStayOnTheBoundary) {
  const TriangleMesh disk = test::disk(40, 160);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(disk, 300);
  remesh::LloydOptions options;
  options.iterations = 4;
  const remesh::LloydResult relaxed = remesh::lloyd_relax(disk, sites, options);
  int on_rim = 0;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const double r0 = sites[i].position(disk).norm(), r1 = relaxed.sites[i].position(disk).norm();
    if (r0 > std::cos(std::numbers::pi / 160) - 1e-9) {  // on a rim edge (a chord of the circle)
      ++on_rim;
      EXPECT_EQ(relaxed.sites[i].position(disk), sites[i].position(disk));
    } else {
      EXPECT_LE(r1, 1 + 1e-12);  // never off the surface
    }
  }
  EXPECT_GE(on_rim, 3);
  for (std::size_t i = 1; i < relaxed.energy.size(); ++i) EXPECT_LE(relaxed.energy[i], relaxed.energy[i - 1]);
}

TEST(Lloyd, ConvergesToTheRegularCentroidalTessellationOnAPlane) {
  // On a flat disk the geodesic CVT is the Euclidean one: after enough
  // iterations each interior site sits at its cell's centroid, i.e. the
  // mean log map (cell_log_moment / area) is small against the spacing.
  const TriangleMesh disk = test::disk(32, 128);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(disk, 120);
  remesh::LloydOptions options;
  options.iterations = 30;
  options.tolerance = 0;
  const remesh::LloydResult relaxed = remesh::lloyd_relax(disk, sites, options);
  const double spacing = std::sqrt(3.14159 / 120);
  double worst = 0;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    if (relaxed.sites[i].position(disk).norm() > std::cos(std::numbers::pi / 128) - 1e-9) continue;  // fixed on the rim
    worst = std::max(worst, (relaxed.diagram.cell_log_moment[i] / relaxed.diagram.cell_area[i]).norm());
  }
  EXPECT_LT(worst, 0.05 * spacing);
}

/// The largest Lloyd step (distance to the cell's centroid) of the sites
/// inside the unit disk's rim.
double largest_interior_lloyd_step(const TriangleMesh& disk, const remesh::LloydResult& relaxed) {
  double worst = 0;
  for (std::size_t i = 0; i < relaxed.sites.size(); ++i) {
    if (relaxed.sites[i].position(disk).norm() > std::cos(std::numbers::pi / 128) - 1e-9) continue;  // fixed on the rim
    worst = std::max(worst, (relaxed.diagram.cell_log_moment[i] / relaxed.diagram.cell_area[i]).norm());
  }
  return worst;
}

TEST(Lloyd, NewtonStepsConvergeMuchFasterThanLloydOnAPlane) {
  // On a plane the CVT Hessian of cvt_newton.cpp is exact. From the same
  // nearly centroidal sites, a few (damped, bounded) Newton steps bring the
  // sites far closer to their centroids than as many Lloyd steps, whose
  // convergence is linear and slow.
  const TriangleMesh disk = test::disk(32, 128);
  remesh::LloydOptions warm;
  warm.iterations = 20;
  warm.warm_start_iterations = 0;  // the geodesic steps alone, here and below
  warm.tolerance = warm.geodesic_tolerance = 0;
  warm.newton = false;
  const remesh::LloydResult start = remesh::lloyd_relax(disk, remesh::sample_sites(disk, 120), warm);
  const double before = largest_interior_lloyd_step(disk, start);

  remesh::LloydOptions newton;
  newton.iterations = 5;
  newton.warm_start_iterations = 0;
  newton.tolerance = newton.geodesic_tolerance = 0;
  remesh::LloydOptions lloyd = newton;
  lloyd.newton = false;
  const remesh::LloydResult by_newton = remesh::lloyd_relax(disk, start.sites, newton);
  const remesh::LloydResult by_lloyd = remesh::lloyd_relax(disk, start.sites, lloyd);
  const double after_newton = largest_interior_lloyd_step(disk, by_newton);
  const double after_lloyd = largest_interior_lloyd_step(disk, by_lloyd);
  std::printf(
      "largest distance to the centroid %.3g; after 5 Newton steps %.3g (energy %.9g, %d diagrams), "
      "after 5 Lloyd steps %.3g (energy %.9g)\n",
      before, after_newton, by_newton.energy.back(), by_newton.diagrams, after_lloyd, by_lloyd.energy.back());
  EXPECT_LT(after_newton, 0.5 * before);
  EXPECT_GT(after_lloyd, 0.8 * before);
  const double e0 = start.energy.back();
  EXPECT_GT(e0 - by_newton.energy.back(), 2 * (e0 - by_lloyd.energy.back()));
}

TEST(Lloyd, NewtonReachesALowerEnergyAndBetterTrianglesThanLloydOnAScan) {
  const TriangleMesh mesh = scan("bunny.ply");
  const std::vector<SurfacePoint> sites =
      remesh::sample_sites(mesh, 1500, {.strategy = remesh::SamplingStrategy::poisson});
  remesh::RemeshOptions newton;
  newton.lloyd.iterations = 6;
  newton.lloyd.warm_start_iterations = 0;  // the geodesic steps alone
  newton.lloyd.tolerance = 0;
  remesh::RemeshOptions lloyd = newton;
  lloyd.lloyd.newton = false;
  const remesh::RemeshResult by_newton = remesh::remesh_from_sites(mesh, sites, newton);
  const remesh::RemeshResult by_lloyd = remesh::remesh_from_sites(mesh, sites, lloyd);
  EXPECT_EQ(by_newton.relaxation.iterations, 6);
  for (std::size_t i = 1; i < by_newton.relaxation.energy.size(); ++i)
    EXPECT_LT(by_newton.relaxation.energy[i], by_newton.relaxation.energy[i - 1]);
  // Lloyd's energy above the CVT's decays slowly; Newton's steps go further
  // down in as many iterations.
  EXPECT_LT(by_newton.relaxation.energy.back(), by_lloyd.relaxation.energy.back());
  EXPECT_GT(quality::triangle_quality(by_newton.dual.mesh).q_avg, quality::triangle_quality(by_lloyd.dual.mesh).q_avg);
}

TEST(Lloyd, NoExactIterationWhereTheWarmStartLeftLittleForIt) {
  // Where the warm start took the sites about as close to the geodesic
  // centroids as an exact iteration would (its first-order gain below
  // geodesic_tolerance), the first exact diagram is the last: the iteration
  // forced would lower the energy by little and change the triangles little.
  const TriangleMesh mesh = scan("bunny.ply");
  const std::vector<SurfacePoint> sites =
      remesh::sample_sites(mesh, 1500, {.strategy = remesh::SamplingStrategy::poisson});
  remesh::RemeshOptions skipped, forced;
  forced.lloyd.geodesic_tolerance = 0;
  forced.lloyd.iterations = 2;
  const remesh::RemeshResult without = remesh::remesh_from_sites(mesh, sites, skipped);
  const remesh::RemeshResult with = remesh::remesh_from_sites(mesh, sites, forced);
  EXPECT_GT(without.relaxation.warm_start_iterations, 0);
  EXPECT_EQ(without.relaxation.iterations, 0);
  EXPECT_EQ(without.relaxation.diagrams, 1);
  ASSERT_GE(with.relaxation.iterations, 1);
  ASSERT_EQ(without.relaxation.energy.size(), 1u);
  EXPECT_EQ(with.relaxation.energy.front(), without.relaxation.energy.front());  // the same warm start
  EXPECT_LT(with.relaxation.energy.front() - with.relaxation.energy.back(), 0.005 * with.relaxation.energy.front());
  EXPECT_NEAR(quality::triangle_quality(without.dual.mesh).q_avg, quality::triangle_quality(with.dual.mesh).q_avg,
              0.005);
  // Few sites on the bunny: cells as large as its ears, where the restricted
  // diagram is far from the geodesic one and the exact iterations go on.
  const std::vector<SurfacePoint> few =
      remesh::sample_sites(mesh, 100, {.strategy = remesh::SamplingStrategy::poisson});
  EXPECT_GE(remesh::remesh_from_sites(mesh, few, skipped).relaxation.iterations, 1);
}

TEST(Lloyd, OptionsOutOfRangeAreRefusedByName) {
  const TriangleMesh disk = test::disk(8, 32);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(disk, 20);
  auto refused = [&](const remesh::LloydOptions& options, const std::string& name) {
    try {
      (void)remesh::lloyd_relax(disk, sites, options);
    } catch (const UsageError& error) {
      EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
      return;
    }
    ADD_FAILURE() << name << " was accepted";
  };
  remesh::LloydOptions options;
  options.iterations = -1;
  refused(options, "iterations");
  options = {};
  options.tolerance = std::nan("");
  refused(options, "tolerance");
  options = {};
  options.over_relaxation = 2;
  refused(options, "over_relaxation");
  options = {};
  options.newton_damping = 0;
  refused(options, "newton_damping");
  options = {};
  options.newton_max_step = std::numeric_limits<double>::infinity();
  refused(options, "newton_max_step");
  options = {};
  options.warm_start_iterations = -2;
  refused(options, "warm_start_iterations");
  options = {};
  options.warm_start_momentum = 1;
  refused(options, "warm_start_momentum");
  options = {};
  options.warm_start_momentum = -0.1;
  refused(options, "warm_start_momentum");
}

TEST(Lloyd, OneOrTwoThreadsGiveTheSameSites) {
  const TriangleMesh mesh = scan("fertility.ply");
  const std::vector<SurfacePoint> sites = remesh::sample_sites(mesh, 600);
  // The plain geodesic CVT, and one weighted by a curvature density.
  for (const bool weighted : {false, true}) {
    SCOPED_TRACE(weighted ? "weighted" : "uniform");
    remesh::LloydOptions options;
    options.iterations = 3;
    if (weighted) options.density = remesh::curvature_density(mesh, {.spacing = remesh::uniform_spacing(mesh, 600)});
    remesh::LloydResult one, two;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      one = remesh::lloyd_relax(mesh, sites, options);
    }
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      two = remesh::lloyd_relax(mesh, sites, options);
    }
    ASSERT_EQ(one.sites.size(), two.sites.size());
    for (std::size_t i = 0; i < one.sites.size(); ++i) {
      EXPECT_EQ(one.sites[i].element, two.sites[i].element);
      EXPECT_EQ(one.sites[i].barycentric, two.sites[i].barycentric);
    }
    EXPECT_EQ(one.energy, two.energy);
  }
}

}  // namespace
}  // namespace geodual

namespace geodual {
namespace {

/// Three geodesic iterations, none stopped early, after `warm_start` warm-start steps.
remesh::LloydOptions three_iterations_after(int warm_start) {
  remesh::LloydOptions options;
  options.iterations = 3;
  options.geodesic_tolerance = 0;
  options.warm_start_iterations = warm_start;
  return options;
}

TEST(Lloyd, VertexSitesMoveToo) {
  const TriangleMesh sphere = test::icosphere(4);
  std::vector<SurfacePoint> sites;
  for (Index v = 0; v < sphere.vertices.rows(); v += 17) sites.push_back(SurfacePoint::at_vertex(v));
  remesh::LloydOptions measure_only;
  measure_only.iterations = 0;
  const double given = remesh::lloyd_relax(sphere, sites, measure_only).energy.front();
  // By the geodesic steps, and by the warm start's.
  for (const int warm_start : {0, 5}) {
    SCOPED_TRACE(warm_start);
    remesh::LloydOptions options = three_iterations_after(warm_start);
    const remesh::LloydResult relaxed = remesh::lloyd_relax(sphere, sites, options);
    EXPECT_EQ(relaxed.iterations, 3);
    EXPECT_EQ(relaxed.warm_start_iterations, warm_start);
    EXPECT_EQ(relaxed.energy.size(), 4u);  // the first diagram's, then each iteration's
    EXPECT_LT(relaxed.energy.back(), 0.9 * given);
    int moved = 0;
    for (std::size_t i = 0; i < sites.size(); ++i)
      moved += relaxed.sites[i].position(sphere) != sites[i].position(sphere);
    EXPECT_GT(moved, static_cast<int>(sites.size()) / 2);
  }
}

TEST(Lloyd, FixedSitesStayWhereTheyAreAndTheOthersMove) {
  const TriangleMesh sphere = test::icosphere(4);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(sphere, 120);
  for (const int warm_start : {0, 5}) {
    SCOPED_TRACE(warm_start);
    remesh::LloydOptions options = three_iterations_after(warm_start);
    options.fixed_sites.assign(sites.size(), 0);
    for (std::size_t i = 0; i < sites.size(); i += 7) options.fixed_sites[i] = 1;
    const remesh::LloydResult relaxed = remesh::lloyd_relax(sphere, sites, options);
    EXPECT_GE(relaxed.iterations + relaxed.warm_start_iterations, 1);
    int moved = 0;
    for (std::size_t i = 0; i < sites.size(); ++i) {
      const bool same = relaxed.sites[i].position(sphere) == sites[i].position(sphere);
      if (options.fixed_sites[i]) {
        EXPECT_TRUE(same) << "fixed site " << i << " moved";
      } else {
        moved += !same;
      }
    }
    EXPECT_GT(moved, static_cast<int>(sites.size()) / 2);
  }
}

TEST(Lloyd, AWarmStartAloneMovesTheFewFreeSitesWithOneExactDiagram) {
  // A cap of free sites among fixed ones (an error bound's later rounds):
  // the warm start alone relaxes them, on the cells their steps can change,
  // and only the diagram of the sites reached is exact.
  const TriangleMesh sphere = test::icosphere(4);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(sphere, 400);
  const Eigen::Vector3d pole(0, 0, 1);
  remesh::LloydOptions options;
  options.iterations = 0;
  options.warm_start_alone = true;
  options.warm_start_iterations = 10;
  options.fixed_sites.assign(sites.size(), 1);
  int free = 0;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    if (sites[i].position(sphere).normalized().dot(pole) > 0.8) options.fixed_sites[i] = 0, ++free;
  }
  ASSERT_GT(free, 10);
  ASSERT_LT(4 * free, static_cast<int>(sites.size()));  // few enough for the cells near them alone
  const remesh::LloydResult relaxed = remesh::lloyd_relax(sphere, sites, options);
  EXPECT_EQ(relaxed.iterations, 0);
  EXPECT_GT(relaxed.warm_start_iterations, 0);
  EXPECT_EQ(relaxed.diagrams, 1);
  int moved = 0;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const bool same = relaxed.sites[i].position(sphere) == sites[i].position(sphere);
    if (options.fixed_sites[i]) {
      EXPECT_TRUE(same) << "fixed site " << i << " moved";
    } else {
      moved += !same;
    }
  }
  EXPECT_GT(moved, free / 2);
  // The exact energy of the whole fell (energy[0]: the sites reached).
  remesh::LloydOptions given;
  given.iterations = 0;
  const remesh::LloydResult unmoved = remesh::lloyd_relax(sphere, sites, given);
  ASSERT_EQ(unmoved.energy.size(), 1u);
  EXPECT_LT(relaxed.energy.front(), unmoved.energy.front());
  // Without warm_start_alone no iterations means none: the given sites.
  options.warm_start_alone = false;
  const remesh::LloydResult none = remesh::lloyd_relax(sphere, sites, options);
  EXPECT_EQ(none.warm_start_iterations, 0);
  EXPECT_EQ(none.energy, unmoved.energy);
}

TEST(Lloyd, TheWarmStartCanBeCancelled) {
  // The progress callback of the geodesics is asked between warm-start
  // steps too (with 0), before any diagram: cancelled there, the warm start
  // stops.
  const TriangleMesh sphere = test::icosphere(4);
  const std::vector<SurfacePoint> sites = remesh::sample_sites(sphere, 200);
  remesh::LloydOptions options;
  options.iterations = 3;
  int calls = 0;
  options.voronoi.geodesic.progress = [&](double fraction) {
    EXPECT_EQ(fraction, 0.0);  // no diagram is under way
    return ++calls < 3;
  };
  try {
    (void)remesh::lloyd_relax(sphere, sites, options);
    ADD_FAILURE() << "not cancelled";
  } catch (const Cancelled& cancelled) {
    EXPECT_NE(std::string(cancelled.what()).find("warm start"), std::string::npos) << cancelled.what();
  }
  EXPECT_EQ(calls, 3);
}

TEST(Lloyd, WarmStartBringsTheSitesCloserToACentroidalTessellation) {
  // The restricted diagram's steps cost no geodesics; after them the
  // geodesic iterations start from a lower energy than the given sites', and
  // as many of them end lower and with better triangles than without.
  const TriangleMesh mesh = scan("bunny.ply");
  const std::vector<SurfacePoint> sites =
      remesh::sample_sites(mesh, 1500, {.strategy = remesh::SamplingStrategy::poisson});
  remesh::RemeshOptions cold, warm;
  cold.lloyd.iterations = warm.lloyd.iterations = 3;
  cold.lloyd.tolerance = warm.lloyd.tolerance = 0;
  cold.lloyd.geodesic_tolerance = warm.lloyd.geodesic_tolerance = 0;
  cold.lloyd.warm_start_iterations = 0;
  warm.lloyd.warm_start_iterations = 15;
  const remesh::RemeshResult from_cold = remesh::remesh_from_sites(mesh, sites, cold);
  const remesh::RemeshResult from_warm = remesh::remesh_from_sites(mesh, sites, warm);
  EXPECT_EQ(from_warm.relaxation.warm_start_iterations, 15);
  ASSERT_EQ(from_warm.relaxation.energy.size(), 4u);  // the warm start's sites, three iterations
  ASSERT_EQ(from_cold.relaxation.energy.size(), 4u);  // the given sites, three iterations
  for (std::size_t i = 1; i < from_warm.relaxation.energy.size(); ++i)
    EXPECT_LT(from_warm.relaxation.energy[i], from_warm.relaxation.energy[i - 1]);
  EXPECT_LT(from_warm.relaxation.energy[0],
            from_cold.relaxation.energy.back());  // the warm start alone beats three geodesic iterations
  EXPECT_LT(from_warm.relaxation.energy.back(), from_cold.relaxation.energy.back());
  EXPECT_GT(quality::triangle_quality(from_warm.dual.mesh).q_avg,
            quality::triangle_quality(from_cold.dual.mesh).q_avg + 0.01);
}

TEST(Lloyd, MomentumTakesTheWarmStartFurtherInNoMoreSteps) {
  // The heavy-ball momentum carries the slow slides of the warm start's
  // tail: in at most as many steps (30, or until no step lowers the energy)
  // its sites reach a lower geodesic CVT energy and better triangles than
  // the steps without it.
  for (const auto& [name, count] : {std::pair{"bunny.ply", 1500}, std::pair{"fertility.ply", 2000}}) {
    SCOPED_TRACE(name);
    const TriangleMesh mesh = scan(name);
    const std::vector<SurfacePoint> sites =
        remesh::sample_sites(mesh, count, {.strategy = remesh::SamplingStrategy::poisson});
    remesh::RemeshOptions plain, heavy;
    plain.lloyd.iterations = heavy.lloyd.iterations = 1;  // the warm start runs before the first iteration
    plain.lloyd.tolerance = heavy.lloyd.tolerance = 0;
    plain.lloyd.warm_start_iterations = heavy.lloyd.warm_start_iterations = 30;
    plain.lloyd.warm_start_momentum = 0;
    heavy.lloyd.warm_start_momentum = 0.6;
    const remesh::RemeshResult without = remesh::remesh_from_sites(mesh, sites, plain);
    const remesh::RemeshResult with = remesh::remesh_from_sites(mesh, sites, heavy);
    EXPECT_LE(with.relaxation.warm_start_iterations, without.relaxation.warm_start_iterations);
    EXPECT_LT(with.relaxation.energy.front(), without.relaxation.energy.front());
    EXPECT_GT(quality::triangle_quality(with.dual.mesh).q_avg, quality::triangle_quality(without.dual.mesh).q_avg);
  }
}

}  // namespace
}  // namespace geodual

namespace geodual {
namespace {

TEST(Lloyd, EndingOnARejectedStepKeepsTheWholeDiagramOfTheSitesReached) {
  // A trial step's diagram is computed after the current one's windows are
  // freed; when the last step is rejected, the windows the result holds must
  // be those of its sites, as a fresh field has them. Sites on the boundary
  // stay, so every step of these is rejected.
  const TriangleMesh disk = test::disk(8, 32);
  const double radius = disk.vertices.leftCols<2>().rowwise().norm().maxCoeff();
  std::vector<SurfacePoint> sites;
  for (Index v = 0; v < disk.num_vertices(); ++v) {
    if (disk.vertices.row(v).head<2>().norm() > radius - 1e-9 && v % 3 == 0)
      sites.push_back(SurfacePoint::at_vertex(v));
  }
  ASSERT_GT(sites.size(), 5u);
  const remesh::LloydResult relaxed = remesh::lloyd_relax(disk, sites, {});
  ASSERT_EQ(relaxed.iterations, 0);
  ASSERT_GT(relaxed.diagrams, 1);  // the first diagram, then the rejected steps'
  const voronoi::GeodesicField fresh = voronoi::compute_geodesic_field(disk, relaxed.sites);
  const voronoi::GeodesicField& held = relaxed.diagram.field;
  ASSERT_FALSE(held.windows.empty());
  EXPECT_EQ(held.window_begin, fresh.window_begin);
  ASSERT_EQ(held.windows.size(), fresh.windows.size());
  for (std::size_t w = 0; w < held.windows.size(); ++w) {
    const voronoi::EdgeWindow &a = held.windows[w], &b = fresh.windows[w];
    EXPECT_TRUE(a.b0 == b.b0 && a.b1 == b.b1 && a.source_x == b.source_x && a.source_y == b.source_y &&
                a.sigma == b.sigma && a.site == b.site)
        << "window " << w;
  }
  EXPECT_EQ(held.distance, fresh.distance);
  EXPECT_EQ(held.nearest_site, fresh.nearest_site);
}

}  // namespace
}  // namespace geodual
