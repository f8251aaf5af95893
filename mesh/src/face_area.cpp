#include "geodual/mesh/face_area.hpp"

#include <Eigen/Geometry>

namespace geodual {

bool has_positive_area(const TriangleMesh& mesh, Index f) {
  if (has_repeated_corner(mesh, f)) return false;
  std::array<double, 3> length{};
  for (int k = 0; k < 3; ++k) {
    length[k] = (mesh.vertices.row(mesh.faces(f, (k + 1) % 3)) - mesh.vertices.row(mesh.faces(f, k))).norm();
  }
  return has_area_from_lengths(length);
}

double face_area(const TriangleMesh& mesh, Index f) {
  const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0));
  const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1));
  const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2));
  const double area = 0.5 * (b - a).cross(c - a).norm();
  return std::isfinite(area) ? area : 0.0;
}

Eigen::Vector3d face_unit_normal(const TriangleMesh& mesh, Index f) {
  const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0));
  const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1));
  const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2));
  const Eigen::Vector3d normal = (b - a).cross(c - a);
  const double length = normal.norm();
  return std::isfinite(length) && length > 0 ? Eigen::Vector3d(normal / length) : Eigen::Vector3d::Zero();
}

}  // namespace geodual
