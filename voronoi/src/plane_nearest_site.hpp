#pragma once
// The nearest site at points of a face of a ConeEnvelope with many cones,
// in about O(1) per point instead of O(n): the same answers as
// ConeEnvelope::nearest_site, bit for bit. A face that holds many sites
// (a coarse input remeshed finely: hundreds of sites in one triangle) is
// traced with thousands of such queries, each over all its cones.
//
// Exact by pruning, not by a different computation. Every cone's value
// sigma + |p - apex| is at least sigma + the distance from p to any box
// holding its apex. The cones are bucketed by apex in a grid of square cells
// over the face (and as far again round it); the cells are read in rings
// round p's, each cell only while its bound (the least sigma in it plus its
// distance from p) is at most the smallest value found so far plus a
// rounding margin, and the rings stop once even the least sigma at their
// distance exceeds it. Cones with their apex off the grid are evaluated at
// every query. Each cone is evaluated as ConeEnvelope::nearest_site
// evaluates it (same value, same tie rule), so the answer is the same site.

#include "face_distance.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace geodual::voronoi::detail {

class PlaneNearestSite {
 public:
  /// Indexes `envelope`'s cones (copied: the envelope may change
  /// afterwards) for queries in and near the polygon `region` (a face's corners).
  void build(const ConeEnvelope& envelope, std::span<const Eigen::Vector2d> region);
  /// envelope.nearest_site(p) for the envelope last built from.
  Index nearest_site(const Eigen::Vector2d& p) const;

 private:
  /// The grid's cones, cell by cell: cell c's are entries_[cell_begin_[c] .. cell_begin_[c + 1]).
  std::vector<SiteCone> entries_;
  std::vector<Index> cell_begin_;
  std::vector<double> cell_least_sigma_;
  double least_sigma_ = 0;  ///< over the grid's cones
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_size_ = 0;
  int columns_ = 0, rows_ = 0;
  /// Cones off the grid, and every cone when the coordinates are too large
  /// for the bounds: evaluated at every query.
  std::vector<SiteCone> others_;
  /// max |sigma| + |apex.x| + |apex.y|: the scale of the rounding margin.
  double scale_ = 0;
  std::vector<Index> fill_;  ///< scratch: per cell, where its next cone goes

  /// The cell holding an apex, or -1 off the grid (or with no grid).
  Index cell_of(const Eigen::Vector2d& apex) const;
};

}  // namespace geodual::voronoi::detail
