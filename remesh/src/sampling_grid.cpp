#include "sampling_grid.hpp"

#include <algorithm>
#include <array>
#include <bit>

namespace geodual::remesh::detail {

PointGrid::PointGrid(std::span<const Eigen::Vector3d> points, double cell_size) {
  if (points.empty()) return;
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  origin_ = lo;
  // Keep cell coordinates far from int64 overflow whatever the caller asks.
  const double extent = (hi - lo).maxCoeff();
  cell_size = std::max(cell_size, extent * 0x1p-40);
  if (!(cell_size > 0)) cell_size = 1;
  inverse_cell_size_ = 1 / cell_size;

  struct Keyed {
    std::array<std::int64_t, 3> cell;
    Index point;
  };
  std::vector<Keyed> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    keyed[i] = {{coordinate(points[i][0], 0), coordinate(points[i][1], 1), coordinate(points[i][2], 2)},
                static_cast<Index>(i)};
  }
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
    return a.cell != b.cell ? a.cell < b.cell : a.point < b.point;
  });
  slot_point_.resize(points.size());
  slot_position_.resize(points.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    slot_point_[i] = keyed[i].point;
    slot_position_[i] = points[keyed[i].point];
    if (i == 0 || keyed[i].cell != keyed[i - 1].cell) {
      cells_.push_back({keyed[i].cell[0], keyed[i].cell[1], keyed[i].cell[2], static_cast<Index>(i), 0});
    }
    cells_.back().end = static_cast<Index>(i + 1);
  }
  const std::uint64_t table_size = std::bit_ceil(static_cast<std::uint64_t>(cells_.size()) * 2);
  mask_ = table_size - 1;
  table_.assign(table_size, -1);
  for (Index c = 0; c < static_cast<Index>(cells_.size()); ++c) {
    std::uint64_t slot = hash(cells_[c].x, cells_[c].y, cells_[c].z) & mask_;
    while (table_[slot] >= 0) slot = (slot + 1) & mask_;
    table_[slot] = c;
  }
}

std::uint64_t PointGrid::hash(std::int64_t x, std::int64_t y, std::int64_t z) {
  std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9e3779b97f4a7c15ULL;
  h ^= static_cast<std::uint64_t>(y) * 0xc2b2ae3d27d4eb4fULL;
  h ^= static_cast<std::uint64_t>(z) * 0x165667b19e3779f9ULL;
  h ^= h >> 29;
  h *= 0xbf58476d1ce4e5b9ULL;
  return h ^ (h >> 32);
}

Index PointGrid::find_cell(std::int64_t x, std::int64_t y, std::int64_t z) const {
  if (table_.empty()) return -1;
  for (std::uint64_t slot = hash(x, y, z) & mask_;; slot = (slot + 1) & mask_) {
    const Index c = table_[slot];
    if (c < 0) return -1;
    if (cells_[c].x == x && cells_[c].y == y && cells_[c].z == z) return c;
  }
}

}  // namespace geodual::remesh::detail
