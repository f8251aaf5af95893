#pragma once
// A set of points that grows while it is queried, hashed into cubic cells,
// for "is a point held within r of x" with r no larger than a cell: only the
// 27 cells round x's are looked at. (For neighbours within a set known in
// advance, remesh/src/common/point_grid.hpp sorts it into a grid once.)

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace geodual {

/// Points, each with an `Item`, in cells `cell` wide (> 0).
template <class Item>
class PointHash {
 public:
  explicit PointHash(double cell) : cell_(cell) {}

  void insert(const Eigen::Vector3d& x, Item item) { cells_[cell_of(x)].emplace_back(x, std::move(item)); }

  /// Whether a point within `radius` (at most the cell size) of x holds an
  /// item for which accept(item) is true.
  template <class Accept>
  bool any_within(const Eigen::Vector3d& x, double radius, Accept accept) const {
    const std::array<std::int64_t, 3> cell = cell_of(x);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
          if (it == cells_.end()) continue;
          for (const auto& [y, item] : it->second) {
            if ((x - y).norm() <= radius && accept(item)) return true;
          }
        }
      }
    }
    return false;
  }

 private:
  std::array<std::int64_t, 3> cell_of(const Eigen::Vector3d& x) const {
    return {static_cast<std::int64_t>(std::floor(x.x() / cell_)), static_cast<std::int64_t>(std::floor(x.y() / cell_)),
            static_cast<std::int64_t>(std::floor(x.z() / cell_))};
  }

  double cell_;
  std::map<std::array<std::int64_t, 3>, std::vector<std::pair<Eigen::Vector3d, Item>>> cells_;
};

}  // namespace geodual
