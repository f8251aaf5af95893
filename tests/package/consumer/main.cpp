// Uses every installed geodual library through the imported targets, and
// checks each result against an independent oracle (analytic values):
//   io       write a .glb and read it back: the same vertices and faces;
//   voronoi  geodesic distances on a flat grid are Euclidean distances;
//   remesh   quality of a grid of right isosceles triangles (closed form),
//            Hausdorff distance between two parallel grids (their offset),
//            and a remesh of a sphere (CGAL, TBB) that is a closed genus-0 surface;
//   pipeline the library's version is the package's version.
// Prints one line per check; exit status 0 when all pass, 1 otherwise.

#include <geodual/io/gltf.hpp>
#include <geodual/io/read_mesh.hpp>
#include <geodual/mesh/error.hpp>
#include <geodual/mesh/triangle_mesh.hpp>
#include <geodual/pipeline/version.hpp>
#include <geodual/quality/quality_stats.hpp>
#include <geodual/remesh/remesh.hpp>
#include <geodual/remesh/sample_sites.hpp>
#include <geodual/voronoi/geodesic_field.hpp>

#include <cmath>
#include <cstddef>
#include <exception>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

namespace {

int failures = 0;

void check(bool ok, const std::string& what) {
  std::cout << (ok ? "ok   " : "FAIL ") << what << '\n';
  if (!ok) ++failures;
}

// n x n vertices at integer (x, y), height z: 2 (n-1)^2 right isosceles triangles.
geodual::TriangleMesh grid(int n, double z) {
  geodual::TriangleMesh mesh;
  mesh.vertices.resize(n * n, 3);
  mesh.faces.resize(2 * (n - 1) * (n - 1), 3);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) mesh.vertices.row(y * n + x) << x, y, z;
  }
  int f = 0;
  for (int y = 0; y + 1 < n; ++y) {
    for (int x = 0; x + 1 < n; ++x) {
      const int a = y * n + x;
      mesh.faces.row(f++) << a, a + 1, a + n + 1;
      mesh.faces.row(f++) << a, a + n + 1, a + n;
    }
  }
  return mesh;
}

// A UV sphere of radius 1, counter-clockwise seen from outside.
geodual::TriangleMesh sphere(int rings, int segments) {
  geodual::TriangleMesh mesh;
  const int ring_vertices = (rings - 1) * segments;
  mesh.vertices.resize(ring_vertices + 2, 3);
  for (int i = 1; i < rings; ++i) {
    const double theta = std::numbers::pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * std::numbers::pi * j / segments;
      mesh.vertices.row((i - 1) * segments + j) << std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
          std::cos(theta);
    }
  }
  const int north = ring_vertices, south = ring_vertices + 1;
  mesh.vertices.row(north) << 0, 0, 1;
  mesh.vertices.row(south) << 0, 0, -1;
  auto v = [segments](int ring, int j) { return (ring - 1) * segments + j % segments; };
  std::vector<int> faces;
  for (int j = 0; j < segments; ++j) {
    faces.insert(faces.end(), {north, v(1, j), v(1, j + 1), south, v(rings - 1, j + 1), v(rings - 1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      faces.insert(faces.end(), {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  }
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size() / 3), 3);
  for (std::size_t k = 0; k < faces.size(); ++k)
    mesh.faces(static_cast<Eigen::Index>(k / 3), static_cast<Eigen::Index>(k % 3)) = faces[k];
  return mesh;
}

void run_checks() {
  check(geodual::version() == GEODUAL_PACKAGE_VERSION,
        "pipeline: version() " + std::string(geodual::version()) + " is the package's " GEODUAL_PACKAGE_VERSION);

  const geodual::TriangleMesh flat = grid(11, 0.0);

  // io: integer coordinates are float32 values, so the round trip is exact.
  const std::filesystem::path glb = "consumer_grid.glb";
  geodual::io::write_gltf(glb, flat);
  const geodual::TriangleMesh back = geodual::io::read_mesh(glb).mesh;
  check(back.vertices == flat.vertices && back.faces == flat.faces, "io: write_gltf + read_mesh give the grid back");

  // voronoi: on a flat convex patch the geodesic is the straight segment.
  const geodual::SurfacePoint site = geodual::SurfacePoint::at_vertex(5 * 11 + 5);
  const auto field = geodual::voronoi::compute_geodesic_field(flat, std::vector{site});
  double worst = 0;
  for (int v = 0; v < flat.num_vertices(); ++v) {
    worst =
        std::max(worst, std::abs(field.distance[v] - (flat.vertices.row(v) - flat.vertices.row(site.element)).norm()));
  }
  check(worst < 1e-9, "voronoi: geodesic distances on a plane are Euclidean (max error " + std::to_string(worst) + ")");

  // remesh: Q = 6/sqrt(3) A / (p h) with A = 1/2, p = 1 + sqrt(2)/2, h = sqrt(2).
  const double q_right_isosceles = 6 / std::sqrt(3.0) * 0.5 / ((1 + std::sqrt(2.0) / 2) * std::sqrt(2.0));
  const auto quality = geodual::quality::triangle_quality(flat);
  check(std::abs(quality.q_min - q_right_isosceles) < 1e-12 && std::abs(quality.q_avg - q_right_isosceles) < 1e-12 &&
            quality.euler_characteristic == 1 && quality.boundary_loops == 1,
        "remesh: triangle_quality of the grid (Q = " + std::to_string(quality.q_min) + ", one disk)");

  const auto distance = geodual::quality::compare_meshes(flat, grid(11, 0.25), {.samples_per_side = 1000});
  check(std::abs(distance.hausdorff - 0.25) < 1e-9 && std::abs(distance.rms - 0.25) < 1e-9,
        "remesh: compare_meshes of parallel grids 0.25 apart (Hausdorff " + std::to_string(distance.hausdorff) + ")");

  const geodual::TriangleMesh ball = sphere(16, 32);
  const auto sites = geodual::remesh::sample_sites(ball, 60);
  const auto remeshed = geodual::remesh::remesh_from_sites(ball, sites);
  const auto remeshed_quality = geodual::quality::triangle_quality(remeshed.dual.mesh);
  check(remeshed.dual.mesh.num_vertices() == static_cast<geodual::Index>(remeshed.dual.sites.size()) &&
            remeshed_quality.euler_characteristic == 2 && remeshed_quality.boundary_loops == 0 &&
            remeshed_quality.nonmanifold_edges == 0 && remeshed_quality.components == 1,
        "remesh: remesh_from_sites of a sphere is a closed genus-0 surface (" +
            std::to_string(remeshed.dual.mesh.num_vertices()) + " vertices, " +
            std::to_string(remeshed.dual.mesh.num_faces()) + " faces)");
}

}  // namespace

int main() {
  try {
    run_checks();
  } catch (const std::exception& error) {
    std::cout << "FAIL exception: " << error.what() << '\n';
    return 1;
  }
  if (failures != 0) {
    std::cout << failures << " checks failed\n";
    return 1;
  }
  std::cout << "geodual consumer: all checks passed\n";
  return 0;
}
