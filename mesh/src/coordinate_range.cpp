#include "geodual/mesh/coordinate_range.hpp"

#include "geodual/mesh/error.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <limits>
#include <sstream>
#include <string>

namespace geodual {

BoundingBox referenced_bounding_box(const TriangleMesh& mesh) {
  BoundingBox box{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
                  Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (Eigen::Index i = 0; i < mesh.faces.size(); ++i) {
    const Eigen::Vector3d p = mesh.vertices.row(mesh.faces.data()[i]).transpose();
    box.low = box.low.cwiseMin(p);
    box.high = box.high.cwiseMax(p);
  }
  return box;
}

void require_computable_range(const TriangleMesh& mesh, std::string_view name) {
  if (mesh.faces.rows() == 0) return;
  const auto [low, high] = referenced_bounding_box(mesh);
  std::ostringstream message;
  message << name << ": ";
  const double largest = std::max(low.cwiseAbs().maxCoeff(), high.cwiseAbs().maxCoeff());
  if (!(largest <= max_coordinate_magnitude)) {
    message << "a coordinate of magnitude " << largest << " is beyond the " << max_coordinate_magnitude
            << " geodual computes with; scale the mesh down";
    throw Error(message.str());
  }
  const double extent = (high - low).maxCoeff();  // not the diagonal: its square would underflow
  if (extent > 0 && extent < min_extent) {
    message << "the mesh spans only " << extent << " (largest side of its bounding box), below the " << min_extent
            << " geodual computes with; scale the mesh up";
    throw Error(message.str());
  }
}

}  // namespace geodual
