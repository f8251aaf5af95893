#pragma once
// Internal: a triangle mesh for EXT_meshopt_compression with
// KHR_mesh_quantization (GltfCompression::meshopt): the triangles reordered
// for the vertex cache, the vertices for fetch (meshoptimizer 0.18), the
// attributes quantised, then each stream encoded with meshopt's vertex or
// index codec. Plain data out; the model builder makes the glTF of it.

#include "gltf_constants.hpp"
#include "gltf_triangle_streams.hpp"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace geodual::io::detail::gltf {

/// One accessor's data, meshopt-encoded.
struct MeshoptStream {
  std::string
      attribute{};  ///< "POSITION", "NORMAL", "COLOR_0", "TEXCOORD_0", "TANGENT", "_NAME"; empty for the indices
  std::vector<std::byte> encoded{};
  std::size_t count = 0;        ///< vertices, or indices
  std::size_t byte_stride = 0;  ///< decoded bytes per element: a multiple of 4 for vertices, 2 or 4 for indices
  ComponentType component_type = ComponentType::float_;
  int components = 1;  ///< 1 (SCALAR), 2 (VEC2), 3 (VEC3) or 4 (VEC4)
  bool normalized = false;
  std::vector<double> min{}, max{};  ///< POSITION only: the integer grid's bounds
  /// EXT_meshopt_compression's filter that a decoder applies after the codec: "NONE" or
  /// "OCTAHEDRAL" (NORMAL: 8-bit octahedral x, y, decoded to normalised int8 x, y, z and a zero;
  /// TANGENT: the same with w kept).
  std::string filter = "NONE";
};

struct MeshoptPrimitive {
  std::vector<MeshoptStream> streams{};  ///< the vertex attributes, then the indices
  /// The node's transform: position = translation + scale * (integer position).
  std::array<double, 3> translation{};
  double scale = 1;
};

/// Positions go on a grid of 2^14 - 1 steps over the largest side of their
/// bounding box, from its low corner (each coordinate off by at most half a
/// step, plus float rounding), stored as uint16. Same input, same bytes.
MeshoptPrimitive encode_meshopt(const TriangleStreams& mesh);

/// The grid's bits (gltfpack's default): a step is 1/16383 of the largest side.
inline constexpr int meshopt_position_bits = 14;

}  // namespace geodual::io::detail::gltf
