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
//
// Positions and indices are read whole into vectors; vertex attributes are
// visited element by element (for_each_element), so that nothing but the
// output is held in memory.

#include "gltf_buffers.hpp"
#include "gltf_constants.hpp"
#include "gltf_json.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace geodual::io::detail::gltf {

struct AccessorView {
  std::span<const std::byte> bytes;  ///< from element 0's first byte to the last element's last byte
  std::size_t count = 0;
  std::size_t stride = 0;      ///< bytes from one element to the next
  std::size_t components = 3;  ///< numbers per element: 1 (SCALAR), 2, 3 or 4 (VEC2..VEC4)
  ComponentType component_type = ComponentType::float_;
  bool normalized = false;
  std::string where;  ///< e.g. "scan.glb: mesh 0 primitive 1: POSITION accessor 4", for messages
};

enum class AccessorShape { scalar, vec2, vec3, vec4 };

/// Accessor `index`, which must have one of the given shapes. `where` names the
/// user, e.g. "scan.glb: mesh 0 primitive 1: POSITION".
AccessorView view_accessor(const Json& root, BufferStore& buffers, std::size_t index,
                           std::initializer_list<AccessorShape> shapes, const std::string& where);
inline AccessorView view_accessor(const Json& root, BufferStore& buffers, std::size_t index, AccessorShape shape,
                                  const std::string& where) {
  return view_accessor(root, buffers, index, {shape}, where);
}

/// The accessor's "type" string ("SCALAR", "VEC3", ...), or an empty string
/// when the accessor or its type is missing (view_accessor reports those).
std::string accessor_type(const Json& root, std::size_t index);

/// The bytes of buffer view `index` (e.g. an image's), bounds checked.
std::span<const std::byte> buffer_view_bytes(const Json& root, BufferStore& buffers, std::size_t index,
                                             const std::string& where);

namespace element_detail {

template <class T>
T load(const std::byte* at) {
  T value;
  std::memcpy(&value, at, sizeof value);
  return value;
}

// Normalized integers map to [0, 1] (unsigned) or [-1, 1] (signed), as the spec defines.
template <class T>
double dequantize(T value, bool normalized) {
  const double v = static_cast<double>(value);
  if (!normalized) return v;
  if constexpr (std::is_signed_v<T>) {
    return std::max(v / static_cast<double>(std::numeric_limits<T>::max()), -1.0);
  } else {
    return v / static_cast<double>(std::numeric_limits<T>::max());
  }
}

template <class T, class F>
void visit(const AccessorView& view, F&& f) {
  double values[4] = {0, 0, 0, 0};
  const std::byte* src = view.bytes.data();
  for (std::size_t i = 0; i < view.count; ++i, src += view.stride) {
    for (std::size_t c = 0; c < view.components; ++c) {
      values[c] = dequantize(load<T>(src + c * sizeof(T)), view.normalized);
    }
    f(i, static_cast<const double*>(values));
  }
}

}  // namespace element_detail

/// Calls f(i, values) for every element i in order, `values` pointing to its
/// view.components numbers as doubles (normalized integers mapped to [0, 1]
/// or [-1, 1]).
template <class F>
void for_each_element(const AccessorView& view, F&& f) {
  switch (view.component_type) {
    case ComponentType::byte: element_detail::visit<std::int8_t>(view, f); break;
    case ComponentType::unsigned_byte: element_detail::visit<std::uint8_t>(view, f); break;
    case ComponentType::short_: element_detail::visit<std::int16_t>(view, f); break;
    case ComponentType::unsigned_short: element_detail::visit<std::uint16_t>(view, f); break;
    case ComponentType::unsigned_int: element_detail::visit<std::uint32_t>(view, f); break;
    case ComponentType::float_: element_detail::visit<float>(view, f); break;
  }
}

/// Appends count x 3 coordinates to `out`. FLOAT always; (unsigned) byte and
/// short, normalized or not, when `allow_quantized` (KHR_mesh_quantization).
void append_positions(const AccessorView& view, bool allow_quantized, std::vector<double>& out);

/// The values of an UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT scalar accessor.
std::vector<std::uint32_t> read_indices(const AccessorView& view);

}  // namespace geodual::io::detail::gltf
