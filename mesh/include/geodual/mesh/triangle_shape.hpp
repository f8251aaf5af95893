#pragma once
// The shape of one triangle: its quality Q = 6/sqrt(3) A / (p h) (A its area,
// p its half-perimeter, h its longest side; 1 for the equilateral triangle,
// 0 for a degenerate one) and its angles. Shared by the quality statistics
// and the smoothing of a remesh's worst triangles, so that both judge a
// triangle alike.

#include <Eigen/Core>

#include <algorithm>
#include <array>

namespace geodual {

struct TriangleShape {
  double q = 0;
  std::array<double, 3> angles{};  ///< radians, at corners 0, 1, 2
  double area = 0;
  double min_angle() const { return std::min({angles[0], angles[1], angles[2]}); }
};

/// The shape of the triangle (p0, p1, p2); for a degenerate one Q is 0 or
/// not a number (no side, or a zero-length longest side).
TriangleShape triangle_shape(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2);

}  // namespace geodual
