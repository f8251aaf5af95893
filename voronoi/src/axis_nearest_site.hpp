#pragma once
// The nearest site along the x axis of a ConeEnvelope with many cones, in
// O(log n + k) per point instead of O(n): the same answers as
// ConeEnvelope::nearest_site, bit for bit. Finding where the nearest site
// changes along a mesh edge asks a few points per window on it, and an edge
// that long thin faces run along can hold thousands of windows.
//
// Exact by pruning, not by a different computation. At (x, 0) every cone's
// value sigma + |(x, 0) - apex| is at least sigma + |x - apex.x|. A wedge
// cone that opens sees an interval of the axis, in floating point too (each
// of its two ray tests is monotone in x), found once by a search over the
// doubles; a query evaluates the wedges whose interval holds x, and the
// cones without a wedge (they see everywhere) with the smallest bound on
// either side of x. The smallest value so far bounds the nearest from above:
// only cones whose bound is at most that (plus a rounding margin) can be the
// nearest, and min-trees over the cones sorted by apex.x list them. Each
// cone is evaluated as ConeEnvelope::nearest_site evaluates it (same value,
// same tie rule), so the answer is the same site.

#include "face_distance.hpp"

#include "geodual/mesh/triangle_mesh.hpp"

#include <span>
#include <vector>

namespace geodual::voronoi::detail {

/// Keys in a fixed order, listing those of a range at most a threshold in
/// O((k + 1) log n) for k listed.
class MinTree {
 public:
  /// Replaces the keys (keeps the storage).
  void assign(std::span<const double> keys);
  Index size() const { return size_; }
  /// Calls visit(i) for every i in [begin, end) whose key is at most `threshold`.
  template <typename Visit>
  void for_each_at_most(Index begin, Index end, double threshold, Visit&& visit) const {
    if (begin < end) visit_at_most(1, 0, leaves_, begin, end, threshold, visit);
  }

 private:
  template <typename Visit>
  void visit_at_most(Index node, Index node_begin, Index node_end, Index begin, Index end, double threshold,
                     Visit& visit) const {
    if (node_end <= begin || end <= node_begin || !(nodes_[node] <= threshold)) return;
    if (node >= leaves_) {
      visit(node - leaves_);
      return;
    }
    const Index middle = node_begin + (node_end - node_begin) / 2;
    visit_at_most(2 * node, node_begin, middle, begin, end, threshold, visit);
    visit_at_most(2 * node + 1, middle, node_end, begin, end, threshold, visit);
  }

  Index size_ = 0;
  Index leaves_ = 1;           ///< a power of two, at least size_
  std::vector<double> nodes_;  ///< heap order: node v's children are 2v and 2v + 1; leaves from leaves_
};

/// Answers ConeEnvelope::nearest_site at points (x, 0), |x| < 2^1000.
/// Building costs O(n log n) for n cones; worth it from a few dozen cones.
/// Keeps its storage between builds.
class AxisNearestSite {
 public:
  /// Indexes `envelope`'s cones (copied: the envelope may change afterwards).
  void build(const ConeEnvelope& envelope);
  /// envelope.nearest_site(Eigen::Vector2d(x, 0)) for the envelope last built from.
  Index nearest_site(double x) const;

 private:
  /// Cones that see every point (no wedge), sorted by apex.x, with their
  /// bounds' constant parts: sigma - apex.x left of x, sigma + apex.x right of it.
  std::vector<SiteCone> points_;
  std::vector<double> point_x_;
  MinTree left_keys_, right_keys_;
  /// Per i: a point of smallest left key among [0, i], of smallest right key among [i, n).
  std::vector<Index> best_left_upto_, best_right_from_;
  /// Opening wedges that see some of the axis, sorted by the start of that
  /// interval; the tree holds minus its end (a wedge holds x when lo <= x and -hi <= -x).
  std::vector<SiteCone> wedges_;
  std::vector<double> wedge_lo_;
  MinTree wedge_minus_hi_;
  /// Everything else (wedges that do not open), and every cone when the
  /// coordinates are too large for the bounds: evaluated at every query.
  std::vector<SiteCone> others_;
  /// max |sigma| + |apex.x| + |apex.y|: the scale of the rounding margin.
  double scale_ = 0;
  struct Wedge {
    double lo = 0, hi = 0;  ///< the interval of the axis it sees
    SiteCone entry;
  };
  std::vector<Wedge> wedge_scratch_;
  std::vector<double> keys_;  ///< scratch
};

}  // namespace geodual::voronoi::detail
