#include "geodual/mesh/sharp_edges.hpp"

#include "geodual/mesh/face_area.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace geodual {

bool face_runs_edge(const TriangleMesh& mesh, Index f, Index a, Index b) {
  for (int k = 0; k < 3; ++k) {
    if (mesh.faces(f, k) == a && mesh.faces(f, (k + 1) % 3) == b) return true;
  }
  return false;
}

double normal_turn_degrees(const TriangleMesh& mesh, const MeshTopology& topology, Index e) {
  const auto faces = topology.edge_faces(e);
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (faces.size() != 2 || !has_positive_area(mesh, faces[0]) || !has_positive_area(mesh, faces[1])) return nan;
  Eigen::Vector3d normal[2];
  for (int i = 0; i < 2; ++i) {
    normal[i] = face_unit_normal(mesh, faces[i]);
    if (normal[i].isZero(0)) return nan;
  }
  const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(e)];
  if (face_runs_edge(mesh, faces[0], a, b) == face_runs_edge(mesh, faces[1], a, b)) normal[1] = -normal[1];
  // atan2 of sine and cosine: accurate near 0 and 180 degrees alike.
  const double angle = std::atan2(normal[0].cross(normal[1]).norm(), normal[0].dot(normal[1]));
  return angle * 180 / std::numbers::pi;
}

std::vector<Index> sharp_edges(const TriangleMesh& mesh, const MeshTopology& topology, double angle_degrees) {
  // Most edges turn far less than the angle: the dot product of their faces'
  // unit normals, above the angle's cosine by more than any round-off, rules
  // them out; normal_turn_degrees decides the others.
  std::vector<Eigen::Vector3d> normal(static_cast<std::size_t>(mesh.num_faces()));
  for (Index f = 0; f < mesh.num_faces(); ++f) normal[static_cast<std::size_t>(f)] = face_unit_normal(mesh, f);
  const double clearly_smooth = std::cos(angle_degrees * std::numbers::pi / 180) + 1e-9;
  std::vector<Index> sharp;
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto faces = topology.edge_faces(e);
    if (faces.size() != 2) continue;  // no turn (normal_turn_degrees is NaN)
    const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(e)];
    const bool opposite = face_runs_edge(mesh, faces[0], a, b) != face_runs_edge(mesh, faces[1], a, b);
    const double cosine = (opposite ? 1.0 : -1.0) *
                          normal[static_cast<std::size_t>(faces[0])].dot(normal[static_cast<std::size_t>(faces[1])]);
    if (cosine > clearly_smooth) continue;
    if (normal_turn_degrees(mesh, topology, e) >= angle_degrees) sharp.push_back(e);
  }
  return sharp;
}

}  // namespace geodual
