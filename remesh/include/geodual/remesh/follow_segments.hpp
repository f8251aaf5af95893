#pragma once
// Edge flips that make a remesh follow given segments (pairs of its vertices,
// such as the pins on a short crease, crease_pins.hpp): the edges a segment
// crosses are flipped one after the other until it is an edge, unless a
// flip would fold a triangle against the ones it replaces or the new
// triangles have a smaller angle than both the old ones and a bound.
//
//   auto followed = follow_segments(remesh.mesh, segments);

#include "geodual/mesh/triangle_mesh.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace geodual::remesh {

struct FollowedSegments {
  std::int64_t segments = 0;  ///< segments given
  std::int64_t edges = 0;     ///< of those, edges of the mesh afterwards
  std::int64_t flipped = 0;   ///< edges flipped to make them so
};

struct FollowSegmentsOptions {
  /// A flip may make an angle smaller than this (degrees) only where the
  /// triangles it replaces had one smaller still.
  double min_angle_degrees = 25;
  /// At most this many flips per segment.
  int max_flips = 3;
};

/// Flips edges of `mesh` (oriented, manifold) onto `segments`; the vertices
/// and their count stay, the faces keep their count and orientation.
/// Deterministic: segments are taken in order.
FollowedSegments follow_segments(TriangleMesh& mesh, std::span<const std::array<Index, 2>> segments,
                                 const FollowSegmentsOptions& options = {});

/// follow_segments on pairs of pins (ShortCreasePins::segments) by their
/// vertices in `mesh` (pin_vertices): those with both vertices there.
FollowedSegments follow_pin_segments(TriangleMesh& mesh, std::span<const Index> pin_vertex,
                                     std::span<const std::array<std::size_t, 2>> segments,
                                     const FollowSegmentsOptions& options = {});

}  // namespace geodual::remesh
