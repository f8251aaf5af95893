// Every test mesh, defects included (boundaries, non-manifold edges and
// vertices, several components, zero-area faces, unreferenced vertices), with
// 1, 30 and 1000 random vertex sites: the engine completes, reaches exactly the
// components that hold a site, gives distances that are 1-Lipschitz along every
// edge, zero at the sites, and the same with Redundant Window Removal on and
// off. Plus the error contract: bad sites, the window memory limit and
// cancellation through the progress callback.

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/voronoi/geodesic_field.hpp"
#include "voronoi/test_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace geodual::voronoi {
namespace {

// The test meshes as listed in tests/data/MANIFEST.tsv; the test below checks
// that the folder holds no other mesh, so that a new file is not silently skipped.
const std::vector<std::string>& manifest_meshes() {
  static const std::vector<std::string> files = {
      "armadillo_86k.ply", "bunny.ply",      "bunny_res2.ply", "cheburashka.ply", "dragon_100k.ply",
      "fandisk.ply",       "fertility.ply",  "homer.ply",      "horse.ply",       "nefertiti_100k.ply",
      "ogre.ply",          "rocker_arm.ply", "spot.ply",       "woody.ply"};
  return files;
}

TEST(GeodesicRobustness, EveryTestMeshIsCovered) { EXPECT_EQ(test::test_mesh_files(), manifest_meshes()); }

struct FieldSummary {
  int finite = 0;
  double max_lipschitz_excess = 0;  ///< max (|d(a) - d(b)| / |ab| - 1) over edges
};

/// Checks the invariants of one field; returns a summary for the report.
FieldSummary check_invariants(const std::string& what, const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites,
                              const GeodesicField& field, const std::vector<Index>& component,
                              const std::vector<bool>& referenced, const std::vector<std::array<Index, 2>>& edges) {
  SCOPED_TRACE(what);
  FieldSummary summary;
  const Index nv = mesh.num_vertices();
  const Index num_sites = static_cast<Index>(sites.size());
  EXPECT_EQ(field.distance.size(), static_cast<std::size_t>(nv));
  EXPECT_EQ(field.nearest_site.size(), static_cast<std::size_t>(nv));
  if (field.distance.size() != static_cast<std::size_t>(nv) ||
      field.nearest_site.size() != static_cast<std::size_t>(nv)) {
    return summary;
  }
  std::set<Index> site_components;
  for (const SurfacePoint& s : sites) site_components.insert(component[s.element]);

  int failures = 0;
  for (Index v = 0; v < nv; ++v) {
    const double d = field.distance[v];
    const Index label = field.nearest_site[v];
    const bool reachable = referenced[v] && site_components.count(component[v]) > 0;
    bool ok;
    if (reachable) {
      ok = std::isfinite(d) && d >= 0 && label >= 0 && label < num_sites &&
           component[sites[static_cast<std::size_t>(label)].element] == component[v];
      ++summary.finite;
    } else {
      ok = d == std::numeric_limits<double>::infinity() && label == -1;
    }
    if (!ok && failures++ < 10) {
      ADD_FAILURE() << "vertex " << v << (reachable ? " (reachable)" : " (unreachable)") << ": distance " << d
                    << ", label " << label;
    }
  }
  EXPECT_EQ(failures, 0) << "vertices with a wrong reachability, distance or label";

  int lipschitz_failures = 0;
  for (const auto& [a, b] : edges) {
    const double da = field.distance[a], db = field.distance[b];
    if (!std::isfinite(da) || !std::isfinite(db)) continue;
    const double length = (mesh.vertices.row(a) - mesh.vertices.row(b)).norm();
    const double jump = std::abs(da - db);
    if (length > 0) summary.max_lipschitz_excess = std::max(summary.max_lipschitz_excess, jump / length - 1);
    if (!(jump <= length * (1 + 1e-9)) && lipschitz_failures++ < 10) {
      ADD_FAILURE() << std::setprecision(17) << "edge " << a << "-" << b << " of length " << length << ": distances "
                    << da << " (site " << field.nearest_site[a] << ") and " << db << " (site " << field.nearest_site[b]
                    << ") differ by more than the length";
    }
  }
  EXPECT_EQ(lipschitz_failures, 0) << "edges where the distance is not 1-Lipschitz";

  for (Index i = 0; i < num_sites; ++i) {
    const Index v = sites[static_cast<std::size_t>(i)].element;
    EXPECT_EQ(field.distance[v], 0.0) << "site " << i << " at vertex " << v;
    EXPECT_EQ(field.nearest_site[v], i) << "site " << i << " at vertex " << v;
  }
  EXPECT_EQ(field.sites.size(), sites.size());
  for (std::size_t i = 0; i < sites.size() && i < field.sites.size(); ++i) {
    EXPECT_EQ(field.sites[i].position(mesh), sites[i].position(mesh)) << "site " << i;
  }

  // Faces whose corners name different sites are crossed by a Voronoi
  // boundary, so they must be valid.
  EXPECT_EQ(field.valid_face.size(), static_cast<std::size_t>(mesh.num_faces())) << "valid_face";
  if (field.valid_face.size() != static_cast<std::size_t>(mesh.num_faces())) return summary;
  int validity_failures = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!test::face_takes_part(mesh, f)) continue;
    const Index l0 = field.nearest_site[mesh.faces(f, 0)], l1 = field.nearest_site[mesh.faces(f, 1)],
                l2 = field.nearest_site[mesh.faces(f, 2)];
    if ((l0 != l1 || l1 != l2) && !field.valid_face[static_cast<std::size_t>(f)] && validity_failures++ < 5) {
      ADD_FAILURE() << "face " << f << " has corners labelled " << l0 << ", " << l1 << ", " << l2
                    << " but is not valid";
    }
  }
  EXPECT_EQ(validity_failures, 0);

  // The retained windows: sorted, disjoint, inside their edge, and never
  // promising less than the triangle inequality allows from the edge's ends.
  const Index ne = static_cast<Index>(field.edge_faces.size());
  EXPECT_EQ(field.window_begin.size(), static_cast<std::size_t>(ne) + 1);
  EXPECT_EQ(field.edge_length.size(), static_cast<std::size_t>(ne));
  if (field.window_begin.size() != static_cast<std::size_t>(ne) + 1 ||
      field.edge_length.size() != static_cast<std::size_t>(ne)) {
    return summary;
  }
  EXPECT_EQ(field.window_begin.back(), static_cast<Index>(field.windows.size()));
  EXPECT_EQ(field.stats.windows_stored, static_cast<std::int64_t>(field.windows.size()));
  EXPECT_GE(field.stats.peak_windows, field.stats.windows_stored);
  const double tol = 1e-9 * test::bbox_diagonal(mesh);
  int window_failures = 0;
  for (Index e = 0; e < ne; ++e) {
    const double length = field.edge_length[e];
    const auto [v0, v1] = field.edge_vertices(mesh, e);
    double previous_end = -std::numeric_limits<double>::infinity();
    for (Index i = field.window_begin[e]; i < field.window_begin[e + 1]; ++i) {
      const EdgeWindow& w = field.windows[static_cast<std::size_t>(i)];
      auto value = [&](double x) { return w.sigma + std::hypot(x - w.source_x, w.source_y); };
      bool ok = w.b0 >= -tol && w.b1 <= length + tol && w.b0 <= w.b1 && w.b0 >= previous_end - tol && w.sigma >= 0 &&
                w.site >= 0 && w.site < num_sites;
      for (double x : {w.b0, 0.5 * (w.b0 + w.b1), w.b1}) {
        ok = ok && value(x) >= field.distance[v0] - x - tol && value(x) >= field.distance[v1] - (length - x) - tol;
      }
      previous_end = w.b1;
      if (!ok && window_failures++ < 5) {
        ADD_FAILURE() << std::setprecision(17) << "edge " << e << " (" << v0 << "-" << v1 << ", length " << length
                      << ", distances " << field.distance[v0] << ", " << field.distance[v1] << ") window " << i << ": ["
                      << w.b0 << ", " << w.b1 << "] source (" << w.source_x << ", " << w.source_y << ") sigma "
                      << w.sigma << " site " << w.site;
      }
    }
  }
  EXPECT_EQ(window_failures, 0) << "malformed windows";
  return summary;
}

