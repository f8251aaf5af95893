#include "post/vertex_search.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_topology.hpp"

namespace geodual::remesh::detail {

double smallest_angle(const TriangleMesh& mesh, Index f) {
  return triangle_shape(mesh.vertices.row(mesh.faces(f, 0)), mesh.vertices.row(mesh.faces(f, 1)),
                        mesh.vertices.row(mesh.faces(f, 2)))
      .min_angle();
}

double smallest_angle(const TriangleMesh& mesh) {
  double smallest = std::numbers::pi;
  for (Index f = 0; f < mesh.num_faces(); ++f) smallest = std::min(smallest, smallest_angle(mesh, f));
  return smallest;
}

std::vector<std::uint8_t> movable_vertices(const TriangleMesh& remesh, const voronoi::SurfaceTopology& topology,
                                           const std::vector<SurfacePoint>& points,
                                           std::span<const std::uint8_t> fixed) {
  const std::vector<std::uint8_t> on_remesh_boundary = build_mesh_topology(remesh).vertex_on_boundary;
  std::vector<std::uint8_t> movable(points.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint& point = points[i];
    const bool at_vertex = point.kind == SurfacePoint::Kind::vertex ||
                           (point.barycentric.array() == 0).count() >= 2;  // a face point at one of its corners
    movable[i] = !(i < fixed.size() && fixed[i]) && !on_remesh_boundary[i] && !at_vertex &&
                 !on_surface_boundary(topology, point);
  }
  return movable;
}

void check_points(const TriangleMesh& remesh, const std::vector<SurfacePoint>& points, const std::string& what) {
  if (points.size() != static_cast<std::size_t>(remesh.num_vertices())) {
    throw UsageError(what + ": " + std::to_string(points.size()) + " points for a remesh of " +
                     std::to_string(remesh.num_vertices()) + " vertices");
  }
}

}  // namespace geodual::remesh::detail
