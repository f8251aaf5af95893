#include "gltf_accessor.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

namespace geodual::io::detail::gltf {
namespace {

constexpr std::uint64_t min_byte_stride = 4;
constexpr std::uint64_t max_byte_stride = 252;

using element_detail::dequantize;
using element_detail::load;

std::string_view shape_name(AccessorShape shape) {
  switch (shape) {
    case AccessorShape::scalar: return "SCALAR";
    case AccessorShape::vec2: return "VEC2";
    case AccessorShape::vec3: return "VEC3";
    case AccessorShape::vec4: return "VEC4";
  }
  return "?";
}

std::size_t shape_components(AccessorShape shape) {
  switch (shape) {
    case AccessorShape::scalar: return 1;
    case AccessorShape::vec2: return 2;
    case AccessorShape::vec3: return 3;
    case AccessorShape::vec4: return 4;
  }
  return 0;
}

struct CheckedView {
  const Json* json = nullptr;
  std::string where;
  std::size_t buffer = 0;
  std::uint64_t offset = 0;
  std::uint64_t length = 0;
};

// Buffer view `index`: its buffer, byteOffset and byteLength, checked to lie inside the buffer.
CheckedView check_buffer_view(const Json& root, BufferStore& buffers, std::size_t index, const std::string& where) {
  const Json& views = array_member(root, "bufferViews", where);
  CheckedView result;
  result.json = &views[index];
  result.where = where + ": " + describe("bufferView", index, *result.json);
  const Json& view = *result.json;
  if (!view.is_object()) fail(result.where, "must be a JSON object");
  result.buffer = required_index(view, "buffer", buffers.size(), "buffer", result.where);
  result.offset = optional_uint(view, "byteOffset", result.where).value_or(0);
  result.length = required_uint(view, "byteLength", result.where);
  if (result.length == 0) fail(result.where, "'byteLength' must be at least 1");
  const std::span<const std::byte> buffer = buffers.bytes(result.buffer);
  if (result.offset > buffer.size() || result.length > buffer.size() - result.offset) {
    fail(result.where, "bytes " + std::to_string(result.offset) + ".." + std::to_string(result.offset + result.length) +
                           " run past the end of buffer " + std::to_string(result.buffer) + " (" +
                           std::to_string(buffer.size()) + " bytes)");
  }
  return result;
}

template <class T>
void append_vec3(const AccessorView& view, std::vector<double>& out) {
  const std::size_t first = out.size();
  out.resize(first + 3 * view.count);
  double* dst = out.data() + first;
  const std::byte* src = view.bytes.data();
  for (std::size_t i = 0; i < view.count; ++i, src += view.stride, dst += 3) {
    for (std::size_t c = 0; c < 3; ++c) {
      dst[c] = dequantize(load<T>(src + c * sizeof(T)), view.normalized);
    }
  }
}

template <class T>
std::vector<std::uint32_t> load_scalars(const AccessorView& view) {
  std::vector<std::uint32_t> values(view.count);
  const std::byte* src = view.bytes.data();
  for (std::size_t i = 0; i < view.count; ++i, src += view.stride) values[i] = load<T>(src);
  return values;
}

}  // namespace

AccessorView view_accessor(const Json& root, BufferStore& buffers, std::size_t index,
                           std::initializer_list<AccessorShape> shapes, const std::string& user) {
  const Json& accessors = array_member(root, "accessors", user);
  if (index >= accessors.size()) {
    fail(user,
         "refers to accessor " + std::to_string(index) + ", but the file has " + std::to_string(accessors.size()));
  }
  const Json& accessor = accessors[index];
  const std::string where = user + " " + describe("accessor", index, accessor);
  if (!accessor.is_object()) fail(where, "must be a JSON object");
  if (find_member(accessor, "sparse") != nullptr) {
    fail(where, "sparse accessors are not supported for geometry");
  }

  const std::uint64_t type_code = required_uint(accessor, "componentType", where);
  const std::optional<ComponentType> component_type = component_type_from_code(type_code);
  if (!component_type) fail(where, "invalid componentType " + std::to_string(type_code));

  const std::optional<std::string> type = optional_string(accessor, "type", where);
  if (!type) fail(where, "required 'type' is missing");
  const auto shape =
      std::find_if(shapes.begin(), shapes.end(), [&](AccessorShape s) { return shape_name(s) == *type; });
  if (shape == shapes.end()) {
    std::string expected;
    for (const AccessorShape s : shapes) expected += (expected.empty() ? "" : " or ") + std::string(shape_name(s));
    fail(where, "has type '" + type->substr(0, 16) + "', expected " + expected);
  }
  const std::size_t components = shape_components(*shape);

  const std::uint64_t count = required_uint(accessor, "count", where);
  if (count == 0) fail(where, "'count' must be at least 1");
  const bool normalized = optional_bool(accessor, "normalized", false, where);
  const std::uint64_t accessor_offset = optional_uint(accessor, "byteOffset", where).value_or(0);

  const Json& views = array_member(root, "bufferViews", where);
  const std::optional<std::size_t> view_index =
      optional_index(accessor, "bufferView", views.size(), "bufferView", where);
  if (!view_index) fail(where, "has no bufferView (an all-zero accessor); not supported for geometry");
  const CheckedView view = check_buffer_view(root, buffers, *view_index, where);
  const std::string& view_where = view.where;

  const std::uint64_t element_size = component_size(*component_type) * components;
  const std::optional<std::uint64_t> declared_stride = optional_uint(*view.json, "byteStride", view_where);
  if (declared_stride) {
    if (*declared_stride < min_byte_stride || *declared_stride > max_byte_stride) {
      fail(view_where, "'byteStride' " + std::to_string(*declared_stride) + " is outside 4..252");
    }
    if (*declared_stride < element_size) {
      fail(view_where, "'byteStride' " + std::to_string(*declared_stride) +
                           " is shorter than one element of accessor " + std::to_string(index) + " (" +
                           std::to_string(element_size) + " bytes)");
    }
  }
  const std::uint64_t stride = declared_stride.value_or(element_size);
  const std::uint64_t view_offset = view.offset;
  const std::uint64_t view_length = view.length;
  const std::span<const std::byte> buffer = buffers.bytes(view.buffer);
  // All terms are below 2^53 and stride <= 252, so none of this overflows.
  const std::uint64_t accessor_bytes = (count - 1) * stride + element_size;
  if (accessor_offset > view_length || accessor_bytes > view_length - accessor_offset) {
    fail(where, std::to_string(count) + " elements from byteOffset " + std::to_string(accessor_offset) + " need " +
                    std::to_string(accessor_offset + accessor_bytes) + " bytes, but bufferView " +
                    std::to_string(*view_index) + " has " + std::to_string(view_length));
  }

  AccessorView result;
  result.bytes =
      buffer.subspan(static_cast<std::size_t>(view_offset + accessor_offset), static_cast<std::size_t>(accessor_bytes));
  result.count = static_cast<std::size_t>(count);
  result.stride = static_cast<std::size_t>(stride);
  result.components = components;
  result.component_type = *component_type;
  result.normalized = normalized;
  result.where = where;
  return result;
}

std::string accessor_type(const Json& root, std::size_t index) {
  const Json* accessors = find_member(root, "accessors");
  if (accessors == nullptr || !accessors->is_array() || index >= accessors->size()) return {};
  const Json* type = find_member((*accessors)[index], "type");
  return type != nullptr && type->is_string() ? type->get<std::string>() : std::string();
}

std::span<const std::byte> buffer_view_bytes(const Json& root, BufferStore& buffers, std::size_t index,
                                             const std::string& where) {
  const std::size_t count = array_member(root, "bufferViews", where).size();
  if (index >= count) {
    fail(where, "refers to bufferView " + std::to_string(index) + ", but the file has " + std::to_string(count));
  }
  const CheckedView view = check_buffer_view(root, buffers, index, where);
  return buffers.bytes(view.buffer)
      .subspan(static_cast<std::size_t>(view.offset), static_cast<std::size_t>(view.length));
}

void append_positions(const AccessorView& view, bool allow_quantized, std::vector<double>& out) {
  const std::string& where = view.where;
  if (view.component_type == ComponentType::float_) {
    if (view.normalized) fail(where, "a FLOAT accessor cannot be normalized");
    append_vec3<float>(view, out);
    return;
  }
  if (!allow_quantized || view.component_type == ComponentType::unsigned_int) {
    fail(where, "POSITION has componentType " + std::string(component_type_name(view.component_type)) +
                    "; glTF requires FLOAT (integer positions need the KHR_mesh_quantization extension)");
  }
  switch (view.component_type) {
    case ComponentType::byte: append_vec3<std::int8_t>(view, out); break;
    case ComponentType::unsigned_byte: append_vec3<std::uint8_t>(view, out); break;
    case ComponentType::short_: append_vec3<std::int16_t>(view, out); break;
    case ComponentType::unsigned_short: append_vec3<std::uint16_t>(view, out); break;
    case ComponentType::unsigned_int:
    case ComponentType::float_: break;  // handled above
  }
}

std::vector<std::uint32_t> read_indices(const AccessorView& view) {
  const std::string& where = view.where;
  if (view.normalized) fail(where, "an index accessor cannot be normalized");
  switch (view.component_type) {
    case ComponentType::unsigned_byte: return load_scalars<std::uint8_t>(view);
    case ComponentType::unsigned_short: return load_scalars<std::uint16_t>(view);
    case ComponentType::unsigned_int: return load_scalars<std::uint32_t>(view);
    default:
      fail(where, "indices have componentType " + std::string(component_type_name(view.component_type)) +
                      "; expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  }
}

}  // namespace geodual::io::detail::gltf
