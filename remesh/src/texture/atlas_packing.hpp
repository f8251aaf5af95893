#pragma once
// Packing the atlas's charts into a square texture: each chart turned to its
// smallest bounding rectangle, all scaled alike, placed by a skyline packer
// with a gutter of free texels round each one and along the border.

#include <Eigen/Core>

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
/// lengths compare) in a texture of texture_size texels a side: each chart's
/// bounding rectangle rounded out to whole texels with `gutter` free texels
/// round it (so 2 gutter between charts, gutter to the border), at as large
/// a common scale as the packer finds room for (a search on the scale).
/// Deterministic. \throw geodual::Error when the charts, however small, do
/// not fit (too many for the texture and gutter).
std::vector<ChartPlacement> pack_charts(const std::vector<std::vector<Eigen::Vector2d>>& charts, int texture_size,
                                        int gutter);

}  // namespace geodual::remesh::detail
