#pragma once
// The corners of a surface's boundary loops at the scale of a remesh: where
// sample_sites puts a boundary site of its own, so that the remesh keeps a
// square's corners and no triangle spans the end of a slit (where the loop
// turns back on itself, its two sides at the same points).

#include "sampling_surface.hpp"

#include "geodual/triangle_mesh.hpp"
#include "geodual/voronoi/surface_point.hpp"

#include <Eigen/Core>

#include <cstdint>
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
  /// Distance along the loop between two arc lengths in [0, length] (the
  /// shorter way round on a closed loop).
  double gap(double a, double b) const;

  Eigen::Vector3d point(double at) const;
  /// The point at `at` as a site on the edge's face (point_on_face_edge: kept
  /// 2^-20 of the edge off its ends).
  SurfacePoint site(double at) const;

 private:
  /// `at` brought into [0, length], and the edge it lies on with the
  /// fraction of it walked.
  std::size_t locate(double at, double& fraction) const;

  const TriangleMesh& mesh_;
  const BoundaryLoop& loop_;
  std::vector<double> start_;
};

/// cos 100°: a corner turns the boundary by more than 80 degrees over about
/// a spacing.
inline constexpr double kCornerCosine = -0.17364817766693033;

/// The corners of a closed loop at the scale of a remesh of edge length
/// `spacing`, as edges (entered at the corner) in walking order, at most
/// `limit`; none for an open chain. At the point v where the walk enters an
/// edge, the chords from v to the loop's points r before and after it
/// (r = spacing / 2, at most a sixth of the loop) make an angle: about 180
/// degrees where the boundary runs straight or bends gently at that scale,
/// 90 at a square's corner, about 0 at the end of a slit. Corners are the
/// edges where it is below 100 degrees (cosine above kCornerCosine), the
/// sharpest first, each at least 2 r along the loop from a sharper one (two
/// corner sites closer than a spacing would make a short edge). Cosines, not
/// angles, are compared: they take only correctly rounded operations, so the
/// corners do not depend on the maths library.
std::vector<std::size_t> loop_corners(const LoopWalk& walk, double spacing, std::int64_t limit);

}  // namespace geodual::remesh::detail
