#pragma once
// The pieces of parallel window-VTP (docs/algorithms.md, "Parallel
// propagation"): the sites split into groups that propagate apart, an upper
// bound U of the distance to the nearest site that stops each group where it
// cannot be nearest, and a test that keeps a group from freeing windows where
// another group's site may still be nearer.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "propagation_mesh.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <span>
#include <vector>

namespace geodual::voronoi::detail {

/// How many groups `num_sites` sites propagate in: `requested` where > 0
/// (at most one per site), otherwise one per 256 sites, 2 to 16 (1 for a
/// single site). A function
/// of the input alone, never of the thread count, so that the result is.
int site_group_count(std::size_t num_sites, int requested);

/// Per site its group in [0, groups): the sites sorted along a Morton curve
/// through their positions (ties by index) and cut into runs of equal size,
/// so that each group is a compact patch of the surface.
std::vector<int> partition_sites(std::span<const Eigen::Vector3d> positions, int groups);

/// Per vertex of the propagation mesh, an upper bound of the geodesic distance
/// to the nearest site: the shortest path (Dijkstra) along edges and along
/// straight lines across an edge between the far corners of its two faces,
/// a face site reaching its face's corners in straight lines, with a relative margin of
/// 1e-9 (and 1e-12 of the longest edge) for rounding; +inf where no site
/// reaches. Every path it measures lies on the surface, so it is >= d(v).
std::vector<double> surface_path_upper_bound(const PropagationMesh& pm, std::span<const SurfacePoint> local_sites);

/// A kd-tree over the sites' positions and groups. Answers whether a site of
/// another group lies within a Euclidean distance of a point; the Euclidean
/// distance is a lower bound of the geodesic one.
class SiteTree {
 public:
  SiteTree(std::span<const Eigen::Vector3d> positions, std::span<const int> groups);
  /// True if some site not in `group` is at distance <= radius from p.
  bool other_group_within(const Eigen::Vector3d& p, double radius, int group) const;

 private:
  static constexpr int kLeafSize = 8;
  void build(int lo, int hi);

  std::vector<Eigen::Vector3d> points_;  ///< in tree order
  std::vector<int> group_;
  std::vector<std::uint8_t> axis_;  ///< per node (its middle point): the splitting axis
};

}  // namespace geodual::voronoi::detail