class SharedMesh : public ::testing::TestWithParam<std::string> {};

TEST_P(SharedMesh, RandomVertexSites) {
  const std::string file = GetParam();
  const TriangleMesh mesh = io::read_mesh(test::test_mesh_path(file)).mesh;
  const auto component = test::vertex_components(mesh);
  const auto referenced = test::referenced_vertices(mesh);
  const auto edges = test::unique_edges(mesh);
  std::uint64_t seed = 1;
  for (char ch : file) seed = seed * 131 + static_cast<unsigned char>(ch);

  const int usable = static_cast<int>(std::count(referenced.begin(), referenced.end(), true));
  for (int wanted : {1, 30, 1000}) {
    const int count = std::min(wanted, usable / 2);  // woody has only 694 vertices
    const std::vector<SurfacePoint> sites =
        test::random_vertex_sites(mesh, count, seed + static_cast<std::uint64_t>(count));
    const std::string what = file + ", " + std::to_string(count) + " vertex sites, seed " +
                             std::to_string(seed + static_cast<std::uint64_t>(count));
    GeodesicOptions on, off;
    off.remove_redundant_windows = false;
    GeodesicField with_rwr, without_rwr;
    ASSERT_NO_THROW(with_rwr = compute_geodesic_field(mesh, sites, on)) << what;
    const FieldSummary summary =
        check_invariants(what + " (RWR on)", mesh, sites, with_rwr, component, referenced, edges);
    // RWR off keeps every window: the single-site run of the three meshes
    // above 150K faces alone would take half a minute, so they compare RWR on
    // and off with 30 and 1000 sites only.
    if (count == 1 && mesh.num_faces() > 150000) {
      std::cout << std::setprecision(3) << "[robustness] " << what << ": " << summary.finite
                << " reached vertices, max Lipschitz excess " << summary.max_lipschitz_excess << "; RWR on "
                << with_rwr.stats.total_seconds << " s, peak windows " << with_rwr.stats.peak_windows
                << " (RWR off not run)\n";
      continue;
    }
    ASSERT_NO_THROW(without_rwr = compute_geodesic_field(mesh, sites, off)) << what;
    check_invariants(what + " (RWR off)", mesh, sites, without_rwr, component, referenced, edges);

    // RWR frees windows only; distances and labels must not change.
    int different_distances = 0, different_labels = 0;
    double max_relative = 0;
    const double diag = test::bbox_diagonal(mesh);
    for (Index v = 0; v < mesh.num_vertices(); ++v) {
      const double a = with_rwr.distance[v], b = without_rwr.distance[v];
      if (a != b) {
        ++different_distances;
        max_relative = std::max(max_relative, std::isfinite(a - b) ? std::abs(a - b) / diag : 1e300);
      }
      different_labels += with_rwr.nearest_site[v] != without_rwr.nearest_site[v];
    }
    EXPECT_LE(max_relative, 1e-12) << what << ": RWR on and off disagree";
    EXPECT_EQ(different_labels, 0) << what << ": RWR on and off name different sites";
    std::cout << std::setprecision(3) << "[robustness] " << what << ": " << summary.finite
              << " reached vertices, max Lipschitz excess " << summary.max_lipschitz_excess << "; RWR on "
              << with_rwr.stats.total_seconds << " s, peak windows " << with_rwr.stats.peak_windows << ", stored "
              << with_rwr.stats.windows_stored << " | off " << without_rwr.stats.total_seconds << " s, peak "
              << without_rwr.stats.peak_windows << "; on/off: " << different_distances << " distances differ (max "
              << max_relative << " of the diagonal), " << different_labels << " labels differ\n";
  }
}

