#pragma once
// A face's area and normal, and the one test of whether a face has any: shared by the
// mesh report, the quality statistics, the manifold cut, the site sampling and
// the geodesic engine, so that they agree on which faces are degenerate.

#include "geodual/mesh/triangle_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace geodual {

/// Whether two of face f's corner indices are the same vertex.
inline bool has_repeated_corner(const TriangleMesh& mesh, Index f) {
  const Index a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
  return a == b || b == c || c == a;
}

/// Twice the area of a triangle with side lengths a, b, c, by Kahan's
/// cancellation-free form of Heron's formula (0 for impossible lengths).
inline double twice_area_from_lengths(double a, double b, double c) {
  if (a < b) std::swap(a, b);
  if (b < c) std::swap(b, c);
  if (a < b) std::swap(a, b);
  const double product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return product > 0 ? 0.5 * std::sqrt(product) : 0.0;
}

/// Whether a triangle with these side lengths has positive area and a
/// positive height over its longest side (false for NaN lengths).
inline bool has_area_from_lengths(const std::array<double, 3>& length) {
  const double twice_area = twice_area_from_lengths(length[0], length[1], length[2]);
  const double longest = std::max({length[0], length[1], length[2]});
  return twice_area > 0 && twice_area / longest > 0;
}

/// Whether face f has an area: three distinct corners, finite coordinates and
/// a positive area from its edge lengths (has_area_from_lengths), which is how
/// the geodesic engine lays faces out. A needle whose height is below the
/// rounding of its lengths has none, even where the cross product of two of
/// its edges is not zero.
bool has_positive_area(const TriangleMesh& mesh, Index f);

/// Face f's area, half the norm of the cross product of two edges; 0 where
/// that is not finite. Corner indices are assumed in range.
double face_area(const TriangleMesh& mesh, Index f);

/// Face f's unit normal (right-handed in its corner order); zero where the
/// cross product of two edges has no finite, positive length.
Eigen::Vector3d face_unit_normal(const TriangleMesh& mesh, Index f);

}  // namespace geodual
