// Our exact geodesics against an independent exact solver, CGAL's
// Surface_mesh_shortest_path, on real manifold scans of about 100K faces (three
// closed ones, and the bunny with its holes), with 1, 30 and 300 random sites
// at vertices, inside faces and on edges.
//
// Asserted per vertex: |ours - CGAL| <= 1e-8 * bbox diagonal, and the nearest
// site agrees. Where the labels differ, the site we name must be a nearest
// site too: a single-source CGAL run from our site must give CGAL's
// multi-source distance at that vertex (so only genuine ties may differ).
// query() at random face points: never below CGAL's distance, equal to it in
// valid faces. Timings of both are printed, not asserted.
//
// The meshes are read with the tests' own PLY reader, so that the oracle does
// not depend on geodual_io.

#include "geodual/voronoi/geodesic_field.hpp"
#include "voronoi/cgal_oracle.hpp"
#include "voronoi/test_meshes.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace geodual::voronoi {
namespace {

struct OracleCase {
  int vertex_sites = 0;
  int face_sites = 0;
  std::uint64_t seed = 0;
  int edge_sites = 0;  ///< face points with one zero barycentric coordinate
  /// GeodesicOptions::site_groups to check against the one CGAL run (0: as
  /// many as the default picks).
  std::vector<int> site_groups = {0};
};

struct Timer {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  double wall_seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count(); }
  double cpu_seconds() const { return static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC; }
};

constexpr double kRelativeTolerance = 1e-8;
constexpr int kQueryPoints = 300;
constexpr std::size_t kMaxTieChecks = 4;  // single-site CGAL runs allowed per case

std::vector<SurfacePoint> random_query_points(const TriangleMesh& mesh, std::uint64_t seed) {
  return test::random_face_sites(mesh, kQueryPoints, seed);
}

void check_groups(const std::string& file, const TriangleMesh& mesh, const OracleCase& c,
                  const std::vector<SurfacePoint>& sites, const std::vector<SurfacePoint>& queries,
                  const test::OracleResult& cgal, int site_groups, double tol, double diag);

void run_case(const std::string& file, const TriangleMesh& mesh, const OracleCase& c) {
  const double diag = test::bbox_diagonal(mesh);
  const double tol = kRelativeTolerance * diag;
  std::vector<SurfacePoint> sites = test::random_vertex_sites(mesh, c.vertex_sites, c.seed);
  for (const SurfacePoint& s : test::random_face_sites(mesh, c.face_sites, c.seed + 1)) sites.push_back(s);
  for (SurfacePoint s : test::random_face_sites(mesh, c.edge_sites, c.seed + 3)) {
    // On the edge opposite a random corner.
    const int zero = static_cast<int>(s.element % 3);
    s.barycentric[zero] = 0;
    s.barycentric /= s.barycentric.sum();
    sites.push_back(s);
  }
  const std::vector<SurfacePoint> queries = random_query_points(mesh, c.seed + 2);
  std::ostringstream what;
  what << file << " seed " << c.seed << " (" << c.vertex_sites << " vertex + " << c.face_sites << " face + "
       << c.edge_sites << " edge sites)";
  SCOPED_TRACE(what.str());

  Timer cgal_timer;
  const test::OracleResult cgal = test::cgal_geodesic(mesh, sites, queries);
  std::cout << std::setprecision(3) << "[oracle] CGAL " << cgal.solve_seconds << " s (wall "
            << cgal_timer.wall_seconds() << ", cpu " << cgal_timer.cpu_seconds() << ")\n";

  for (const int site_groups : c.site_groups) check_groups(file, mesh, c, sites, queries, cgal, site_groups, tol, diag);
}

