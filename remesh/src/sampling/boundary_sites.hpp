#pragma once
// Sites along a surface's boundary loops, for sample_sites: evenly by arc
// length, except that the end of a slit gets a site of its own.
//
// A slit is a stretch where a loop runs out and back along itself, its two
// sides at the same points (a cut in a scan, two edges of a sheet glued
// back to back and cut apart). Evenly spaced sites land there in mirrored
// pairs at one point; the pair next to the slit's end shares a triangle
// round it, of zero area (ogre at 2000 sites: Q 9e-7). A site at the end
// keeps the two sides apart there.

#include "sampling/sampling_surface.hpp"

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <vector>

namespace geodual::remesh::detail {

/// Points of a boundary loop by arc length, walking its edges in order and
/// in the direction the walk runs them. Arc lengths are taken modulo the
/// length on a closed loop and clamped to [0, length] on an open chain.
class LoopWalk {
 public:
  LoopWalk(const TriangleMesh& mesh, const BoundaryLoop& loop);

  double length() const { return loop_.length; }
  bool closed() const { return loop_.closed; }
  std::size_t num_edges() const { return start_.size(); }
  /// Arc length where the walk enters edge i.
  double start(std::size_t i) const { return start_[i]; }

  Eigen::Vector3d point(double at) const;
  /// The point at `at` as a site on the edge's face (point_on_face_edge: kept
  /// 2^-20 of the edge off its ends).
  SurfacePoint site(double at) const;

 private:
  /// The edge `at` lies on (after the rule above), and the fraction of it walked.
  std::size_t locate(double at, double& fraction) const;

  const TriangleMesh& mesh_;
  const BoundaryLoop& loop_;
  std::vector<double> start_;
};

/// The slit ends of boundary loops (one walk each), for a remesh of edge
/// length `spacing`: per loop, the edges the walk enters at a slit's end, in
/// walking order, at most limits[l] on walks[l], none on an open chain. At the point v where
/// the walk enters an edge, take the loop's points r before and after it
/// (r = spacing / 2, at most a sixth of the loop): v ends a slit when the
/// chords to them leave v within 20 degrees of each other and the two
/// points are within r / 4 of each other, i.e. the sides run together for at
/// least r. (Shallower slits, a few edges deep, are left to the even
/// placement: sites at their ends left bunny_res2's cut with no valid dual.)
/// Ends are taken sharpest first over all the loops, each at least 2 r in
/// space from every end taken before it, on its loop or another.
std::vector<std::vector<std::size_t>> slit_ends(std::span<const LoopWalk> walks, double spacing,
                                                std::span<const std::int64_t> limits);

/// The corners of boundary loops (one walk each) that get a site of their
/// own, for a remesh of edge length `spacing`: per loop, the edges the walk
/// enters at a corner, in walking order, at most limits[l] less the slit ends
/// `taken` on walks[l]. At the point v where the walk enters an edge, with r
/// as for slit_ends: v is a corner when the loop runs straight for r on
/// either side (its vertices within r / 20 of the chord from v) and the two
/// chords meet at 135 degrees or less, a turn of 45 or more. A machined
/// part's outline has such corners; a scan's ragged hole, or a loop that
/// bends smoothly, does not. Only on closed loops of 4 spacings or longer;
/// taken sharpest first, each at least 2 r in space from every corner and
/// slit end taken before it.
std::vector<std::vector<std::size_t>> loop_corners(std::span<const LoopWalk> walks, double spacing,
                                                   std::span<const std::int64_t> limits,
                                                   const std::vector<std::vector<std::size_t>>& taken);

/// Sites on the loops of one component: sites[l] of them on loops[l] (at
/// least 3 each), for a remesh of edge length `spacing`, appended to `out`
/// loop by loop. One at each slit end (slit_ends) and corner (loop_corners),
/// just off its vertex, the others evenly by arc length between consecutive
/// ones, in proportion to the stretches' lengths; on a loop without any evenly all round, at
/// (j + 1/2) L / k. A closed loop smaller than the spacing whose sites would
/// come closer in space than a quarter of their spacing along it (it runs
/// back over itself, as copies of one short edge the cut to a manifold
/// opened) takes them at its vertices and edge midpoints instead, farthest
/// first, where that keeps its closest two farther apart.
void place_boundary_sites(const TriangleMesh& mesh, std::span<const BoundaryLoop* const> loops,
                          std::span<const std::int64_t> sites, double spacing, std::vector<SurfacePoint>& out);

}  // namespace geodual::remesh::detail
