// The prepared surface: fields and diagrams computed on one GeodesicSurface
// are bit for bit those computed from the mesh, call after call, and share
// its topology instead of copying it.

#include "geodual/voronoi/geodesic_surface.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"
#include "test_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

namespace geodual::voronoi {
namespace {

using test::random_face_sites;
using test::random_vertex_sites;
using IndexPair = std::array<Index, 2>;
using IndexTriple = std::array<Index, 3>;

/// Same bits (NaN-safe, and telling -0 from 0). Arrays of structs with
/// padding (EdgeWindow) are compared member by member.
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

template <class T>
bool same_span(std::span<const T> a, std::span<const T> b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size_bytes()) == 0);
}

void expect_same_field(const GeodesicField& a, const GeodesicField& b) {
  ASSERT_EQ(a.distance.size(), b.distance.size());
  for (std::size_t v = 0; v < a.distance.size(); ++v) {
    ASSERT_TRUE(same_bits(a.distance[v], b.distance[v])) << "vertex " << v;
  }
  EXPECT_EQ(a.nearest_site, b.nearest_site);
  EXPECT_TRUE(same_span<IndexPair>(a.edge_faces, b.edge_faces));
  EXPECT_TRUE(same_span<double>(a.edge_length, b.edge_length));
  EXPECT_TRUE(same_span<IndexTriple>(a.face_edges, b.face_edges));
  EXPECT_EQ(a.window_begin, b.window_begin);
  ASSERT_EQ(a.windows.size(), b.windows.size());
  for (std::size_t i = 0; i < a.windows.size(); ++i) {
    const EdgeWindow &w = a.windows[i], &u = b.windows[i];
    ASSERT_TRUE(same_bits(w.b0, u.b0) && same_bits(w.b1, u.b1) && same_bits(w.source_x, u.source_x) &&
                same_bits(w.source_y, u.source_y) && same_bits(w.sigma, u.sigma) && w.site == u.site)
        << "window " << i;
  }
  EXPECT_EQ(a.valid_face, b.valid_face);
  ASSERT_EQ(a.face_point_sources.size(), b.face_point_sources.size());
  for (std::size_t i = 0; i < a.face_point_sources.size(); ++i) {
    const FacePointSource &p = a.face_point_sources[i], &q = b.face_point_sources[i];
    EXPECT_TRUE(p.face == q.face && p.site == q.site && same_bits(p.sigma, q.sigma) && p.barycentric == q.barycentric);
  }
}

/// A scan with boundary loops, non-manifold edges and duplicated vertices.
const TriangleMesh& scan() {
  static const TriangleMesh mesh = test::read_test_ply(test::test_mesh_path("bunny_res2.ply"));
  return mesh;
}

TEST(GeodesicSurface, EdgesRunAsTheirFirstFaceAndHaveTheirEndsLength) {
  // On a scan with boundaries and non-manifold edges: every edge's ends are
  // consecutive corners of its face [0], in that face's order, at the
  // edge's length apart; its face [1], if any, has the edge too.
  const TriangleMesh& mesh = scan();
  const GeodesicSurface surface(mesh);
  const SurfaceTopology& topology = *surface.topology();
  ASSERT_EQ(topology.edge_length.size(), topology.edge_faces.size());
  int failures = 0;
  for (Index e = 0; e < static_cast<Index>(topology.edge_faces.size()) && failures < 5; ++e) {
    const auto [v0, v1] = topology.edge_vertices(mesh, e);
    const auto [f0, f1] = topology.edge_faces[static_cast<std::size_t>(e)];
    bool ok = f0 >= 0 && v0 != v1;
    if (ok) {
      int k = 0;
      while (k < 3 && topology.face_edges[static_cast<std::size_t>(f0)][static_cast<std::size_t>(k)] != e) ++k;
      ok = k < 3 && mesh.faces(f0, k) == v0 && mesh.faces(f0, (k + 1) % 3) == v1;
    }
    if (ok && f1 >= 0) {
      const IndexTriple& sides = topology.face_edges[static_cast<std::size_t>(f1)];
      int ends = 0;
      for (int c = 0; c < 3; ++c) ends += mesh.faces(f1, c) == v0 || mesh.faces(f1, c) == v1;
      ok = std::count(sides.begin(), sides.end(), e) == 1 && ends == 2;
    }
    const double length = (mesh.vertices.row(v1) - mesh.vertices.row(v0)).norm();
    ok = ok && std::abs(length - topology.edge_length[static_cast<std::size_t>(e)]) <= 1e-15 * (1 + length);
    if (!ok) ADD_FAILURE() << "edge " << e << " (" << v0 << ", " << v1 << ") faces " << f0 << ", " << f1, ++failures;
  }
}

