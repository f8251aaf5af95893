#pragma once
// Internal: a triangle mesh for KHR_draco_mesh_compression
// (GltfCompression::draco) through Debian's libdraco (draco::Encoder,
// edgebreaker). Plain data out; the model builder makes the glTF of it.

#include "gltf_triangle_streams.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace geodual::io::detail::gltf {

struct DracoPrimitive {
  std::vector<std::byte> encoded{};  ///< the Draco bitstream
  /// Attribute names as written ("POSITION", "NORMAL", "COLOR_0", "_NAME"), each
  /// with its Draco attribute's unique id, in the order written.
  std::vector<std::pair<std::string, std::uint32_t>> attribute_ids{};
  /// What a decoder gives back, for the accessors: Draco may reorder, drop
  /// unused or split vertices.
  std::size_t decoded_vertices = 0;
  std::size_t decoded_indices = 0;
  std::vector<double> position_min{}, position_max{};  ///< of the decoded positions
};

/// Positions quantised to 14 bits over the largest bounding-box side, normals to
/// 10 bits, colours to 16; scalars kept exact. Decodes the result once to
/// fill in the decoded figures; throws geodual::Error("<where>: ...") if
/// Draco fails. Same input, same bytes.
DracoPrimitive encode_draco(const TriangleStreams& mesh, const std::string& where);

/// The quantisation bits used for positions (the decode test's tolerance).
inline constexpr int draco_position_bits = 14;

}  // namespace geodual::io::detail::gltf
