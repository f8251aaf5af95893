// An edge crossed by thousands of Voronoi cells holds more windows than one
// page of the window store, which keeps them in pages of their own. Moving
// the windows out of the store after propagation then has to step over the
// pages given back below that edge (issue 19: a SIGSEGV on a CAD surface).

#include "geodual/voronoi/geodesic_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace geodual::voronoi {
namespace {

TEST(LongEdge, ThousandsOfCellsAlongOneEdgeBesideAFineGrid) {
  // A strip [0, n] x [0, 1] of two triangles with a site at every unit along
  // it (its diagonal and long sides each hold ~n windows), and a grid of
  // g x g unit cells to the right with many vertex sites (many edges of a
  // few windows each).
  constexpr int n = 5000, g = 60;
  constexpr double length = n;
  TriangleMesh mesh;
  mesh.vertices.resize(4 + (g + 1) * (g + 1), 3);
  mesh.vertices.topRows(4) << 0, 0, 0, length, 0, 0, length, 1, 0, 0, 1, 0;
  auto grid = [&](int i, int j) { return static_cast<Index>(4 + j * (g + 1) + i); };
  for (int j = 0; j <= g; ++j) {
    for (int i = 0; i <= g; ++i) mesh.vertices.row(grid(i, j)) << 2 * length + i, 5.0 + j, 0;
  }
  mesh.faces.resize(2 + 2 * g * g, 3);
  mesh.faces.topRows(2) << 0, 1, 2, 0, 2, 3;
  Index f = 2;
  for (int j = 0; j < g; ++j) {
    for (int i = 0; i < g; ++i) {
      mesh.faces.row(f++) << grid(i, j), grid(i + 1, j), grid(i + 1, j + 1);
      mesh.faces.row(f++) << grid(i, j), grid(i + 1, j + 1), grid(i, j + 1);
    }
  }
  std::vector<SurfacePoint> sites;
  for (int i = 0; i < n; ++i) {
    const double x = i + 0.5, y = i % 2 ? 0.3 : 0.7;
    if (y < x / length) {  // face 0: (0,0) + u (n,0) + v (n,1) - ...
      sites.push_back(SurfacePoint::in_face(0, 1 - x / length, x / length - y, y));
    } else {  // face 1: (0,0) + u (n,1) + v (0,1)
      sites.push_back(SurfacePoint::in_face(1, 1 - y, x / length, y - x / length));
    }
  }
  for (int j = 0; j <= g; ++j) {
    for (int i = 0; i <= g; i += 3) {
      if ((i + j) % 2 == 0) sites.push_back(SurfacePoint::at_vertex(grid(i, j)));
    }
  }
  const GeodesicField field = compute_geodesic_field(mesh, sites);

  // The diagonal (vertices 0 and 2) holds more windows than a page (4096).
  std::int64_t diagonal_windows = -1;
  for (std::size_t e = 0; e < field.edge_faces.size(); ++e) {
    const auto [a, b] = field.edge_vertices(mesh, static_cast<Index>(e));
    if ((a == 0 && b == 2) || (a == 2 && b == 0)) diagonal_windows = field.window_begin[e + 1] - field.window_begin[e];
  }
  EXPECT_GT(diagonal_windows, 4096);
  // Straight-line distances on the flat strip: the corners' nearest sites.
  EXPECT_EQ(field.nearest_site[0], 0);
  EXPECT_NEAR(field.distance[0], std::hypot(0.5, 0.7), 1e-9);
  EXPECT_EQ(field.nearest_site[2], n - 1);
  EXPECT_NEAR(field.distance[2], std::hypot(0.5, 0.7), 1e-9);
  for (Index v = 4; v < mesh.num_vertices(); ++v) EXPECT_GE(field.nearest_site[v], n) << "vertex " << v;
}

}  // namespace
}  // namespace geodual::voronoi