INSTANTIATE_TEST_SUITE_P(Shared, SharedMesh, ::testing::ValuesIn(manifest_meshes()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = param_info.param.substr(0, param_info.param.find('.'));
                           for (char& ch : name) {
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           }
                           return name;
                         });

TEST(GeodesicRobustness, SameInputSameOutput) {
  const TriangleMesh mesh = test::read_test_ply(test::test_mesh_path("bunny_res2.ply"));
  const auto sites = test::random_vertex_sites(mesh, 40, 9);
  const GeodesicField a = compute_geodesic_field(mesh, sites), b = compute_geodesic_field(mesh, sites);
  EXPECT_EQ(a.distance, b.distance);
  EXPECT_EQ(a.nearest_site, b.nearest_site);
  EXPECT_EQ(a.valid_face, b.valid_face);
  EXPECT_EQ(a.window_begin, b.window_begin);
  ASSERT_EQ(a.windows.size(), b.windows.size());
  for (std::size_t i = 0; i < a.windows.size(); ++i) {
    const EdgeWindow &x = a.windows[i], &y = b.windows[i];
    EXPECT_TRUE(x.b0 == y.b0 && x.b1 == y.b1 && x.source_x == y.source_x && x.source_y == y.source_y &&
                x.sigma == y.sigma && x.site == y.site)
        << "window " << i;
  }
}

