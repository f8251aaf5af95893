#include "plane_nearest_site.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace geodual::voronoi::detail {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
/// Beyond this scale the bounds' arithmetic could overflow: every cone is
/// evaluated instead.
constexpr double largest_scale = 0x1p900;
/// About this many cones per cell, and at most this many cells a side.
constexpr double cones_per_cell = 2;
constexpr int most_cells_per_side = 128;

}  // namespace

void PlaneNearestSite::build(const ConeEnvelope& envelope, std::span<const Eigen::Vector2d> region) {
  entries_.clear();
  others_.clear();
  columns_ = rows_ = 0;
  scale_ = 0;
  for (int slot = 0; slot < envelope.slot_count(); ++slot) {
    for (const DistanceCone& cone : envelope.cones(slot)) {
      scale_ = std::max(scale_, std::abs(cone.sigma) + std::abs(cone.apex.x()) + std::abs(cone.apex.y()));
    }
  }
  // The grid: the region's bounding box and as far again on every side.
  Eigen::Vector2d low = Eigen::Vector2d::Constant(infinity), high = -low;
  for (const Eigen::Vector2d& p : region) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const Eigen::Vector2d extent = high - low;
  const double width = 3 * extent.x(), height = 3 * extent.y();
  if (scale_ <= largest_scale && width > 0 && height > 0 && std::isfinite(width * height)) {  // false for NaN
    origin_ = low - extent;
    const double cells = std::max(1.0, static_cast<double>(envelope.cone_count()) / cones_per_cell);
    cell_size_ = std::sqrt(width * height / cells);
    cell_size_ = std::max({cell_size_, width / most_cells_per_side, height / most_cells_per_side});
    columns_ = std::clamp(static_cast<int>(std::ceil(width / cell_size_)), 1, most_cells_per_side);
    rows_ = std::clamp(static_cast<int>(std::ceil(height / cell_size_)), 1, most_cells_per_side);
    // The cells' corners are rounded on that scale too.
    scale_ = std::max(scale_, std::abs(origin_.x()) + std::abs(origin_.y()) + width + height);
  }
  // The cones counted per cell, then placed cell by cell; those off the grid
  // go to others_.
  const auto num_cells = static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_);
  cell_begin_.assign(num_cells + 1, 0);
  cell_least_sigma_.assign(num_cells, infinity);
  least_sigma_ = infinity;
  for (int slot = 0; slot < envelope.slot_count(); ++slot) {
    for (const DistanceCone& cone : envelope.cones(slot)) {
      const Index cell = cell_of(cone.apex);
      if (cell < 0) {
        others_.push_back({cone, envelope.site(slot)});
        continue;
      }
      ++cell_begin_[static_cast<std::size_t>(cell) + 1];
      double& least = cell_least_sigma_[static_cast<std::size_t>(cell)];
      least = std::min(least, cone.sigma);
      least_sigma_ = std::min(least_sigma_, cone.sigma);
    }
  }
  for (std::size_t c = 0; c < num_cells; ++c) cell_begin_[c + 1] += cell_begin_[c];
  entries_.resize(static_cast<std::size_t>(cell_begin_[num_cells]));
  fill_.assign(cell_begin_.begin(), cell_begin_.begin() + static_cast<std::ptrdiff_t>(num_cells));
  for (int slot = 0; slot < envelope.slot_count(); ++slot) {
    for (const DistanceCone& cone : envelope.cones(slot)) {
      const Index cell = cell_of(cone.apex);
      if (cell >= 0)
        entries_[static_cast<std::size_t>(fill_[static_cast<std::size_t>(cell)]++)] = {cone, envelope.site(slot)};
    }
  }
}

Index PlaneNearestSite::cell_of(const Eigen::Vector2d& apex) const {
  if (columns_ == 0) return -1;
  const double i = std::floor((apex.x() - origin_.x()) / cell_size_);
  const double j = std::floor((apex.y() - origin_.y()) / cell_size_);
  if (!(i >= 0 && i < columns_ && j >= 0 && j < rows_)) return -1;  // also for NaN
  return static_cast<Index>(j) * columns_ + static_cast<Index>(i);
}

Index PlaneNearestSite::nearest_site(const Eigen::Vector2d& p) const {
  NearestCone nearest{p};
  for (const SiteCone& c : others_) nearest.consider(c);
  if (entries_.empty()) return nearest.site;
  if (!p.allFinite()) {
    for (const SiteCone& c : entries_) nearest.consider(c);
    return nearest.site;
  }
  // A cone whose computed value is at most the least value found so far has
  // a computed bound below that plus the margin: the value, the bound and the
  // cells' corners are each within a few units in the last place of
  // scale_ + |p| of their exact figures.
  const double margin = 32 * std::numeric_limits<double>::epsilon() * (scale_ + std::abs(p.x()) + std::abs(p.y()));
  // p's cell, or the nearest one when p is off the grid: a cell r rings out
  // lies at least r - 1 cells from p.
  const int ci = static_cast<int>(
      std::clamp(std::floor((p.x() - origin_.x()) / cell_size_), 0.0, static_cast<double>(columns_ - 1)));
  const int cj =
      static_cast<int>(std::clamp(std::floor((p.y() - origin_.y()) / cell_size_), 0.0, static_cast<double>(rows_ - 1)));
  auto read_cell = [&](int i, int j) {
    const auto cell = static_cast<std::size_t>(j) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(i);
    if (cell_begin_[cell] == cell_begin_[cell + 1]) return;
    const double x0 = origin_.x() + i * cell_size_, y0 = origin_.y() + j * cell_size_;
    const double dx = std::max({x0 - p.x(), 0.0, p.x() - (x0 + cell_size_)});
    const double dy = std::max({y0 - p.y(), 0.0, p.y() - (y0 + cell_size_)});
    if (cell_least_sigma_[cell] + std::sqrt(dx * dx + dy * dy) - margin > nearest.value) return;
    for (Index e = cell_begin_[cell]; e < cell_begin_[cell + 1]; ++e)
      nearest.consider(entries_[static_cast<std::size_t>(e)]);
  };
  const int rings = std::max({ci, columns_ - 1 - ci, cj, rows_ - 1 - cj});
  for (int r = 0; r <= rings; ++r) {
    if (r > 0 && least_sigma_ + (r - 1) * cell_size_ - margin > nearest.value) break;
    const int i0 = ci - r, i1 = ci + r, j0 = cj - r, j1 = cj + r;
    for (int i = std::max(i0, 0); i <= std::min(i1, columns_ - 1); ++i) {
      if (j0 >= 0) read_cell(i, j0);
      if (r > 0 && j1 < rows_) read_cell(i, j1);
    }
    for (int j = std::max(j0 + 1, 0); j <= std::min(j1 - 1, rows_ - 1); ++j) {
      if (i0 >= 0) read_cell(i0, j);
      if (r > 0 && i1 < columns_) read_cell(i1, j);
    }
  }
  return nearest.site;
}

}  // namespace geodual::voronoi::detail