TEST(GeodesicSurface, FieldsAreThoseOfTheMeshCallAfterCall) {
  const TriangleMesh& mesh = scan();
  const GeodesicSurface surface(mesh);
  // Several site sets on the one surface (face points and vertices): each
  // field is the one the mesh gives, whatever was computed on it before.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    std::vector<SurfacePoint> sites = random_face_sites(mesh, 60, seed);
    for (const SurfacePoint& v : random_vertex_sites(mesh, 20, seed + 100)) sites.push_back(v);
    const GeodesicField prepared = compute_geodesic_field(surface, sites);
    const GeodesicField unprepared = compute_geodesic_field(mesh, sites);
    ASSERT_GT(prepared.windows.size(), 0U);
    expect_same_field(prepared, unprepared);
  }
}

TEST(GeodesicSurface, DiagramsAreThoseOfTheMesh) {
  const TriangleMesh& mesh = scan();
  const GeodesicSurface surface(mesh);
  const std::vector<SurfacePoint> sites = random_face_sites(mesh, 80, 7);
  const VoronoiDiagram prepared = compute_voronoi(surface, sites);
  const VoronoiDiagram unprepared = compute_voronoi(mesh, sites);
  expect_same_field(prepared.field, unprepared.field);
  ASSERT_EQ(prepared.cell_area.size(), unprepared.cell_area.size());
  for (std::size_t s = 0; s < prepared.cell_area.size(); ++s) {
    EXPECT_TRUE(same_bits(prepared.cell_area[s], unprepared.cell_area[s])) << "site " << s;
    EXPECT_TRUE(same_bits(prepared.cell_energy[s], unprepared.cell_energy[s])) << "site " << s;
  }
  ASSERT_EQ(prepared.points.size(), unprepared.points.size());
  EXPECT_TRUE(same_span<Eigen::Vector3d>(prepared.points, unprepared.points));
  EXPECT_EQ(prepared.vertex_sites, unprepared.vertex_sites);
  EXPECT_EQ(prepared.arcs.size(), unprepared.arcs.size());
}

TEST(GeodesicSurface, FieldsShareTheTopologyAndOutliveTheSurface) {
  const TriangleMesh& mesh = scan();
  std::optional<GeodesicSurface> surface(std::in_place, mesh);
  const GeodesicField a = compute_geodesic_field(*surface, random_face_sites(mesh, 30, 1));
  const GeodesicField b = compute_geodesic_field(*surface, random_face_sites(mesh, 30, 2));
  EXPECT_EQ(a.topology.get(), surface->topology().get());
  EXPECT_EQ(b.topology.get(), a.topology.get());
  EXPECT_EQ(a.face_edges.data(), b.face_edges.data());
  EXPECT_GT(surface->memory_bytes(), mesh.faces.size() * sizeof(Index));
  const std::vector<IndexTriple> face_edges(a.face_edges.begin(), a.face_edges.end());
  surface.reset();
  // The topology lives on with the fields.
  ASSERT_EQ(a.face_edges.size(), static_cast<std::size_t>(mesh.num_faces()));
  EXPECT_TRUE(same_span<IndexTriple>(a.face_edges, face_edges));
  const GeodesicField c = compute_geodesic_field(mesh, random_face_sites(mesh, 30, 1));
  EXPECT_NE(c.topology.get(), a.topology.get());
  expect_same_field(a, c);
}

TEST(GeodesicSurface, BadSitesAreRejectedAsFromTheMesh) {
  const TriangleMesh& mesh = scan();
  const GeodesicSurface surface(mesh);
  const std::vector<SurfacePoint> bad = {SurfacePoint::at_vertex(mesh.num_vertices())};
  EXPECT_THROW(compute_geodesic_field(surface, bad), Error);
  // The surface is still good afterwards.
  const std::vector<SurfacePoint> sites = random_face_sites(mesh, 10, 3);
  expect_same_field(compute_geodesic_field(surface, sites), compute_geodesic_field(mesh, sites));
}

}  // namespace
}  // namespace geodual::voronoi