// ---------------------------------------------------------------------------
// Error contract

TriangleMesh small_square() { return test::flat_square(6, 0.2, 5); }

template <class Exception>
void expect_throws(const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites, const std::string& what,
                   const GeodesicOptions& options = {}) {
  try {
    (void)compute_geodesic_field(mesh, sites, options);
    ADD_FAILURE() << what << ": no exception";
  } catch (const Exception& e) {
    EXPECT_FALSE(std::string(e.what()).empty()) << what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": wrong exception type: " << e.what();
  }
}

TEST(GeodesicErrors, VertexOutOfRange) {
  const TriangleMesh mesh = small_square();
  expect_throws<Error>(mesh, {SurfacePoint::at_vertex(-1)}, "vertex -1");
  expect_throws<Error>(mesh, {SurfacePoint::at_vertex(mesh.num_vertices())}, "vertex == num_vertices");
  expect_throws<Error>(mesh, {SurfacePoint::at_vertex(3), SurfacePoint::at_vertex(1 << 30)}, "second site bad");
}

TEST(GeodesicErrors, FaceOutOfRange) {
  const TriangleMesh mesh = small_square();
  expect_throws<Error>(mesh, {SurfacePoint::in_face(-1, 0.2, 0.3, 0.5)}, "face -1");
  expect_throws<Error>(mesh, {SurfacePoint::in_face(mesh.num_faces(), 0.2, 0.3, 0.5)}, "face == num_faces");
}

TEST(GeodesicErrors, BadBarycentricCoordinates) {
  const TriangleMesh mesh = small_square();
  expect_throws<Error>(mesh, {SurfacePoint::in_face(3, -0.1, 0.6, 0.5)}, "negative coordinate");
  expect_throws<Error>(mesh, {SurfacePoint::in_face(3, 0.2, 0.2, 0.2)}, "sum 0.6");
  expect_throws<Error>(mesh, {SurfacePoint::in_face(3, 0.5, 0.5, 0.5)}, "sum 1.5");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_throws<Error>(mesh, {SurfacePoint::in_face(3, nan, 0.5, 0.5)}, "NaN");
  const double inf = std::numeric_limits<double>::infinity();
  expect_throws<Error>(mesh, {SurfacePoint::in_face(3, inf, -inf, 1.0)}, "infinite");
}

TEST(GeodesicErrors, TwoSitesAtTheSamePoint) {
  const TriangleMesh mesh = small_square();
  expect_throws<Error>(mesh, {SurfacePoint::at_vertex(9), SurfacePoint::at_vertex(9)}, "same vertex twice");
  expect_throws<Error>(mesh, {SurfacePoint::in_face(4, 0.2, 0.3, 0.5), SurfacePoint::in_face(4, 0.2, 0.3, 0.5)},
                       "same face point twice");
  // The same point named two ways: a vertex and a face corner.
  const Index v = mesh.faces(4, 1);
  expect_throws<Error>(mesh, {SurfacePoint::at_vertex(v), SurfacePoint::in_face(4, 0.0, 1.0, 0.0)},
                       "vertex and face corner");
}

