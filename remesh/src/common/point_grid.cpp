#include "common/point_grid.hpp"

#include "geodual/mesh/detail/morton_code.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace geodual::remesh::detail {
namespace {

std::uint64_t hash_cell(const std::array<std::int64_t, 3>& c) {
  std::uint64_t h = static_cast<std::uint64_t>(c[0]) * 0x9e3779b97f4a7c15ULL;
  h ^= static_cast<std::uint64_t>(c[1]) * 0xc2b2ae3d27d4eb4fULL;
  h ^= static_cast<std::uint64_t>(c[2]) * 0x165667b19e3779f9ULL;
  h ^= h >> 29;
  h *= 0xbf58476d1ce4e5b9ULL;
  return h ^ (h >> 32);
}

}  // namespace

PointGrid::PointGrid(std::span<const Eigen::Vector3d> points, double radius) {
  radius2_ = radius * radius;
  const std::size_t n = points.size();
  if (n == 0) {
    neighbour_begin_.assign(1, 0);
    cell_begin_.assign(1, 0);
    return;
  }
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // Cells at least as large as the radius (so 3 x 3 x 3 cells cover it), and
  // large enough to keep coordinates far from int64 overflow.
  const double extent = (hi - lo).maxCoeff();
  double cell_size = std::max(radius, extent * 0x1p-40);
  if (!(cell_size > 0)) cell_size = 1;
  const double inverse = 1 / cell_size;
  origin_ = lo;
  cell_size_ = cell_size;
  inverse_cell_ = inverse;

  struct Keyed {
    CellCoordinates cell;
    std::uint64_t morton;
    Index point;
  };
  std::vector<Keyed> keyed(n);
  std::int64_t largest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    Keyed& k = keyed[i];
    for (int a = 0; a < 3; ++a) {
      k.cell[a] = static_cast<std::int64_t>(std::floor((points[i][a] - lo[a]) * inverse));
      largest = std::max(largest, k.cell[a]);
    }
    k.point = static_cast<Index>(i);
  }
  // Z-order when the coordinates fit in 21 bits (always, unless a component
  // is millions of spacings long); row order otherwise.
  const bool z_order = largest < (std::int64_t{1} << 21);
  for (Keyed& k : keyed) {
    k.morton = z_order ? morton_code(static_cast<std::uint64_t>(k.cell[0]), static_cast<std::uint64_t>(k.cell[1]),
                                     static_cast<std::uint64_t>(k.cell[2]))
                       : 0;
  }
  // A total order (ties by point), so the parallel sort's result is unique.
  tbb::parallel_sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
    if (a.morton != b.morton) return a.morton < b.morton;
    if (a.cell != b.cell) return a.cell < b.cell;
    return a.point < b.point;
  });

  slot_point_.resize(n);
  slot_position_.resize(n);
  slot_cell_.resize(n);
  std::vector<CellCoordinates>& cells = cells_;
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0 || keyed[i].cell != keyed[i - 1].cell) {
      cells.push_back(keyed[i].cell);
      cell_begin_.push_back(static_cast<Index>(i));
    }
    slot_point_[i] = keyed[i].point;
    slot_position_[i] = points[keyed[i].point];
    slot_cell_[i] = static_cast<Index>(cells.size()) - 1;
  }
  cell_begin_.push_back(static_cast<Index>(n));
  keyed.clear();
  keyed.shrink_to_fit();

  // Occupied cells in a hash table: each cell's occupied neighbours are
  // found through it once here, other cells by for_each_within.
  const std::uint64_t table_size = std::bit_ceil(static_cast<std::uint64_t>(cells.size()) * 2);
  const std::uint64_t mask = table_size - 1;
  table_.assign(table_size, -1);
  for (Index c = 0; c < static_cast<Index>(cells.size()); ++c) {
    std::uint64_t slot = hash_cell(cells[c]) & mask;
    while (table_[slot] >= 0) slot = (slot + 1) & mask;
    table_[slot] = c;
  }
  // Each cell's occupied neighbours (itself included), sorted: up to 27 per
  // cell in a scratch row on all threads, then packed.
  const auto cell_count = static_cast<Index>(cells.size());
  std::vector<Index> rows(27 * cells.size());
  neighbour_begin_.assign(cells.size() + 1, 0);
  tbb::parallel_for(tbb::blocked_range<Index>(0, cell_count, 1024), [&](const tbb::blocked_range<Index>& range) {
    for (Index c = range.begin(); c != range.end(); ++c) {
      const CellCoordinates& cell = cells[c];
      Index* row = rows.data() + 27 * static_cast<std::size_t>(c);
      Index found = 0;
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          for (std::int64_t dz = -1; dz <= 1; ++dz) {
            const Index other = find_cell({cell[0] + dx, cell[1] + dy, cell[2] + dz});
            if (other >= 0) row[found++] = other;
          }
        }
      }
      std::sort(row, row + found);
      neighbour_begin_[c + 1] = found;
    }
  });
  for (Index c = 0; c < cell_count; ++c) neighbour_begin_[c + 1] += neighbour_begin_[c];
  neighbours_.resize(static_cast<std::size_t>(neighbour_begin_[cell_count]));
  tbb::parallel_for(tbb::blocked_range<Index>(0, cell_count, 1024), [&](const tbb::blocked_range<Index>& range) {
    for (Index c = range.begin(); c != range.end(); ++c) {
      std::copy_n(rows.data() + 27 * static_cast<std::size_t>(c), neighbour_begin_[c + 1] - neighbour_begin_[c],
                  neighbours_.data() + neighbour_begin_[c]);
    }
  });
}

Index PointGrid::find_cell(const CellCoordinates& cell) const {
  const std::uint64_t mask = table_.size() - 1;
  for (std::uint64_t slot = hash_cell(cell) & mask;; slot = (slot + 1) & mask) {
    const Index c = table_[slot];
    if (c < 0 || cells_[c] == cell) return c;
  }
}

}  // namespace geodual::remesh::detail
