#include "geodual/mesh/triangle_shape.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace geodual {

TriangleShape triangle_shape(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
  const Eigen::Vector3d e01 = p1 - p0;
  const Eigen::Vector3d e12 = p2 - p1;
  const Eigen::Vector3d e20 = p0 - p2;
  const double twice_area = e01.cross(-e20).norm();
  const double l01 = e01.norm();
  const double l12 = e12.norm();
  const double l20 = e20.norm();
  const double half_perimeter = 0.5 * (l01 + l12 + l20);
  const double longest = std::max({l01, l12, l20});
  TriangleShape shape;
  shape.area = 0.5 * twice_area;
  shape.q = 6.0 / std::sqrt(3.0) * shape.area / (half_perimeter * longest);
  // The angle between edge vectors u, v is atan2(|u x v|, u . v), where
  // |u x v| is twice the area at every corner.
  shape.angles[0] = std::atan2(twice_area, e01.dot(-e20));
  shape.angles[1] = std::atan2(twice_area, e12.dot(-e01));
  shape.angles[2] = std::atan2(twice_area, e20.dot(-e12));
  return shape;
}

}  // namespace geodual
