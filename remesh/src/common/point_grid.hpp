#pragma once
// Fixed-radius neighbours within a fixed point set: a uniform grid whose cell
// is the radius, so that the points near a point lie in the 3 x 3 x 3 cells
// around its own. Used by Poisson sample elimination and by the candidate
// graph of farthest point sampling, where every query is about a point of the
// set itself; and, with queries of any radius, by the restricted Voronoi
// diagram for the sites near a site.

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace geodual::remesh::detail {

/// The grid keeps its own copy of the points, sorted by cell along a Z-order
/// curve ("slots"): the cells around a point, and the points in them, lie
/// close together in memory. Callers that index their own arrays by slot get
/// the same locality.
class PointGrid {
 public:
  /// radius > 0: the distance below which points are neighbours.
  PointGrid(std::span<const Eigen::Vector3d> points, double radius);

  Index size() const { return static_cast<Index>(slot_point_.size()); }
  /// The index in the constructor's `points` of the point in `slot`.
  Index original(Index slot) const { return slot_point_[slot]; }
  const Eigen::Vector3d& position(Index slot) const { return slot_position_[slot]; }

  /// Calls visit(other_slot, squared_distance) for every point closer than
  /// the radius to the point in `slot` (itself included), cell by cell in
  /// increasing order, each cell's slots in increasing order.
  template <typename Visit>
  void for_each_near(Index slot, Visit&& visit) const {
    const Eigen::Vector3d& p = slot_position_[slot];
    const Index cell = slot_cell_[slot];
    for (Index i = neighbour_begin_[cell]; i < neighbour_begin_[cell + 1]; ++i) {
      const Index other_cell = neighbours_[i];
      for (Index other = cell_begin_[other_cell]; other < cell_begin_[other_cell + 1]; ++other) {
        const double d2 = (slot_position_[other] - p).squaredNorm();
        if (d2 < radius2_) visit(other, d2);
      }
    }
  }

  /// Calls visit(other_slot, squared_distance) for every point in the 3 x 3 x
  /// 3 cells around the point in `slot` (itself included), whatever its
  /// distance: the cells for_each_within(position(slot), r) looks at for any
  /// r up to the radius, without their look-up.
  template <typename Visit>
  void for_each_around(Index slot, Visit&& visit) const {
    const Eigen::Vector3d& p = slot_position_[slot];
    const Index cell = slot_cell_[slot];
    for (Index i = neighbour_begin_[cell]; i < neighbour_begin_[cell + 1]; ++i) {
      const Index other_cell = neighbours_[i];
      for (Index other = cell_begin_[other_cell]; other < cell_begin_[other_cell + 1]; ++other) {
        visit(other, (slot_position_[other] - p).squaredNorm());
      }
    }
  }

  /// Calls visit(slot, squared_distance) for every point within `radius` of
  /// `p` (any radius; the cells it spans are looked up), cell by cell.
  template <typename Visit>
  void for_each_within(const Eigen::Vector3d& p, double radius, Visit&& visit) const {
    if (cell_begin_.size() < 2) return;
    const auto reach = static_cast<std::int64_t>(std::ceil(radius / cell_size_));
    CellCoordinates at;
    for (int a = 0; a < 3; ++a) at[a] = static_cast<std::int64_t>(std::floor((p[a] - origin_[a]) * inverse_cell_));
    for (std::int64_t dx = -reach; dx <= reach; ++dx) {
      for (std::int64_t dy = -reach; dy <= reach; ++dy) {
        for (std::int64_t dz = -reach; dz <= reach; ++dz) {
          const Index cell = find_cell({at[0] + dx, at[1] + dy, at[2] + dz});
          if (cell < 0) continue;
          for (Index other = cell_begin_[cell]; other < cell_begin_[cell + 1]; ++other) {
            const double d2 = (slot_position_[other] - p).squaredNorm();
            if (d2 <= radius * radius) visit(other, d2);
          }
        }
      }
    }
  }

 private:
  using CellCoordinates = std::array<std::int64_t, 3>;
  /// The occupied cell at these coordinates, or -1.
  Index find_cell(const CellCoordinates& cell) const;

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double cell_size_ = 1;
  double inverse_cell_ = 1;
  std::vector<CellCoordinates> cells_;  ///< coordinates of each occupied cell
  std::vector<Index> table_;            ///< open-addressing table of the occupied cells
  double radius2_ = 0;
  std::vector<Index> slot_point_;
  std::vector<Eigen::Vector3d> slot_position_;
  std::vector<Index> slot_cell_;
  std::vector<Index> cell_begin_;  ///< slots of each cell (CSR)
  /// Occupied cells among the 27 around each cell, itself included (CSR).
  std::vector<Index> neighbour_begin_;
  std::vector<Index> neighbours_;
};

}  // namespace geodual::remesh::detail