void check_groups(const std::string& file, const TriangleMesh& mesh, const OracleCase& c,
                  const std::vector<SurfacePoint>& sites, const std::vector<SurfacePoint>& queries,
                  const test::OracleResult& cgal, int site_groups, double tol, double diag) {
  GeodesicOptions options;
  options.site_groups = site_groups;
  SCOPED_TRACE("site_groups " + std::to_string(site_groups));
  Timer ours_timer;
  const GeodesicField field = compute_geodesic_field(mesh, sites, options);
  const double ours_wall = ours_timer.wall_seconds(), ours_cpu = ours_timer.cpu_seconds();
  ASSERT_EQ(field.distance.size(), static_cast<std::size_t>(mesh.num_vertices()));
  ASSERT_EQ(field.nearest_site.size(), static_cast<std::size_t>(mesh.num_vertices()));

  // Distances.
  double max_error = 0;
  Index worst = -1;
  int distance_failures = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const double ours = field.distance[v], theirs = cgal.distance[v];
    if (std::isinf(theirs) || std::isinf(ours)) {
      if (std::isinf(theirs) != std::isinf(ours) && distance_failures++ < 10) {
        ADD_FAILURE() << "vertex " << v << ": ours " << ours << ", CGAL " << theirs;
      }
      continue;
    }
    const double error = std::abs(ours - theirs);
    if (!(error <= max_error)) {
      max_error = std::isnan(error) ? 1e300 : error;
      worst = v;
    }
    if (!(error <= tol) && distance_failures++ < 10) {
      ADD_FAILURE() << "vertex " << v << " at (" << mesh.vertices.row(v) << "): ours " << std::setprecision(17) << ours
                    << " (site " << field.nearest_site[v] << "), CGAL " << theirs << " (site " << cgal.nearest_site[v]
                    << "), error " << error / diag << " of the diagonal";
    }
  }
  EXPECT_EQ(distance_failures, 0) << "vertices farther than " << kRelativeTolerance << " * diagonal from CGAL";

  // Labels. Where they differ, our site must be a nearest site as well.
  std::map<Index, std::vector<Index>> differing;  // our label -> vertices
  int label_range_failures = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const Index ours = field.nearest_site[v], theirs = cgal.nearest_site[v];
    if (ours == theirs) continue;
    if (ours < 0 || ours >= static_cast<Index>(sites.size())) {
      if (label_range_failures++ < 10) ADD_FAILURE() << "vertex " << v << ": label " << ours << " out of range";
      continue;
    }
    differing[ours].push_back(v);
  }
  // Query points whose labels differ, by our label.
  std::map<Index, std::vector<std::size_t>> differing_queries;

  // query(): never below the truth, exact in valid faces.
  double max_query_error = 0;
  int query_failures = 0, exact_queries = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const SurfacePoint& p = queries[i];
    const PointDistance q = query(field, mesh, p);
    const double truth = cgal.query_distance[i];
    const bool valid = field.valid_face.at(static_cast<std::size_t>(p.element));
    bool ok = q.distance >= truth - tol && q.site >= 0 && q.site < static_cast<Index>(sites.size());
    if (valid) {
      ++exact_queries;
      max_query_error = std::max(max_query_error, std::abs(q.distance - truth) / diag);
      ok = ok && std::abs(q.distance - truth) <= tol;
      if (ok && q.site != cgal.query_site[i]) differing_queries[q.site].push_back(i);
    }
    if (!ok && query_failures++ < 10) {
      ADD_FAILURE() << "query in face " << p.element << " (" << p.barycentric.transpose() << ")"
                    << (valid ? " [valid face: exact]" : " [upper bound]") << ": ours " << std::setprecision(17)
                    << q.distance << " site " << q.site << ", CGAL " << truth << " site " << cgal.query_site[i];
    }
  }
  EXPECT_EQ(query_failures, 0);

  std::size_t differing_vertices = 0;
  for (const auto& [site, vertices] : differing) differing_vertices += vertices.size();
  std::size_t differing_query_count = 0;
  for (const auto& [site, points] : differing_queries) differing_query_count += points.size();
  std::map<Index, bool> labels_to_check;
  for (const auto& [site, vertices] : differing) labels_to_check[site] = true;
  for (const auto& [site, points] : differing_queries) labels_to_check[site] = true;
  if (distance_failures > 0 || query_failures > 0) {
    // Labels are moot where distances are wrong; skip the costly tie checks.
    std::cout << "[oracle] label tie checks skipped: distances already disagree\n";
  } else if (labels_to_check.size() > kMaxTieChecks) {
    ADD_FAILURE() << differing_vertices << " vertices and " << differing_query_count
                  << " valid-face query points name a different site than CGAL, with " << labels_to_check.size()
                  << " distinct sites of ours: too many to be ties";
  } else {
    for (const auto& [site, unused] : labels_to_check) {
      (void)unused;
      const std::vector<SurfacePoint> one = {sites[static_cast<std::size_t>(site)]};
      std::vector<SurfacePoint> points;
      for (std::size_t i : differing_queries[site]) points.push_back(queries[i]);
      const test::OracleResult single = test::cgal_geodesic(mesh, one, points);
      for (Index v : differing[site]) {
        EXPECT_NEAR(single.distance[v], cgal.distance[v], tol)
            << "vertex " << v << ": we name site " << site << " (ours " << field.distance[v] << "), CGAL names site "
            << cgal.nearest_site[v] << "; CGAL's distance from our site is " << single.distance[v];
      }
      for (std::size_t k = 0; k < points.size(); ++k) {
        const std::size_t i = differing_queries[site][k];
        EXPECT_NEAR(single.query_distance[k], cgal.query_distance[i], tol)
            << "query point " << i << " in face " << queries[i].element << ": we name site " << site
            << ", CGAL names site " << cgal.query_site[i];
      }
    }
  }

  std::cout << std::setprecision(3) << "[oracle] " << file << " seed " << c.seed << " groups " << site_groups << ": "
            << sites.size() << " sites (" << c.vertex_sites << " vertex, " << c.face_sites << " face, " << c.edge_sites
            << " edge), max |ours - CGAL| = " << max_error / diag << " of the diagonal (vertex " << worst
            << "), max query error " << max_query_error << " over " << exact_queries << " valid-face points, "
            << differing_vertices << " vertices / " << differing_query_count << " queries with a tied label; ours "
            << field.stats.total_seconds << " s (wall " << ours_wall << ", cpu " << ours_cpu << "); peak windows "
            << field.stats.peak_windows << ", stored " << field.stats.windows_stored << "\n";
}

