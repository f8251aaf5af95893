#include "gltf_vertex_normals.hpp"

#include <Eigen/Geometry>

namespace geodual::io::detail::gltf {

std::vector<float> area_weighted_vertex_normals(const VertexMatrix& vertices, const FaceMatrix& faces) {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> sums =
      Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>::Zero(vertices.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0));
    const Eigen::Vector3d b = vertices.row(faces(f, 1));
    const Eigen::Vector3d c = vertices.row(faces(f, 2));
    const Eigen::RowVector3d twice_area_normal = (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k) sums.row(faces(f, k)) += twice_area_normal;
  }

  std::vector<float> normals(static_cast<std::size_t>(3 * vertices.rows()));
  for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
    Eigen::Vector3d n = sums.row(v).transpose();
    // Scale before normalizing so that tiny sums do not underflow in the norm.
    const double largest = n.cwiseAbs().maxCoeff();
    n = largest > 0.0 ? Eigen::Vector3d((n / largest).normalized()) : Eigen::Vector3d::UnitZ();
    for (int k = 0; k < 3; ++k) normals[static_cast<std::size_t>(3 * v + k)] = static_cast<float>(n[k]);
  }
  return normals;
}

}  // namespace geodual::io::detail::gltf
