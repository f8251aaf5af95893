#pragma once
// Internal: locating a glTF accessor's elements in its buffer, with every
// bound checked, and reading them as positions or vertex indices.
//
// Checked: the accessor's componentType, type, count (>= 1), byteOffset; its
// buffer view's buffer, byteOffset, byteLength, byteStride (4..252 and at
// least one element long); that the view lies inside the buffer and the
// accessor's last element inside the view. Not required: the spec's alignment
// rules (offsets that are multiples of the component size, strides that are
// multiples of 4), which matter to GPUs but not to reading with memcpy.
// Sparse accessors and accessors without a buffer view are refused.

#include "gltf_buffers.hpp"
#include "gltf_constants.hpp"
#include "gltf_json.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::io::detail::gltf {

struct AccessorView {
  std::span<const std::byte> bytes;  ///< from element 0's first byte to the last element's last byte
  std::size_t count = 0;
  std::size_t stride = 0;  ///< bytes from one element to the next
  ComponentType component_type = ComponentType::float_;
  bool normalized = false;
  std::string where;  ///< e.g. "scan.glb: mesh 0 primitive 1: POSITION accessor 4", for messages
};

enum class AccessorShape { scalar, vec3 };

/// Accessor `index`, which must have the given shape. `where` names the user,
/// e.g. "scan.glb: mesh 0 primitive 1: POSITION".
AccessorView view_accessor(const Json& root, BufferStore& buffers, std::size_t index, AccessorShape shape,
                           const std::string& where);

/// Appends count x 3 coordinates to `out`. FLOAT always; (unsigned) byte and
/// short, normalized or not, when `allow_quantized` (KHR_mesh_quantization).
void append_positions(const AccessorView& view, bool allow_quantized, std::vector<double>& out);

/// The values of an UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT scalar accessor.
std::vector<std::uint32_t> read_indices(const AccessorView& view);

}  // namespace geodual::io::detail::gltf