// The oracle itself, against closed forms: vertex, interior and edge sites on
// a flat square, the L plate (boundary), the saddle cone and the cube. This
// is what caught CGAL 5.5 mirroring sources on edges (see cgal_oracle.cpp).
TEST(GeodesicOracle, CgalMatchesClosedForms) {
  struct Case {
    std::string name;
    TriangleMesh mesh;
    std::function<double(const SurfacePoint&, const SurfacePoint&)> exact;
  };
  const TriangleMesh square = test::flat_square(16, 0.3, 901);
  const TriangleMesh plate = test::l_shape(6, 0.3, 902);
  const test::Cone cone = test::cone(16, 8, 1.0, 2.5 * std::numbers::pi, 0.3, 903);
  const test::Cube cube = test::cube(5, 0.25, 904);
  std::vector<Case> cases;
  cases.push_back({"flat square", square, [&](const SurfacePoint& a, const SurfacePoint& b) {
                     return (a.position(square) - b.position(square)).norm();
                   }});
  cases.push_back({"L plate", plate, [&](const SurfacePoint& a, const SurfacePoint& b) {
                     return test::l_shape_distance(a.position(plate), b.position(plate));
                   }});
  cases.push_back(
      {"saddle cone", cone.mesh, [&](const SurfacePoint& a, const SurfacePoint& b) { return cone.distance(a, b); }});
  cases.push_back({"cube", cube.mesh, [&](const SurfacePoint& a, const SurfacePoint& b) {
                     return cube.distance(a.position(cube.mesh), b.position(cube.mesh));
                   }});
  for (const Case& c : cases) {
    const double tol = 1e-12 * test::bbox_diagonal(c.mesh);
    std::vector<SurfacePoint> probes = test::random_vertex_sites(c.mesh, 2, 905);
    for (const SurfacePoint& p : test::random_face_sites(c.mesh, 2, 906)) probes.push_back(p);
    for (SurfacePoint p : test::random_face_sites(c.mesh, 3, 907)) {
      p.barycentric[static_cast<int>(p.element % 3)] = 0;
      p.barycentric /= p.barycentric.sum();
      probes.push_back(p);
    }
    for (const SurfacePoint& site : probes) {
      const test::OracleResult r = test::cgal_geodesic(c.mesh, std::vector<SurfacePoint>{site});
      double worst = 0;
      for (Index v = 0; v < c.mesh.num_vertices(); ++v) {
        worst = std::max(worst, std::abs(r.distance[v] - c.exact(site, SurfacePoint::at_vertex(v))));
      }
      EXPECT_LE(worst, tol) << c.name << ": CGAL from "
                            << (site.kind == SurfacePoint::Kind::vertex ? "vertex " : "face ") << site.element << " ("
                            << site.barycentric.transpose() << ")";
    }
  }
}

