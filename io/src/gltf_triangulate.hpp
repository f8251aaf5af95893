#pragma once
// Internal: triangle corners of a glTF TRIANGLES, TRIANGLE_STRIP or
// TRIANGLE_FAN primitive, following the spec's definitions of strips
// (triangle i = v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]) and fans
// (triangle i = v[i + 1], v[i + 2], v[0]).

#include "gltf_constants.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace geodual::io::detail::gltf {

struct Triangulation {
  std::vector<std::uint32_t> corners;  ///< three per triangle
  /// Strips and fans: triangles with a repeated vertex, dropped. Encoders put
  /// them there on purpose to join strips; they are not part of the surface.
  std::size_t degenerate_dropped = 0;
  /// TRIANGLES: the 1 or 2 vertices after the last whole triangle, ignored (as GPUs do).
  std::size_t trailing_ignored = 0;
};

/// `vertices` are the primitive's vertex indices in drawing order; `mode` is
/// one of the three triangle modes.
Triangulation triangulate(PrimitiveMode mode, std::vector<std::uint32_t> vertices);

}  // namespace geodual::io::detail::gltf
