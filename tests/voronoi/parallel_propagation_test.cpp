// Propagation in groups of sites (GeodesicOptions::site_groups): the same
// bytes for any number of threads, the exact distances on a plane (where
// they are the Euclidean distance to the nearest site), and the same
// distances and labels as propagating all sites at once. (The CGAL oracle
// checks grouped fields too: geodesic_oracle_test.cpp.)

#include "geodual/voronoi/geodesic_field.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"
#include "voronoi/test_meshes.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace geodual::voronoi {
namespace {

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expect_identical(const GeodesicField& a, const GeodesicField& b) {
  EXPECT_TRUE(same_bytes(a.distance, b.distance));
  EXPECT_TRUE(same_bytes(a.nearest_site, b.nearest_site));
  EXPECT_TRUE(same_bytes(a.window_begin, b.window_begin));
  ASSERT_EQ(a.windows.size(), b.windows.size());
  for (std::size_t i = 0; i < a.windows.size(); ++i) {
    const EdgeWindow &x = a.windows[i], &y = b.windows[i];
    const bool same = std::memcmp(&x.b0, &y.b0, sizeof(double)) == 0 &&
                      std::memcmp(&x.b1, &y.b1, sizeof(double)) == 0 &&
                      std::memcmp(&x.source_x, &y.source_x, sizeof(double)) == 0 &&
                      std::memcmp(&x.source_y, &y.source_y, sizeof(double)) == 0 &&
                      std::memcmp(&x.sigma, &y.sigma, sizeof(double)) == 0 && x.site == y.site;
    if (!same) {
      ADD_FAILURE() << "window " << i << " differs";
      break;
    }
  }
  ASSERT_EQ(a.face_point_sources.size(), b.face_point_sources.size());
  for (std::size_t i = 0; i < a.face_point_sources.size(); ++i) {
    const FacePointSource &x = a.face_point_sources[i], &y = b.face_point_sources[i];
    EXPECT_TRUE(x.face == y.face && x.site == y.site && x.sigma == y.sigma && x.barycentric == y.barycentric);
  }
  EXPECT_EQ(a.valid_face, b.valid_face);
  EXPECT_EQ(a.stats.windows_created, b.stats.windows_created);
  EXPECT_EQ(a.stats.windows_stored, b.stats.windows_stored);
}

GeodesicField field_on_threads(const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites, int groups,
                               int threads) {
  GeodesicOptions options;
  options.site_groups = groups;
  // Allow more threads than cores, so that 3 and 4 threads really run.
  const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  tbb::task_arena arena(threads);
  return arena.execute([&] { return compute_geodesic_field(mesh, sites, options); });
}

std::vector<SurfacePoint> mixed_sites(const TriangleMesh& mesh, int count, std::uint64_t seed) {
  std::vector<SurfacePoint> sites = test::random_vertex_sites(mesh, count / 2, seed);
  for (const SurfacePoint& s : test::random_face_sites(mesh, count - count / 2, seed + 1)) sites.push_back(s);
  return sites;
}

TEST(ParallelPropagation, SameBytesOnAnyNumberOfThreads) {
  const TriangleMesh mesh = test::read_test_ply(test::test_mesh_path("bunny.ply"));  // holes, unreferenced vertices
  const std::vector<SurfacePoint> sites = mixed_sites(mesh, 120, 17);
  for (const int groups : {3, 8}) {
    SCOPED_TRACE("groups " + std::to_string(groups));
    const GeodesicField one = field_on_threads(mesh, sites, groups, 1);
    EXPECT_GT(one.windows.size(), 0u);
    for (const int threads : {2, 3, 4}) {
      SCOPED_TRACE("threads " + std::to_string(threads));
      expect_identical(one, field_on_threads(mesh, sites, groups, threads));
    }
  }
}

TEST(ParallelPropagation, DiagramSameOnAnyNumberOfThreads) {
  const TriangleMesh mesh = test::read_test_ply(test::test_mesh_path("fertility.ply"));
  const std::vector<SurfacePoint> sites = mixed_sites(mesh, 200, 5);
  VoronoiOptions options;
  options.geodesic.site_groups = 6;
  auto diagram_on = [&](int threads) {
    const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    tbb::task_arena arena(threads);
    return arena.execute([&] { return compute_voronoi(mesh, sites, options); });
  };
  const VoronoiDiagram one = diagram_on(1);
  const VoronoiDiagram two = diagram_on(2);
  const VoronoiDiagram four = diagram_on(4);
  for (const VoronoiDiagram* other : {&two, &four}) {
    expect_identical(one.field, other->field);
    ASSERT_EQ(one.vertices.size(), other->vertices.size());
    EXPECT_EQ(one.vertex_sites, other->vertex_sites);
    EXPECT_TRUE(same_bytes(one.cell_area, other->cell_area));
    ASSERT_EQ(one.adjacency.size(), other->adjacency.size());
    for (std::size_t i = 0; i < one.adjacency.size(); ++i) {
      EXPECT_EQ(one.adjacency[i].site_a, other->adjacency[i].site_a);
      EXPECT_EQ(one.adjacency[i].site_b, other->adjacency[i].site_b);
    }
  }
}

// On a plane every geodesic is a straight segment: the distance at a vertex
// is the Euclidean distance to the nearest site, and so is query() inside a
// valid face.
// By default even a few sites propagate in two groups (a second core has
// work), a single site in one, and larger inputs in one group per 256 sites;
// the default's result is the same on any number of threads.
TEST(ParallelPropagation, DefaultGroupsDependOnTheSitesAlone) {
  const TriangleMesh mesh = test::read_test_ply(test::test_mesh_path("bunny.ply"));
  const std::vector<SurfacePoint> few = mixed_sites(mesh, 30, 3);
  const GeodesicField one = field_on_threads(mesh, few, 0, 1);
  EXPECT_EQ(one.stats.site_groups, 2);
  const GeodesicField two = field_on_threads(mesh, few, 0, 2);
  EXPECT_EQ(two.stats.site_groups, 2);
  expect_identical(one, two);
  EXPECT_EQ(field_on_threads(mesh, mixed_sites(mesh, 1, 4), 0, 2).stats.site_groups, 1);
  EXPECT_EQ(field_on_threads(mesh, mixed_sites(mesh, 1000, 5), 0, 2).stats.site_groups, 3);
}

TEST(ParallelPropagation, ExactOnAPlane) {
  const TriangleMesh mesh = test::flat_square(60, 0.3, 11);
  const std::vector<SurfacePoint> sites = mixed_sites(mesh, 90, 23);
  std::vector<Eigen::Vector3d> positions;
  for (const SurfacePoint& s : sites) positions.push_back(s.position(mesh));
  auto nearest = [&](const Eigen::Vector3d& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& q : positions) best = std::min(best, (p - q).norm());
    return best;
  };
  const double tol = 1e-9 * test::bbox_diagonal(mesh);
  for (const int groups : {2, 5, 30}) {
    SCOPED_TRACE("groups " + std::to_string(groups));
    const GeodesicField field = field_on_threads(mesh, sites, groups, 2);
    for (Index v = 0; v < mesh.num_vertices(); ++v) {
      const Eigen::Vector3d p = mesh.vertices.row(v).transpose();
      ASSERT_NEAR(field.distance[v], nearest(p), tol) << "vertex " << v;
      ASSERT_NEAR((positions[static_cast<std::size_t>(field.nearest_site[v])] - p).norm(), field.distance[v], tol);
    }
    int valid = 0;
    for (const SurfacePoint& point : test::random_face_sites(mesh, 400, 29)) {
      if (!field.valid_face[static_cast<std::size_t>(point.element)]) continue;
      ++valid;
      EXPECT_NEAR(query(field, mesh, point).distance, nearest(point.position(mesh)), tol);
    }
    EXPECT_GT(valid, 0);
  }
}