void run_mesh(const std::string& file, const std::vector<OracleCase>& cases) {
  const TriangleMesh mesh = test::read_test_ply(test::test_mesh_path(file));
  for (const OracleCase& c : cases) run_case(file, mesh, c);
}

// Each case checks one field per entry of site_groups against the same CGAL
// run: the default (a single group below 512 sites) and sites propagated in
// groups apart and merged (a few, and many small ones).
// Chosen to keep CGAL's share of the suite near a minute and a half of CPU
// time: every mesh gets 30 sites (a third each at vertices, inside faces and
// on edges), the closed ones also 300 (half at vertices, half inside faces),
// and the armadillo, where CGAL is quickest with one source, a single vertex
// site and a single face site.
TEST(GeodesicOracle, Armadillo86k) {
  run_mesh("armadillo_86k.ply", {{1, 0, 101}, {0, 1, 102}, {10, 10, 103, 10}, {150, 150, 104, 0, {0, 4}}});
}

// (CGAL needs 20-30 s of CPU for a single source on the horse or Nefertiti:
// those runs are in the DISABLED_ tests below.)
TEST(GeodesicOracle, Horse) { run_mesh("horse.ply", {{10, 10, 203, 10, {0, 2}}, {150, 150, 204, 0, {0, 3, 16}}}); }

TEST(GeodesicOracle, Nefertiti100k) {
  // Needle triangles down to 0.06 degrees, float64 coordinates.
  run_mesh("nefertiti_100k.ply", {{10, 10, 303, 10}, {150, 150, 304, 0, {0, 5}}});
}

TEST(GeodesicOracle, BunnyWithHoles) {
  // 5 boundary loops (boundary vertices are pseudo-sources) and 1113
  // unreferenced vertices (+inf on both sides).
  run_mesh("bunny.ply", {{10, 10, 801, 10, {0, 3}}});
}

// Heavier runs, not part of the default suite (several CGAL minutes each on
// two cores): run with --gtest_also_run_disabled_tests.
TEST(GeodesicOracle, DISABLED_HorseAllKinds) {
  run_mesh("horse.ply", {{1, 0, 201}, {0, 1, 502}, {30, 0, 503}, {0, 300, 506}});
}

TEST(GeodesicOracle, DISABLED_Nefertiti100kAllKinds) {
  run_mesh("nefertiti_100k.ply", {{0, 1, 302}, {1, 0, 601}, {0, 30, 604}, {300, 0, 605}});
}

}  // namespace
}  // namespace geodual::voronoi
