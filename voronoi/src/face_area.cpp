#include "geodual/voronoi/face_area.hpp"

#include "propagation_mesh.hpp"

#include <array>

namespace geodual::voronoi {

bool has_geodesic_area(const TriangleMesh& mesh, Index face) {
  std::array<double, 3> length{};
  for (int k = 0; k < 3; ++k) {
    const Index a = mesh.faces(face, k), b = mesh.faces(face, (k + 1) % 3);
    length[k] = detail::edge_length(mesh, a, b);
  }
  return detail::has_area_from_lengths(length);
}

}  // namespace geodual::voronoi
