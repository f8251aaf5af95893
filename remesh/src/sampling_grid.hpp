#pragma once
// A uniform grid over a fixed point set, hashed so that only occupied cells
// cost memory: fixed-radius neighbour queries for Poisson sample elimination
// and for the candidate graph of farthest point sampling.

#include "geodual/triangle_mesh.hpp"

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace geodual::remesh::detail {

/// The grid keeps its own copy of the points sorted by cell ("slots"), so
/// that a query reads memory in order; callers that index their own arrays
/// by slot get the same locality.
class PointGrid {
 public:
  /// cell_size > 0; queries are fastest with a radius of about one cell.
  PointGrid(std::span<const Eigen::Vector3d> points, double cell_size);

  Index size() const { return static_cast<Index>(slot_point_.size()); }
  /// The index in the constructor's `points` of the point in `slot`.
  Index original(Index slot) const { return slot_point_[slot]; }
  const Eigen::Vector3d& position(Index slot) const { return slot_position_[slot]; }

  /// Calls visit(slot, squared_distance) for every point at distance
  /// < radius from p (p itself included if it is one of the points), cell by
  /// cell, each cell's slots in increasing order.
  template <typename Visit>
  void for_each_within(const Eigen::Vector3d& p, double radius, Visit&& visit) const {
    const double radius2 = radius * radius;
    std::int64_t lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = coordinate(p[k] - radius, k);
      hi[k] = coordinate(p[k] + radius, k);
    }
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
          const Index cell = find_cell(x, y, z);
          if (cell < 0) continue;
          for (Index slot = cells_[cell].begin; slot < cells_[cell].end; ++slot) {
            const double d2 = (slot_position_[slot] - p).squaredNorm();
            if (d2 < radius2) visit(slot, d2);
          }
        }
      }
    }
  }

 private:
  struct Cell {
    std::int64_t x, y, z;
    Index begin, end;
  };

  std::int64_t coordinate(double value, int axis) const {
    return static_cast<std::int64_t>(std::floor((value - origin_[axis]) * inverse_cell_size_));
  }
  static std::uint64_t hash(std::int64_t x, std::int64_t y, std::int64_t z);
  Index find_cell(std::int64_t x, std::int64_t y, std::int64_t z) const;

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double inverse_cell_size_ = 1;
  std::vector<Index> slot_point_;  ///< point indices sorted by cell
  std::vector<Eigen::Vector3d> slot_position_;
  std::vector<Cell> cells_;
  std::vector<Index> table_;  ///< open addressing: cell index or -1
  std::uint64_t mask_ = 0;
};

}  // namespace geodual::remesh::detail
