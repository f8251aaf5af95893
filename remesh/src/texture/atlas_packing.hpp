#pragma once
// Packing the atlas's charts into a square texture: each chart rasterised
// (every texel its triangles touch, grown by the gutter) at several turns,
// all charts scaled alike, placed largest first where their texels fit
// among the texels of the charts placed before.

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace geodual::remesh::detail {

/// Where a chart goes: a chart point p lands at texel coordinates
/// transform * p + offset (x right, y down, the texture spanning [0, size]^2).
/// A rotation times a scale: orientation is kept.
struct ChartPlacement {
  Eigen::Matrix2d transform = Eigen::Matrix2d::Identity();
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
};

/// Places charts (each a set of points, all at one density, so that their
/// lengths compare, and its triangles on them) in a texture of texture_size
/// texels a side, at as large a common scale as the packer finds room for
/// (a search on the scale): every texel a chart's triangle touches (closed
/// texel squares) is at least `gutter` texels from the border and more than
/// 2 gutter texels (in x or in y) from every texel another chart touches.
/// A chart without triangles stands for its convex hull. Deterministic.
/// \throw geodual::Error when the charts, however small, do not fit (too
/// many for the texture and gutter).
std::vector<ChartPlacement> pack_charts(const std::vector<std::vector<Eigen::Vector2d>>& charts,
                                        const std::vector<std::vector<std::array<Index, 3>>>& triangles,
                                        int texture_size, int gutter);

/// As above, each chart standing for its convex hull.
std::vector<ChartPlacement> pack_charts(const std::vector<std::vector<Eigen::Vector2d>>& charts, int texture_size,
                                        int gutter);

}  // namespace geodual::remesh::detail
