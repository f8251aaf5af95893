// The exact geodesic Voronoi diagram of sites sampled on a mesh, cell by cell.
//
//   voronoi_cells MESH [SITES] [SEED]     e.g. voronoi_cells scan.ply 40
//
// Prints each cell's site, area and neighbours, then checks that the cells
// tile the surface: their areas add up to the area of the mesh's triangles
// (computed here independently, from cross products).

#include <geodual/io/read_mesh.hpp>
#include <geodual/remesh/sample_sites.hpp>
#include <geodual/voronoi/voronoi_diagram.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

double surface_area(const geodual::TriangleMesh& mesh) {
  double area = 0;
  for (geodual::Index f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 4) {
    std::fprintf(stderr, "usage: voronoi_cells MESH [SITES] [SEED]\n");
    return 2;
  }
  try {
    const geodual::TriangleMesh mesh = geodual::io::read_mesh(argv[1]).mesh;

    // Sites: points on the surface (face + barycentric), some on the boundary loops.
    geodual::remesh::SamplingOptions sampling;
    if (argc == 4) sampling.seed = std::stoull(argv[3]);
    const std::int64_t count = argc >= 3 ? std::stoll(argv[2]) : 40;
    const std::vector<geodual::SurfacePoint> sites = geodual::remesh::sample_sites(mesh, count, sampling);

    const geodual::voronoi::VoronoiDiagram diagram = geodual::voronoi::compute_voronoi(mesh, sites);

    // Neighbours from the adjacency list (pairs site_a < site_b).
    std::vector<int> neighbours(sites.size(), 0);
    for (const geodual::voronoi::CellAdjacency& pair : diagram.adjacency) {
      ++neighbours[static_cast<std::size_t>(pair.site_a)];
      ++neighbours[static_cast<std::size_t>(pair.site_b)];
    }
    std::printf("%6s  %-34s  %13s  %10s\n", "cell", "site (x, y, z)", "area", "neighbours");
    double total = 0;
    for (std::size_t i = 0; i < sites.size(); ++i) {
      const Eigen::Vector3d p = sites[i].position(mesh);
      std::printf("%6zu  (%10.6f, %10.6f, %10.6f)  %13.6e  %10d\n", i, p.x(), p.y(), p.z(), diagram.cell_area[i],
                  neighbours[i]);
      total += diagram.cell_area[i];
    }

    const double area = surface_area(mesh);
    const double difference = std::abs(total - area) / area;
    std::printf("total cell area %.9e, mesh area %.9e, relative difference %.1e\n", total, area, difference);
    std::printf("%zu Voronoi vertices, %zu arcs, %.3f s\n", diagram.vertices.size(), diagram.arcs.size(),
                diagram.stats.geodesic_seconds + diagram.stats.extraction_seconds);
    if (difference > 1e-9) {
      std::printf("the cells do NOT tile the surface\n");
      return 1;
    }
    std::printf("the cells tile the surface\n");
  } catch (const std::exception& error) {  // geodual::Error: bad file, bad site count, ...
    std::fprintf(stderr, "voronoi_cells: %s\n", error.what());
    return 1;
  }
  return 0;
}
