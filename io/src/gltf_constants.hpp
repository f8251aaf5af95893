#pragma once
// Internal: the numeric codes of the glTF 2.0 specification and the GLB
// container that geodual reads and writes.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace geodual::io::detail::gltf {

/// accessor.componentType (the OpenGL type enums). 5124 (INT) is not allowed in glTF 2.0.
enum class ComponentType : std::uint32_t {
  byte = 5120,
  unsigned_byte = 5121,
  short_ = 5122,
  unsigned_short = 5123,
  unsigned_int = 5125,
  float_ = 5126,
};

/// The ComponentType a JSON value names, or nullopt when it names none.
constexpr std::optional<ComponentType> component_type_from_code(std::uint64_t code) {
  switch (code) {
    case 5120: return ComponentType::byte;
    case 5121: return ComponentType::unsigned_byte;
    case 5122: return ComponentType::short_;
    case 5123: return ComponentType::unsigned_short;
    case 5125: return ComponentType::unsigned_int;
    case 5126: return ComponentType::float_;
    default: return std::nullopt;
  }
}

constexpr std::size_t component_size(ComponentType type) {
  switch (type) {
    case ComponentType::byte:
    case ComponentType::unsigned_byte: return 1;
    case ComponentType::short_:
    case ComponentType::unsigned_short: return 2;
    case ComponentType::unsigned_int:
    case ComponentType::float_: return 4;
  }
  return 0;
}

constexpr std::string_view component_type_name(ComponentType type) {
  switch (type) {
    case ComponentType::byte: return "BYTE";
    case ComponentType::unsigned_byte: return "UNSIGNED_BYTE";
    case ComponentType::short_: return "SHORT";
    case ComponentType::unsigned_short: return "UNSIGNED_SHORT";
    case ComponentType::unsigned_int: return "UNSIGNED_INT";
    case ComponentType::float_: return "FLOAT";
  }
  return "?";
}

/// mesh.primitive.mode
enum class PrimitiveMode : std::uint32_t {
  points = 0,
  lines = 1,
  line_loop = 2,
  line_strip = 3,
  triangles = 4,
  triangle_strip = 5,
  triangle_fan = 6,
};

/// The GLB container: a 12-byte header, then chunks of (length, type, data).
inline constexpr std::uint32_t glb_magic = 0x46546C67;  // "glTF"
inline constexpr std::uint32_t glb_version = 2;
inline constexpr std::uint32_t glb_chunk_json = 0x4E4F534A;  // "JSON"
inline constexpr std::uint32_t glb_chunk_bin = 0x004E4942;   // "BIN\0"
inline constexpr std::size_t glb_header_size = 12;
inline constexpr std::size_t glb_chunk_header_size = 8;

}  // namespace geodual::io::detail::gltf