// Grouped and all at once: the same exact distances, the same labels (bar
// exact ties), and windows only where the sequential run keeps them, give or
// take the faces next to ties.
TEST(ParallelPropagation, AgreesWithPropagationAtOnce) {
  const TriangleMesh mesh = test::read_test_ply(test::test_mesh_path("fandisk.ply"));  // sharp features
  const std::vector<SurfacePoint> sites = mixed_sites(mesh, 150, 31);
  const GeodesicField at_once = field_on_threads(mesh, sites, 1, 2);
  const double tol = 1e-9 * test::bbox_diagonal(mesh);
  for (const int groups : {2, 7, 150}) {
    SCOPED_TRACE("groups " + std::to_string(groups));
    const GeodesicField grouped = field_on_threads(mesh, sites, groups, 2);
    int differing_labels = 0;
    for (Index v = 0; v < mesh.num_vertices(); ++v) {
      if (std::isinf(at_once.distance[v])) {
        EXPECT_TRUE(std::isinf(grouped.distance[v]));
        continue;
      }
      ASSERT_NEAR(grouped.distance[v], at_once.distance[v], tol) << "vertex " << v;
      if (grouped.nearest_site[v] != at_once.nearest_site[v]) ++differing_labels;
    }
    EXPECT_LE(differing_labels, 2);
    int valid_differ = 0;
    for (std::size_t f = 0; f < grouped.valid_face.size(); ++f)
      valid_differ += grouped.valid_face[f] != at_once.valid_face[f];
    EXPECT_LE(valid_differ, static_cast<int>(grouped.valid_face.size() / 100)) << "valid faces differ";
  }
}

}  // namespace
}  // namespace geodual::voronoi

namespace geodual::voronoi {
namespace {

TEST(ParallelPropagation, GroupsKeepTheirWindowsWithoutRedundantWindowRemoval) {
  // With RWR off the merge keeps every edge's windows; with it on, an edge
  // keeps the same windows or none.
  const TriangleMesh mesh = test::read_test_ply(test::test_mesh_path("fertility.ply"));
  const std::vector<SurfacePoint> sites = test::random_face_sites(mesh, 120, 3);
  GeodesicOptions kept, removed;
  kept.site_groups = removed.site_groups = 3;
  kept.remove_redundant_windows = false;
  const GeodesicField all = compute_geodesic_field(mesh, sites, kept);
  const GeodesicField some = compute_geodesic_field(mesh, sites, removed);
  EXPECT_GT(all.windows.size(), some.windows.size() * 3 / 2);
  ASSERT_EQ(all.window_begin.size(), some.window_begin.size());
  Index edges_kept = 0;
  for (std::size_t e = 0; e + 1 < all.window_begin.size(); ++e) {
    const Index n = some.window_begin[e + 1] - some.window_begin[e];
    if (n == 0) continue;
    ++edges_kept;
    EXPECT_EQ(n, all.window_begin[e + 1] - all.window_begin[e]) << "edge " << e;
  }
  EXPECT_GT(edges_kept, 0);
  EXPECT_EQ(all.distance, some.distance);
  EXPECT_EQ(all.nearest_site, some.nearest_site);
}

}  // namespace
}  // namespace geodual::voronoi
