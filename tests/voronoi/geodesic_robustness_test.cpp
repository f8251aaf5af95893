// Every shared mesh, defects included (boundaries, non-manifold edges and
// vertices, several components, zero-area faces, unreferenced vertices), with
// 1, 30 and 1000 random vertex sites: the engine completes, reaches exactly the
// components that hold a site, gives distances that are 1-Lipschitz along every
// edge, zero at the sites, and the same with Redundant Window Removal on and
// off. Plus the error contract: bad sites, the window memory limit and
// cancellation through the progress callback.

#include "geodual/error.hpp"
#include "geodual/io/read_mesh.hpp"
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

// The shared set as described by MANIFEST.md; the test below checks that the
// folder holds no other mesh, so that a new file is not silently skipped.
const std::vector<std::string>& manifest_meshes() {
  static const std::vector<std::string> files = {
      "amo.ply",         "armadillo_86k.ply", "bunny.ply",     "bunny_res2.ply",     "cheburashka.ply",
      "dragon_100k.ply", "fandisk.ply",       "fertility.ply", "homer.ply",          "horse.ply",
      "igea.ply",        "lucy_100k.ply",     "nefertiti_100k.ply", "ogre.ply",      "rocker_arm.ply",
      "spot.ply",        "turbineblade_199k.ply", "woody.ply"};
  return files;
}

TEST(GeodesicRobustness, EverySharedMeshIsCovered) {
  EXPECT_EQ(test::shared_mesh_files(), manifest_meshes());
}

struct FieldSummary {
  int finite = 0;
  double max_lipschitz_excess = 0;  ///< max (|d(a) - d(b)| / |ab| - 1) over edges
};

/// Checks the invariants of one field; returns a summary for the report.
FieldSummary check_invariants(const std::string& what, const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites,
                              const GeodesicField& field, const std::vector<Index>& component,
                              const std::vector<bool>& referenced,
                              const std::vector<std::array<Index, 2>>& edges) {
  SCOPED_TRACE(what);
  FieldSummary summary;
  const Index nv = mesh.num_vertices();
  const Index num_sites = static_cast<Index>(sites.size());
  EXPECT_EQ(field.distance.size(), static_cast<std::size_t>(nv));
  EXPECT_EQ(field.nearest_site.size(), static_cast<std::size_t>(nv));
  if (field.distance.size() != static_cast<std::size_t>(nv) || field.nearest_site.size() != static_cast<std::size_t>(nv)) {
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
                    << da << " (site " << field.nearest_site[a] << ") and " << db << " (site "
                    << field.nearest_site[b] << ") differ by more than the length";
    }
  }
  EXPECT_EQ(lipschitz_failures, 0) << "edges where the distance is not 1-Lipschitz";

  for (Index i = 0; i < num_sites; ++i) {
    const Index v = sites[static_cast<std::size_t>(i)].element;
    EXPECT_EQ(field.distance[v], 0.0) << "site " << i << " at vertex " << v;
    EXPECT_EQ(field.nearest_site[v], i) << "site " << i << " at vertex " << v;
  }
  return summary;
}

class SharedMesh : public ::testing::TestWithParam<std::string> {};

TEST_P(SharedMesh, RandomVertexSites) {
  const std::string file = GetParam();
  const TriangleMesh mesh = io::read_mesh(test::shared_mesh_path(file)).mesh;
  const auto component = test::vertex_components(mesh);
  const auto referenced = test::referenced_vertices(mesh);
  const auto edges = test::unique_edges(mesh);
  std::uint64_t seed = 1;
  for (char ch : file) seed = seed * 131 + static_cast<unsigned char>(ch);

  const int usable = static_cast<int>(std::count(referenced.begin(), referenced.end(), true));
  for (int wanted : {1, 30, 1000}) {
    const int count = std::min(wanted, usable / 2);  // woody has only 694 vertices
    const std::vector<SurfacePoint> sites = test::random_vertex_sites(mesh, count, seed + static_cast<std::uint64_t>(count));
    const std::string what = file + ", " + std::to_string(count) + " vertex sites, seed " +
                             std::to_string(seed + static_cast<std::uint64_t>(count));
    GeodesicOptions on, off;
    off.remove_redundant_windows = false;
    GeodesicField with_rwr, without_rwr;
    ASSERT_NO_THROW(with_rwr = compute_geodesic_field(mesh, sites, on)) << what;
    ASSERT_NO_THROW(without_rwr = compute_geodesic_field(mesh, sites, off)) << what;
    const FieldSummary summary =
        check_invariants(what + " (RWR on)", mesh, sites, with_rwr, component, referenced, edges);
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
              << without_rwr.stats.peak_windows << "; on/off: " << different_distances
              << " distances differ (max " << max_relative << " of the diagonal), " << different_labels
              << " labels differ\n";
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
  const TriangleMesh mesh = test::read_shared_ply(test::shared_mesh_path("fertility.ply"));
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
  const TriangleMesh mesh = test::read_shared_ply(test::shared_mesh_path("fertility.ply"));
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