TEST(GeodesicErrors, SiteOnAFaceWithARepeatedVertex) {
  TriangleMesh mesh = small_square();
  const Index f = mesh.num_faces();
  mesh.faces.conservativeResize(f + 1, 3);
  mesh.faces.row(f) << 8, 8, 9;
  expect_throws<Error>(mesh, {SurfacePoint::in_face(f, 0.2, 0.3, 0.5)}, "face with a repeated vertex");
  // The rest of the mesh is unaffected by such a face.
  const GeodesicField field = compute_geodesic_field(mesh, std::vector<SurfacePoint>{SurfacePoint::at_vertex(0)});
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    EXPECT_NEAR(field.distance[v], mesh.vertices.row(v).norm(), 1e-12) << "vertex " << v;
  }
}

TEST(GeodesicErrors, SiteOnAnUnreferencedVertex) {
  TriangleMesh mesh = small_square();
  const Index v = mesh.num_vertices();
  mesh.vertices.conservativeResize(v + 1, 3);
  mesh.vertices.row(v) << 5, 5, 5;
  expect_throws<Error>(mesh, {SurfacePoint::at_vertex(v)}, "unreferenced vertex");
  const GeodesicField field = compute_geodesic_field(mesh, std::vector<SurfacePoint>{SurfacePoint::at_vertex(0)});
  EXPECT_EQ(field.distance[v], std::numeric_limits<double>::infinity());
  EXPECT_EQ(field.nearest_site[v], -1);
}

TEST(GeodesicErrors, NoSitesIsAnErrorOrUnreachable) {
  const TriangleMesh mesh = small_square();
  try {
    const GeodesicField field = compute_geodesic_field(mesh, std::vector<SurfacePoint>{});
    for (Index v = 0; v < mesh.num_vertices(); ++v) {
      EXPECT_EQ(field.distance[v], std::numeric_limits<double>::infinity());
      EXPECT_EQ(field.nearest_site[v], -1);
    }
  } catch (const Error&) {
    SUCCEED();
  }
}

TEST(GeodesicErrors, WindowMemoryLimit) {
  const TriangleMesh mesh = test::read_test_ply(test::test_mesh_path("fertility.ply"));
  const auto sites = test::random_vertex_sites(mesh, 3, 77);
  for (std::size_t limit : {std::size_t{0}, std::size_t{1}, std::size_t{1000}, std::size_t{64} << 10}) {
    GeodesicOptions options;
    options.window_memory_limit_bytes = limit;
    try {
      (void)compute_geodesic_field(mesh, sites, options);
      ADD_FAILURE() << "limit " << limit << " bytes: no exception";
    } catch (const Cancelled& e) {
      ADD_FAILURE() << "limit " << limit << " bytes: Cancelled instead of Error: " << e.what();
    } catch (const Error& e) {
      EXPECT_FALSE(std::string(e.what()).empty());
    }
  }
  // A limit just above what the run needs is enough.
  const GeodesicField field = compute_geodesic_field(mesh, sites);
  GeodesicOptions enough;
  enough.window_memory_limit_bytes = static_cast<std::size_t>(field.stats.peak_window_bytes) * 2 + 4096;
  EXPECT_NO_THROW((void)compute_geodesic_field(mesh, sites, enough));
}

TEST(GeodesicErrors, ProgressCanCancel) {
  const TriangleMesh mesh = test::read_test_ply(test::test_mesh_path("fertility.ply"));
  const auto sites = test::random_vertex_sites(mesh, 3, 78);
  std::vector<double> seen;
  GeodesicOptions options;
  options.progress = [&](double fraction) {
    seen.push_back(fraction);
    return true;
  };
  (void)compute_geodesic_field(mesh, sites, options);
  ASSERT_FALSE(seen.empty()) << "progress never called";
  for (double f : seen) {
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
  }
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end())) << "progress went backwards";

  int calls = 0;
  options.progress = [&](double) { return ++calls < 2; };
  expect_throws<Cancelled>(mesh, sites, "cancel on the second call", options);
  options.progress = [](double) { return false; };
  expect_throws<Cancelled>(mesh, sites, "cancel at once", options);
}

}  // namespace
}  // namespace geodual::voronoi
