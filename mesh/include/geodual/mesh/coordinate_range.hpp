#pragma once
// The coordinates geodual can compute with in double precision: products of
// four lengths (Heron's formula, squared areas) stay finite and normal for
// lengths within about 1e-77 to 1e77; and the box the coordinates span.

#include "geodual/mesh/triangle_mesh.hpp"

#include <string_view>

namespace geodual {

/// The bounding box of the vertices the faces use (low = +inf, high = -inf
/// with no faces).
struct BoundingBox {
  Eigen::Vector3d low;
  Eigen::Vector3d high;
  double diagonal() const { return (high - low).norm(); }
};

BoundingBox referenced_bounding_box(const TriangleMesh& mesh);

inline constexpr double max_coordinate_magnitude = 1e70;
inline constexpr double min_extent = 1e-70;

/// \throw geodual::Error, starting with `name` (e.g. the file), unless every
/// vertex a face uses has coordinates within +-max_coordinate_magnitude and
/// those vertices' bounding box, unless a single point, has a side of at
/// least min_extent.
void require_computable_range(const TriangleMesh& mesh, std::string_view name);

}  // namespace geodual
